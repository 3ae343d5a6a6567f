// SPDX-License-Identifier: MIT
#pragma once
// The zero marks (reference / marker pulses) of an incremental encoder: one mark every
// `period_inc` counts of the actual position, at counts = offset_inc + k * period_inc. Pure: the
// caller passes two successive actual positions and learns which mark the axis passed between
// them, exact to the count whatever the speed (the encoder interface latches the mark; a position
// sampled once per cycle would miss a mark one count wide). Used by the reference runs of the
// legacy controllers (the ELG's REF mode behind the cam, the CLM1.4's homing options 1 and 2).

#include <cstdint>
#include <optional>

#include "hil/motion/gear_ratio.hpp"

namespace hil::motion {

struct ZeroMarkGrid {
  std::int64_t period_inc = 1;  ///< counts between two marks (one encoder revolution: 4 x lines); <= 0 acts as 1
  std::int64_t offset_inc = 0;  ///< the count of mark 0

  /// Marks at or below `counts`, minus one: floor((counts - offset) / period).
  [[nodiscard]] constexpr std::int64_t index(std::int64_t counts) const noexcept {
    return floor_div(counts - offset_inc, period());
  }
  /// The count of mark `k`.
  [[nodiscard]] constexpr std::int64_t mark(std::int64_t k) const noexcept { return offset_inc + k * period(); }
  /// Moving forward from `before` to `now`: the first mark in (before, now], if any.
  [[nodiscard]] constexpr std::optional<std::int64_t> passed_forward(std::int64_t before,
                                                                     std::int64_t now) const noexcept {
    if (now <= before || index(now) == index(before)) return std::nullopt;
    return mark(index(before) + 1);
  }
  /// Moving backward from `before` to `now`: the first mark in (now, before], if any (a position
  /// exactly on a mark leaves it backwards at once).
  [[nodiscard]] constexpr std::optional<std::int64_t> passed_backward(std::int64_t before,
                                                                      std::int64_t now) const noexcept {
    if (now >= before || index(now) == index(before)) return std::nullopt;
    return mark(index(before));
  }
  /// The first mark passed in the direction of travel (forward when now > before).
  [[nodiscard]] constexpr std::optional<std::int64_t> passed(std::int64_t before, std::int64_t now) const noexcept {
    return now > before ? passed_forward(before, now) : passed_backward(before, now);
  }
  /// Whether `counts` sits on a mark (the marker line is high for one count).
  [[nodiscard]] constexpr bool on_mark(std::int64_t counts) const noexcept {
    return counts - offset_inc - index(counts) * period() == 0;
  }

 private:
  [[nodiscard]] constexpr std::int64_t period() const noexcept { return period_inc > 0 ? period_inc : 1; }
};

}  // namespace hil::motion
