// SPDX-License-Identifier: MIT
#pragma once
// A scenario condition (`wait_until:`, `io: - set: ... when:`) evaluated on one axis.

#include "hil/motion/axis.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime {

/// True when `c` holds for `axis` now (fault conditions look at the axis and its drive).
/// Cycle thread; never throws.
[[nodiscard]] bool condition_met(const Condition& c, motion::Axis& axis) noexcept;

}  // namespace hil::runtime
