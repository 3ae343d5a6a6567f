// SPDX-License-Identifier: MIT
#pragma once
// Exact rational conversion between user units and drive increments, linear and rotary.
//
// A user position x maps to round(x * num / den) increments (half away from zero). The integer
// part of x is scaled in 128-bit integer arithmetic, so the result is exact whatever the size of
// x; only the fractional part goes through a double, which cannot accumulate: targets are kept
// in increments and relative moves carry their fractional increment to the next one.

#include <cstdint>

#include "hil/motion/ratio.hpp"

namespace hil::motion {

class Scaling {
 public:
  /// `ratio` must have num > 0, den > 0 (validate() checks). For rotary axes
  /// modulo * num / den must be an integer number of increments per turn.
  Scaling(Ratio ratio, bool rotary, double modulo) noexcept;

  /// Exact: round(units * num / den), half away from zero.
  [[nodiscard]] std::int64_t to_inc(double units) const noexcept;
  /// Fast approximation for the cyclic path (error < 1e-15 relative; not for targets).
  [[nodiscard]] std::int64_t to_inc_fast(double units) const noexcept;
  /// inc * den / num, exact integer part plus the remainder as a double fraction.
  [[nodiscard]] double to_units(std::int64_t inc) const noexcept;
  /// Fast approximation for the cyclic path.
  [[nodiscard]] double to_units_fast(std::int64_t inc) const noexcept {
    return static_cast<double>(inc) * units_per_inc_;
  }
  /// A distance in increments with a carried fraction: returns round(distance*num/den + carry)
  /// and leaves the rest (|carry| <= 0.5) in `carry_inc`. Repeated calls never drift.
  [[nodiscard]] std::int64_t delta_to_inc(double distance, double& carry_inc) const noexcept;

  [[nodiscard]] double inc_per_unit() const noexcept { return inc_per_unit_; }
  [[nodiscard]] bool rotary() const noexcept { return rotary_; }
  [[nodiscard]] double modulo() const noexcept { return modulo_; }
  /// Increments per turn (rotary), 0 for linear axes.
  [[nodiscard]] std::int64_t inc_per_turn() const noexcept { return inc_per_turn_; }
  /// Rotary: `inc` wrapped into [0, inc_per_turn); linear: unchanged.
  [[nodiscard]] std::int64_t wrap_inc(std::int64_t inc) const noexcept;
  /// Rotary: position shown to the user, in [0, modulo); linear: to_units(inc).
  [[nodiscard]] double display_units(std::int64_t inc) const noexcept;
  /// Rotary: the signed increment step from `from_inc` to the angle `target_units` (taken modulo)
  /// going the way `direction` says (0 = shortest, +1 = positive, -1 = negative).
  [[nodiscard]] std::int64_t rotary_step(std::int64_t from_inc, double target_units, int direction) const noexcept;

 private:
  std::int64_t num_, den_;
  bool rotary_;
  double modulo_;
  std::int64_t inc_per_turn_ = 0;
  double inc_per_unit_, units_per_inc_;
};

}  // namespace hil::motion
