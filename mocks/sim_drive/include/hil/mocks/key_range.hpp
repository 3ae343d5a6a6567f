// SPDX-License-Identifier: MIT
#pragma once
// The documented range of a numeric configuration key, and the ranges of the plant keys every
// plant-backed drive block takes (`sim`, the simulated CANopen node, the Modbus drive server).
// The bounds keep every run finite: the plant integrates in a bounded number of sub-steps, and
// no value overflows the increments it is converted to.
#include <string>
#include <string_view>

namespace hil::mocks {

struct KeyRange {
  std::string_view key;
  double min = 0.0;
  double max = 0.0;
  bool min_open = false;  ///< min itself excluded: (min, max] instead of [min, max]
  std::string_view unit;  ///< shown after the range, may be empty

  /// "" when `value` is inside, else "must be in (0, 10000] 1/s, got 1e+09" (NaN is outside).
  [[nodiscard]] std::string check(double value) const;
};

inline constexpr KeyRange kv_range{"kv", 0.0, 1e4, true, "1/s"};
inline constexpr KeyRange max_velocity_range{"max_velocity", 0.0, 1e12, true, "inc/s"};
inline constexpr KeyRange velocity_lag_range{"velocity_lag", 0.0, 10.0, false, "s"};
inline constexpr KeyRange feedforward_range{"feedforward", 0.0, 1.0, false, ""};
inline constexpr KeyRange encoder_step_range{"encoder_step", 1.0, 1e9, false, "inc"};
inline constexpr KeyRange position_range{"initial_position", -1e15, 1e15, false, "inc"};

/// The range of a plant key by name (kv, max_velocity, velocity_lag, feedforward, encoder_step,
/// initial_position); nullptr for another name.
[[nodiscard]] const KeyRange* plant_key_range(std::string_view key) noexcept;

}  // namespace hil::mocks
