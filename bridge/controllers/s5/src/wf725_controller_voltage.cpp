// SPDX-License-Identifier: MIT
// WF 725/726 voltage checks (manual §6.2.1 errors 40-46, MD 41 S; docs/wf725.md "Voltage checks"):
// the module's ADC checks its supplies and reads every command value back. In the simulation the
// faults are inputs of the image (input byte 3, our model): a scenario's `io:` steps or the
// emulator's console inject them. Also the listing of data codes 47/4A.
#include <fmt/format.h>

#include <cmath>

#include "hil/controllers/s5/wf725_controller.hpp"

namespace hil::controllers::s5 {
namespace {

constexpr std::int64_t mask_voltage = 2;  // MD 41 S: voltage check masked

struct Check {
  std::uint8_t bit;
  int code;
  const char* what;
};
constexpr Check checks[] = {
    {0, 0x40, "the ADC (or the +-15 V analog section) is defective"},
    {1, 0x41, "+-15 V not within tolerance"},
    {2, 0x42, "+15 V not within tolerance"},
    {3, 0x43, "-15 V not within tolerance"},
    {4, 0x44, "5 V below its limit: fuse F2 blown"},
    {5, 0x45, "24 V below its limit: fuse F1 blown"},
};
constexpr std::uint8_t in_dac_short = 6;

}  // namespace

double Wf725Controller::command_mv() const noexcept {
  if (open_loop()) return wf725_level_mv(ol_.level);
  const double md3 = static_cast<double>(md_.get(3));  // mm/min at MD 23
  if (md3 <= 0.0) return 0.0;
  return std::abs(axis(0).status().command_velocity) * 60.0 / md3 * static_cast<double>(md_.get(23));
}

void Wf725Controller::voltage_cycle(TimePoint now) {
  if ((md_.integer(41) & mask_voltage) != 0) return;
  const auto in = [&](std::uint8_t b) { return io().get(BitAddress{IoArea::input, 3, b}); };
  for (const auto& c : checks)
    if (in(c.bit) && !has_error(c.code)) raise_wf(c.code, now, c.what);
  // 46: the command value is above 1 V but the readback at the DAC output is 0 V.
  const double mv = command_mv();
  if (in(in_dac_short) && mv > 1000.0 && !has_error(0x46))
    raise_wf(0x46, now, fmt::format("command value {:.0f} mV, 0 V measured at the DAC output", mv));
}

void Wf725Controller::write_list(const std::vector<int>& numbers, int page) {
  const std::size_t first = static_cast<std::size_t>(page - 1) * wf_db::list_page;
  std::uint16_t count = 0;
  for (std::uint16_t i = 0; i < wf_db::list_page; ++i) {
    const std::size_t k = first + i;
    const bool has = k < numbers.size();
    db_.write_word(static_cast<std::uint16_t>(wf_db::dw_list + 1 + i),
                   has ? static_cast<std::uint16_t>(numbers[k]) : std::uint16_t{0});
    count = static_cast<std::uint16_t>(count + (has ? 1 : 0));
  }
  db_.write_word(wf_db::dw_list, count);
}

}  // namespace hil::controllers::s5
