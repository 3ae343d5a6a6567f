// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_follower.hpp"

namespace hil::controllers::s5 {

void Ip247Follower::step(motion::Axis& axis, const Ip247Axis& module, std::int64_t period_ns) noexcept {
  if (module.planner() == nullptr) {  // no machine data: no pulses
    planner_ = nullptr;
    return;
  }
  const std::int64_t pulses = module.planner()->motor_position();
  if (anchored_ && module.planner() != planner_) {
    // A new MD set (BA20) gives the module a new pulse counter; the motor has not moved: its new
    // count continues from the set-point the axis last had.
    base_inc_ += last_pulses_ - base_pulses_;
    base_pulses_ = last_pulses_ = pulses;
  }
  planner_ = module.planner();
  if (!anchored_) {
    base_inc_ = axis.status().command_inc;
    base_pulses_ = last_pulses_ = pulses;
    anchored_ = true;
  }
  const std::int64_t delta = pulses - last_pulses_;
  last_pulses_ = pulses;
  const std::int64_t target = base_inc_ + (pulses - base_pulses_);
  if (delta != 0) {
    resting_ = 0;
    const double v = period_ns > 0 ? static_cast<double>(delta) * 1e9 / static_cast<double>(period_ns) : 0.0;
    following_ = !axis.follow(target, v, 0.0);
  } else if (following_) {
    // The pulse output rests: one cycle at velocity 0, then the axis settles like after any move.
    if (++resting_ >= 2) {
      (void)axis.stop();
      following_ = false;
    } else {
      (void)axis.follow(target, 0.0, 0.0);
    }
  }
}

}  // namespace hil::controllers::s5
