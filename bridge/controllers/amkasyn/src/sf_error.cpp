// SPDX-License-Identifier: MIT
// SF error category, the FB 207 init DB decoder and the FastFunction defaults.
#include <bit>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/fast_function.hpp"
#include "hil/controllers/amkasyn/init_db.hpp"
#include "hil/controllers/amkasyn/sf_error.hpp"

namespace hil::controllers::amkasyn {
namespace {

class SfCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "amkasyn-sf"; }
  std::string message(int v) const override {
    switch (static_cast<SfError>(v)) {
      case SfError::none:
        return "no error";
      case SfError::start_invalid:
        return "START with invalid or out-of-range parameters";
      case SfError::start_while_active:
        return "START while SF-ACTIVE";
      case SfError::value_new_not_active:
        return "VALUE NEW outside SF-ACTIVE";
      case SfError::xfipw_not_reset:
        return "XFIPW: START or READ VALUE not in Reset";
      case SfError::xfipw_not_started:
        return "XFIPW: VALUE NEW not started";
      case SfError::apsf_runtime:
        return "APSF running time error";
    }
    return fmt::format("unknown SF error {}", v);
  }
};

bool one_bit_or_zero(std::uint8_t m) {
  return m == 0 || std::has_single_bit(static_cast<unsigned>(m));
}

}  // namespace

const std::error_category& sf_category() noexcept {
  static const SfCategory c;
  return c;
}

const char* to_string(SfType t) noexcept {
  static constexpr const char* names[] = {"COPY", "FIPW",  "FIPZ",  "STDFKT", "DFKT", "FGEN", "REGL",
                                          "IMES", "BINEA", "XFIPW", "APSF",   "EPOS", "CAM"};
  const auto i = static_cast<std::size_t>(t);
  return i < 13 ? names[i] : "?";
}

std::expected<InitDb, SfFault> InitDb::parse(const DataBlock& db) {
  auto bad = [](std::string t) { return std::unexpected(SfFault{SfError::start_invalid, "FB 207 init DB: " + t}); };
  InitDb i;
  if (db.dr(0) > 12) return bad(fmt::format("DR0 SF type = {}: must be 0..12", db.dr(0)));
  i.type = static_cast<SfType>(db.dr(0));
  i.number = db.dl(0);
  if (i.number >= max_sf) return bad(fmt::format("DL0 SF number = {}: must be 0..15", i.number));
  if (db.dr(1) > 3) return bad(fmt::format("DR1 E/A-M mode = {}: must be 0..3", db.dr(1)));
  i.inputs_from_m = (db.dr(1) & 1) != 0;
  i.outputs_to_m = (db.dr(1) & 2) != 0;
  i.cycle_factor = db.dl(1) == 0 ? 1 : db.dl(1);
  i.source = {db.dl(2), db.dr(2)};
  i.sink = {db.dl(3), db.dr(3)};
  if (!valid_source(i.source))
    return bad(fmt::format("source address {} offset {} is not a data holder of the manual's source tables",
                           i.source.address, i.source.offset));
  if (i.source.address == 255 && i.source.offset >= i.number)
    return bad(fmt::format("source = sink of SF{}: the producer must have a smaller SF number than SF{}",
                           i.source.offset, i.number));
  if (!valid_sink(i.sink))
    return bad(fmt::format("sink address {} offset {} is not a data holder of the manual's sink tables", i.sink.address,
                           i.sink.offset));
  i.in_mask = db.dr(4);
  i.in_byte = db.dl(4);
  i.out_mask = db.dr(5);
  i.out_byte = db.dl(5);
  if (!one_bit_or_zero(i.in_mask)) return bad(fmt::format("DR4 input bit mask = {}: one bit (E1) or 0", i.in_mask));
  if (!one_bit_or_zero(i.out_mask)) return bad(fmt::format("DR5 output bit mask = {}: one bit (A1) or 0", i.out_mask));
  for (std::size_t k = 0; k < 8; ++k) {
    const std::uint8_t v = k % 2 == 0 ? db.dr(6 + k / 2) : db.dl(6 + k / 2);
    if (v > 63) return bad(fmt::format("Tab{} DB number = {}: must be 0..63", k, v));
    i.tables[k] = v;
  }
  return i;
}

int InitDb::in_bit() const noexcept {
  return in_mask == 0 ? 8 : std::countr_zero(static_cast<unsigned>(in_mask));
}
int InitDb::out_bit() const noexcept {
  return out_mask == 0 ? 8 : std::countr_zero(static_cast<unsigned>(out_mask));
}

std::optional<SfFault> FastFunction::value_new(const DataBlock&, SfIo&) {
  return SfFault{SfError::value_new_not_active, "this SF type does not accept VALUE NEW (manual §2.3 code table)"};
}

std::expected<std::int32_t, SfFault> FastFunction::read_value(const DataBlock&, const InitDb&, SfIo&) {
  return std::unexpected(SfFault{SfError::start_invalid, "READ VALUE: only XFIPW has it (manual §2.3 code table)"});
}

void FastFunction::reset(SfIo&) noexcept {}

SfFault start_error(const char* sf, const char* field, long long value, const char* rule) {
  return SfFault{SfError::start_invalid, fmt::format("{}: {} = {}: {}", sf, field, value, rule)};
}

}  // namespace hil::controllers::amkasyn
