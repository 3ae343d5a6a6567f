// SPDX-License-Identifier: MIT
#pragma once
// Internal: the key and interface-signal edge test of the gearbox and the setting-up modes.

namespace hil::controllers::elg::detail {

/// A 0 -> 1 transition between the previous cycle's signal and this one's.
[[nodiscard]] constexpr bool rising(bool now, bool before) noexcept {
  return now && !before;
}

}  // namespace hil::controllers::elg::detail
