// SPDX-License-Identifier: MIT
#pragma once
// Receive filters with SocketCAN CAN_RAW_FILTER / CAN_RAW_ERR_FILTER semantics, shared by the
// virtual bus (applied in-process) and the SocketCAN backend (installed in the kernel). Pure.

#include <cstdint>
#include <vector>

#include "hil/can/frame.hpp"

namespace hil::can {

/// One id/mask filter. A frame matches when `(can_id & mask) == (id & mask)`, where `can_id` is
/// the SocketCAN word (to_socketcan_id: id plus EFF/RTR flags), so a mask that includes
/// `eff_flag` tells 11-bit from 29-bit ids. `inverted` is CAN_INV_FILTER.
struct Filter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;
  bool inverted = false;

  /// Exactly one 11-bit (or 29-bit) data identifier, data and remote frames alike.
  [[nodiscard]] static constexpr Filter exact(std::uint32_t can_id, bool extended = false) noexcept {
    return extended ? Filter{eff_flag | (can_id & eff_mask), eff_flag | eff_mask, false}
                    : Filter{can_id & sff_mask, eff_flag | sff_mask, false};
  }
  [[nodiscard]] constexpr bool matches(std::uint32_t can_id) const noexcept {
    const bool m = (can_id & mask) == (id & mask);
    return inverted ? !m : m;
  }
  friend bool operator==(const Filter&, const Filter&) = default;
};

/// What one receiver accepts. Default: every data/remote frame, no error frames (as a fresh
/// CAN_RAW socket). An empty `filters` list accepts no data frames (SocketCAN: zero filters).
struct FilterSet {
  std::vector<Filter> filters{Filter{}};
  std::uint32_t error_mask = 0;  ///< CAN_RAW_ERR_FILTER: error classes to receive
  bool join = false;             ///< CAN_RAW_JOIN_FILTERS: all filters must match, not any

  [[nodiscard]] bool accepts(const Frame& f) const noexcept {
    if (f.error) return (f.id & error_mask) != 0;
    const std::uint32_t can_id = to_socketcan_id(f);
    if (filters.empty()) return false;
    if (join) {
      for (const auto& flt : filters)
        if (!flt.matches(can_id)) return false;
      return true;
    }
    for (const auto& flt : filters)
      if (flt.matches(can_id)) return true;
    return false;
  }
};

}  // namespace hil::can
