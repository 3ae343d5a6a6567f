// SPDX-License-Identifier: MIT
// Coupling step 0: masters (virtual master axis, external encoder unwrap). See master.hpp.
#include "hil/motion/master.hpp"

#include <cmath>

namespace hil::motion {

const char* to_string(MasterKind k) noexcept {
  switch (k) {
    case MasterKind::axis_command:
      return "axis_command";
    case MasterKind::axis_actual:
      return "axis_actual";
    case MasterKind::virtual_axis:
      return "virtual";
    case MasterKind::encoder:
      return "encoder";
    case MasterKind::time:
      return "time";
  }
  return "?";
}

void VirtualMaster::set_velocity(double velocity_inc_per_s, double acceleration_inc_per_s2) noexcept {
  if (!std::isfinite(velocity_inc_per_s)) return;
  target_ = velocity_inc_per_s;
  acceleration_ = acceleration_inc_per_s2 > 0 ? acceleration_inc_per_s2 : 1.0;
}

std::int64_t VirtualMaster::update(hil::Duration period) noexcept {
  const double dt = hil::to_seconds(period);
  const double v0 = velocity_;
  const double dv = target_ - v0;
  const double step = acceleration_ * dt;  // inf for a step
  velocity_ = std::fabs(dv) <= step ? target_ : v0 + (dv > 0 ? step : -step);
  // Trapezoidal integration: the exact distance of a linear velocity ramp over the cycle.
  const double d = 0.5 * (v0 + velocity_) * dt + frac_;
  const double whole = std::floor(d);
  frac_ = d - whole;
  position_ += static_cast<std::int64_t>(whole);
  return position_;
}

std::int64_t EncoderInput::update(std::uint32_t raw) noexcept {
  if (bits_ == 16) raw &= 0xFFFFu;
  if (first_) {
    first_ = false;
    last_ = raw;
    return position_;
  }
  const std::int64_t d = bits_ == 16 ? static_cast<std::int16_t>(static_cast<std::uint16_t>(raw - last_))
                                     : static_cast<std::int32_t>(raw - last_);
  last_ = raw;
  position_ += d;
  return position_;
}

}  // namespace hil::motion
