// SPDX-License-Identifier: MIT
#pragma once
// The IP247's pulse output as the cyclic set-point of a machine axis (motion::Axis::follow): module
// pulse 0 is where the axis stands when it is first driven; every module cycle the axis follows the
// planner's motor pulses (1 increment = 1 pulse, backlash pulses included) at the cycle's velocity;
// when the pulses rest for two cycles the axis is stopped so it settles in position like after any
// move. Used by the `ip247` controller and by `hilbridge emulate ip247 --machine`.
// Thread: the module cycle only; never throws.

#include <cstdint>

#include "hil/controllers/s5/ip247_axis.hpp"
#include "hil/motion/axis.hpp"

namespace hil::controllers::s5 {

class Ip247Follower {
 public:
  /// One module cycle of `period_ns`: the axis follows `module`'s pulses. Call only while the axis
  /// takes set-points (enabled, not in error).
  void step(motion::Axis& axis, const Ip247Axis& module, std::int64_t period_ns) noexcept;
  /// Whether the axis follows (the last follow() was accepted).
  [[nodiscard]] bool following() const noexcept { return following_; }

 private:
  bool anchored_ = false;
  const stepdir::StepPlanner* planner_ = nullptr;  ///< the counter anchored to (a new MD set re-anchors)
  std::int64_t base_inc_ = 0;                      ///< machine-axis increment of module pulse base_pulses_
  std::int64_t base_pulses_ = 0;
  std::int64_t last_pulses_ = 0;
  int resting_ = 0;
  bool following_ = false;
};

}  // namespace hil::controllers::s5
