// SPDX-License-Identifier: MIT
#pragma once
// Internal: the checks a program step's completion and a wait_until condition share, so that
// "at rest" and "this fault" mean the same in both.

#include <string>

#include "hil/core/fault.hpp"
#include "hil/motion/axis_status.hpp"
#include "hil/runtime/scenario_loader.hpp"

namespace hil::runtime::detail {

/// `f` is set and is `code` ("category:value"); an empty `code` matches any fault.
[[nodiscard]] inline bool fault_matches(const Fault& f, const std::string& code) {
  if (!f) return false;
  if (code.empty()) return true;
  const auto c = parse_fault_code(code);
  return c && c->value == f.code.value() && c->category == f.code.category().name();
}

/// The axis has ended its motion: not busy, not moving, stopping or homing.
[[nodiscard]] inline bool at_rest(const motion::AxisStatus& s) noexcept {
  return !s.busy && s.state != motion::AxisState::moving && s.state != motion::AxisState::stopping &&
         s.state != motion::AxisState::homing;
}

}  // namespace hil::runtime::detail
