// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/wf725_machine_data.hpp"

#include <cmath>
#include <variant>

#include "hil/profiles/validation.hpp"

namespace hil::controllers::s5 {

std::int64_t Wf725MachineData::integer(int n) const noexcept {
  return static_cast<std::int64_t>(std::llround(static_cast<double>(get(n))));
}

void Wf725MachineData::set(int n, long double v) noexcept {
  if (n < 1 || n > 50) return;
  md[static_cast<std::size_t>(n)] = v;
  present |= std::uint64_t{1} << n;
}

int Wf725MachineData::fast_input_function(int input) const noexcept {
  if (!fast_input_map() || input < 1 || input > 6) return 0;
  std::int64_t v = integer(15);
  for (int i = 1; i < input; ++i) v /= 10;
  return static_cast<int>(v % 10);
}

int Wf725MachineData::fast_input_with(int f) const noexcept {
  for (int e = 1; e <= 6; ++e)
    if (fast_input_function(e) == f) return e;
  return 0;
}

Wf725MachineData wf725_machine_data(const LoadedParameters& p, const profiles::Settings& settings) {
  Wf725MachineData d;
  if (const auto it = settings.find("module"); it != settings.end()) {
    if (const auto* s = std::get_if<std::string>(&it->second)) d.series = s->starts_with("WF725") ? 725 : 726;
  }
  const profiles::Scope scope(*p.profile, &p.set, settings);
  for (int n = 1; n <= 50; ++n) {
    const auto v = scope.lookup("MD" + std::to_string(n));
    if (!v) continue;
    if (const auto* x = std::get_if<long double>(&*v)) d.set(n, *x);
  }
  return d;
}

int check_wf725_mode_change(const Wf725MachineData& md) noexcept {
  if (md.get(19) == 0 && md.get(20) == 0) return 0x19;
  if (md.get(34) == 0) return 0x1A;
  if (md.integer(12) > md.integer(11)) return 0x1B;
  if (md.integer(14) < md.integer(13)) return 0x1C;
  return 0;
}

bool wf725_md_shapes_axis(int n) noexcept {
  switch (n) {
    case 1:
    case 2:
    case 3:
    case 4:
    case 18:
    case 19:
    case 20:
    case 21:
    case 22:
    case 24:
    case 25:
    case 26:
    case 27:  // split drive: the coupling is made at power-up (wf725_couple_split_drive)
    case 30:
    case 31:
    case 33:
    case 38:
    case 39:
    case 49:
      return true;
    default:
      return false;
  }
}

}  // namespace hil::controllers::s5
