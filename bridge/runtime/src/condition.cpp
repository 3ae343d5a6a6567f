// SPDX-License-Identifier: MIT
#include "hil/runtime/condition.hpp"

#include <cstring>

#include "axis_checks.hpp"
#include "hil/runtime/scenario_loader.hpp"

namespace hil::runtime {
bool condition_met(const Condition& c, motion::Axis& axis) noexcept {
  const auto& st = axis.status();
  switch (c.kind) {
    case Condition::Kind::compare: {
      const double v = c.quantity == Quantity::position   ? st.position
                       : c.quantity == Quantity::velocity ? st.velocity
                                                          : st.following_error;
      return c.comparison == Comparison::above ? v > c.value : v < c.value;
    }
    case Condition::Kind::state:
      return c.state == motion::to_string(st.state);
    case Condition::Kind::fault:
      return detail::fault_matches(st.fault, c.fault_code) ||
             detail::fault_matches(axis.drive().feedback().fault, c.fault_code);
    case Condition::Kind::no_motion:
      return detail::at_rest(st);
    case Condition::Kind::in_position:
      return detail::at_rest(st) && st.in_position;
  }
  return false;
}

}  // namespace hil::runtime
