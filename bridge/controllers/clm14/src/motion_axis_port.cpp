// SPDX-License-Identifier: MIT
#include "hil/controllers/clm14/motion_axis_port.hpp"

#include <algorithm>
#include <cmath>

namespace hil::controllers::clm14 {

motion::AxisConfig make_axis_config(const AxisSettings& s, std::string name, double following_error_window) {
  motion::AxisConfig c;
  c.name = std::move(name);
  // IU = counts × Ax01 / (pulses × 4)  (§9.2 status 03): counts per IU = pulses × 4 / Ax01, exactly
  const auto feed_e5 = static_cast<std::int64_t>(std::llround(s.feed_constant * 1e5));
  c.inc_per_unit = {static_cast<std::int64_t>(std::max(1, s.encoder_pulses)) * 4 * 100000,
                    std::max<std::int64_t>(1, feed_e5)};
  c.limits.velocity = s.vmax;
  c.limits.acceleration = s.acceleration;
  c.quick_stop_deceleration = s.acceleration * 10.0;
  c.jog_velocity = std::min(s.jog_velocity, s.vmax);
  c.following_error.static_window = following_error_window > 0.0 ? following_error_window : std::max(1.0, s.vmax * 0.1);
  c.standstill_window = std::max(0.002, s.reached_window * 2.0);
  c.in_position_window = std::max(0.001, s.reached_window);
  c.in_position_timeout = std::chrono::seconds(2);
  return c;
}

AxisFeedback MotionAxisPort::feedback() const {
  const auto& s = axis_.status();
  AxisFeedback f;
  f.position = s.position;
  f.velocity = s.velocity;
  f.following_error = s.following_error;
  f.command_position = s.command_position;
  f.command_velocity = s.command_velocity;
  f.busy = s.busy;
  f.in_position = s.in_position;
  f.enabled = s.state == motion::AxisState::standstill || s.state == motion::AxisState::moving ||
              s.state == motion::AxisState::stopping || s.state == motion::AxisState::homing;
  f.referenced = s.referenced;
  f.fault = s.state == motion::AxisState::error;
  f.position_inc = s.position_inc;
  f.command_inc = s.command_inc;
  return f;
}

motion::Limits MotionAxisPort::clamp(const MoveLimits& l) const {
  const auto& c = axis_.config().limits;
  motion::Limits m;
  m.velocity = std::clamp(l.velocity, 1e-9, c.velocity);
  m.acceleration = std::clamp(l.acceleration, 1e-9, c.acceleration);
  m.jerk = std::min(l.jerk, c.jerk);
  return m;
}

void MotionAxisPort::move_to(double target, const MoveLimits& limits) {
  (void)axis_.move_absolute(target, motion::Direction::shortest, clamp(limits));
}

void MotionAxisPort::run(double velocity, const MoveLimits& limits) {
  const auto& c = axis_.config().limits;
  (void)axis_.move_velocity(std::clamp(velocity, -c.velocity, c.velocity), clamp(limits));
}

void MotionAxisPort::stop() {
  (void)axis_.stop();
}

void MotionAxisPort::quick_stop() {
  (void)axis_.quick_stop();
}

void MotionAxisPort::set_enabled(bool on) {
  (void)(on ? axis_.enable() : axis_.disable());
}

void MotionAxisPort::home() {
  (void)axis_.home();
}

void MotionAxisPort::reset() {
  (void)axis_.reset();
}

void MotionAxisPort::follow(std::int64_t position_inc, double velocity_inc_per_s, double acceleration_inc_per_s2) {
  (void)axis_.follow(position_inc, velocity_inc_per_s, acceleration_inc_per_s2);
}

motion::AxisConfig master_encoder_config(const MasterEncoderSettings& me, const AxisSettings& axis1, std::string name) {
  motion::AxisConfig c;
  c.name = std::move(name);
  const auto feed_e5 = static_cast<std::int64_t>(std::llround(me.feed_constant * 1e5));
  c.inc_per_unit = {static_cast<std::int64_t>(std::max(1, me.pulses)) * 4 * 100000, std::max<std::int64_t>(1, feed_e5)};
  c.limits.velocity = 2.0 * axis1.vmax;
  c.limits.acceleration = 10.0 * axis1.acceleration;
  c.quick_stop_deceleration = 20.0 * axis1.acceleration;
  c.jog_velocity = axis1.jog_velocity;
  c.following_error.static_window = std::max(1.0, axis1.vmax * 0.2);
  c.standstill_window = 0.01;
  c.in_position_window = 0.005;
  c.in_position_timeout = std::chrono::seconds(2);
  return c;
}

}  // namespace hil::controllers::clm14
