// SPDX-License-Identifier: MIT
// Coupling step 4: the superimposed (velocity-additive) offset move. See superimposed.hpp.
#include "hil/motion/superimposed.hpp"

#include <cmath>

#include "hil/motion/coupling_fault.hpp"
#include "hil/motion/plan.hpp"

namespace hil::motion {

std::error_code SuperimposedMove::move_by(double distance_inc, const Limits& limits) noexcept {
  if (!std::isfinite(distance_inc) || std::fabs(distance_inc) > 1e15 || !(limits.velocity > 0) ||
      !(limits.acceleration > 0) || !(limits.jerk > 0) || !std::isfinite(limits.velocity) ||
      !std::isfinite(limits.acceleration))
    return make_error_code(CouplingFault::invalid);
  target_ = (active_ ? target_ : state_.p) + distance_inc;
  const State from{state_.p, state_.v, state_.a, 0.0};
  if (!active_ || (from.v == 0.0 && from.a == 0.0))
    plan_rest_to_rest(from.p, target_, limits, profile_);
  else
    plan_position(from, target_, limits, profile_);
  t_ = 0.0;
  hint_ = 0;
  active_ = true;
  return {};
}

void SuperimposedMove::update(hil::Duration period) noexcept {
  if (!active_) return;
  t_ += hil::to_seconds(period);
  if (t_ >= profile_.duration()) {
    state_ = State{target_, 0.0, 0.0, 0.0};  // exactly on the target
    active_ = false;
    return;
  }
  state_ = profile_.sample(t_, hint_);
}

}  // namespace hil::motion
