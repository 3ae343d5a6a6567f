// SPDX-License-Identifier: MIT
#include "hil/runtime/condition.hpp"

#include <cstring>

#include "hil/runtime/scenario_loader.hpp"

namespace hil::runtime {
namespace {

bool fault_matches(const Fault& f, const std::string& code) noexcept {
  if (!f) return false;
  if (code.empty()) return true;
  const auto colon = code.find(':');
  if (colon == std::string::npos) return false;
  if (code.compare(0, colon, f.code.category().name()) != 0) return false;
  const auto c = parse_fault_code(code);
  return c && c->value == f.code.value();
}

bool resting(const motion::AxisStatus& st) noexcept {
  return !st.busy && st.state != motion::AxisState::moving && st.state != motion::AxisState::stopping &&
         st.state != motion::AxisState::homing;
}

}  // namespace

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
      return fault_matches(st.fault, c.fault_code) || fault_matches(axis.drive().feedback().fault, c.fault_code);
    case Condition::Kind::no_motion:
      return resting(st);
    case Condition::Kind::in_position:
      return resting(st) && st.in_position;
  }
  return false;
}

}  // namespace hil::runtime
