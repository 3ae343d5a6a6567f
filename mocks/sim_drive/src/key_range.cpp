// SPDX-License-Identifier: MIT
#include "hil/mocks/key_range.hpp"

#include <fmt/format.h>

namespace hil::mocks {

std::string KeyRange::check(double value) const {
  if (value >= min && value <= max && !(min_open && value == min)) return {};
  return fmt::format("must be in {}{:g}, {:g}]{}{}, got {}", min_open ? "(" : "[", min, max, unit.empty() ? "" : " ",
                     unit, value);
}

const KeyRange* plant_key_range(std::string_view key) noexcept {
  for (const KeyRange* r :
       {&kv_range, &max_velocity_range, &velocity_lag_range, &feedforward_range, &encoder_step_range, &position_range})
    if (r->key == key) return r;
  return nullptr;
}

}  // namespace hil::mocks
