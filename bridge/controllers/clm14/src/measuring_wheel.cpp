// SPDX-License-Identifier: MIT
// CLM1.4 measuring-wheel mode (manual §7.2, digest §5.9: Ax00 modes 3/4, Ax16, Ax31, V047/V048,
// errors 4C/7C): axis 1 measured by master encoder 1, axis 2 by master encoder 2. In Automatic
// (Ax31 set, or Ax31 = 00.00.0) the axis position is the sum of the wheel's moves and the move's
// motor target carries the wheel-motor difference gathered so far; Manual always uses the motor.
// Option 1 (mode 3) corrects until the wheel stands at the target; option 2 (mode 4) until the
// Ax27 window is reached, the rest goes to the next move. docs/clm14.md, "Measuring wheel".
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/controllers/clm14/controller.hpp"

namespace hil::controllers::clm14 {

double Controller::wheel_offset(int axis) const noexcept {
  return axis == 1 || axis == 2 ? wheel_[static_cast<std::size_t>(axis - 1)].offset : 0.0;
}

bool Controller::wheel_active(int axis) const noexcept {
  return (axis == 1 || axis == 2) && wheel_[static_cast<std::size_t>(axis - 1)].active;
}

double Controller::motor_position(int axis) const {
  if (axis < 1 || axis > 4) return 0.0;
  const auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  return a.fb.position + a.base + a.sac;
}

void Controller::reset_wheel(int axis) {
  if (axis != 1 && axis != 2) return;
  auto& w = wheel_[static_cast<std::size_t>(axis - 1)];
  const bool active = w.active;
  w = Wheel{};
  w.active = active;
}

bool Controller::set_motor_position(int axis, double v) {
  if (axis != 1 && axis != 2) return false;
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  if (a.port == nullptr) return false;
  const double shift = v - motor_position(axis);
  a.base += shift;                                             // the motor reads v ...
  wheel_[static_cast<std::size_t>(axis - 1)].offset -= shift;  // ... the axis position stays
  return true;
}

void Controller::on_wheel_move(int axis) {
  if (axis != 1 && axis != 2) return;
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  if (!as.measuring_wheel()) return;
  const auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  auto& w = wheel_[static_cast<std::size_t>(axis - 1)];
  w.correcting = true;
  w.move_offset = w.offset;
  w.move_length = std::abs(a.target - clm_position(axis));
  w.commanded = raw_of(axis, a.target);  // the move starts with the whole difference so far
  w.applied = w.offset;
}

void Controller::step_wheels() {
  if (!settings_ok_) return;
  step_wheel(1);
  step_wheel(2);
}

void Controller::step_wheel(int axis) {
  const auto i = static_cast<std::size_t>(axis - 1);
  auto& w = wheel_[i];
  auto& a = axes_[i];
  const auto& as = settings_.axes[i];
  if (!as.enabled || !as.measuring_wheel() || a.port == nullptr) {
    w.active = w.have_last = false;
    return;
  }
  const bool have = axis == 1 ? me1_.port != nullptr && settings_.me1.used() : master2_available();
  const double wheel = !have ? 0.0 : axis == 1 ? master_position() : master2_position();
  const double motor = a.fb.position;
  // The difference of the last cycle counts when the wheel closed the loop in it.
  if (w.active && w.have_last && have) w.offset += (wheel - w.last_wheel) - (motor - w.last_motor);
  w.last_wheel = wheel;
  w.last_motor = motor;
  w.have_last = have;

  bool want = mode_ == Mode::automatic && error_ == 0 && a.drive_enable && !a.homing &&
              (!as.wheel_input || image_.bit(*as.wheel_input));
  if (want && !have) {
    raise(axis_code(ClmError::encoder_fault, axis),
          fmt::format("axis {}: measuring-wheel mode (A{}00 mode {}) but master encoder {} is not connected "
                      "(name it in the scenario's controller block: master_encoder{})",
                      axis, axis, as.mode, axis, axis == 1 ? "" : "2"));
    want = false;
  }
  if (want != w.active) {
    w.active = want;
    w.revolution = w.exceeded2 = w.tolerance2 = false;
    if (want && a.has_target && a.feeding) {
      // the wheel takes over a running move: its correction counts from here
      w.correcting = true;
      w.move_offset = w.offset;
      w.move_length = std::abs(a.target - clm_position(axis));
      w.commanded = raw_of(axis, a.target);
      w.applied = w.offset;
    }
  }
  if (w.active) {
    // Ax16: the wheel-motor difference within one wheel revolution (C002 / C006 of wheel travel).
    const double circumference = axis == 1 ? settings_.me1.feed_constant : settings_.me2.feed_constant;
    const auto window = [&](int ww) {
      return options_.wheel_window == WheelWindowUnit::percent ? ww / 100.0 * circumference : static_cast<double>(ww);
    };
    if (!w.revolution) {
      w.revolution = true;
      w.rev_wheel = wheel;
      w.rev_motor = motor;
    }
    const double diff = std::abs((wheel - w.rev_wheel) - (motor - w.rev_motor));
    if (as.wheel_window2 > 0 && diff > window(as.wheel_window2)) w.exceeded2 = w.tolerance2 = true;
    if (as.wheel_window1 > 0 && diff > window(as.wheel_window1)) {
      raise(axis_code(ClmError::encoder_fault, axis),
            fmt::format("axis {}: the measuring wheel and the motor differ by {:.3f} IU within one wheel revolution "
                        "(Ax16 window 1: {:.3f} IU): the wheel does not follow",
                        axis, diff, window(as.wheel_window1)));
      w.active = false;
    } else if (std::abs(wheel - w.rev_wheel) >= circumference) {
      // a revolution completed: the output shows whether window 2 was exceeded in it
      w.tolerance2 = w.exceeded2;
      w.exceeded2 = false;
      w.rev_wheel = wheel;
      w.rev_motor = motor;
    }
  }
  if (as.tolerance2_output) write_bit(*as.tolerance2_output, w.active && w.tolerance2);
  if (!w.active || !w.correcting) return;
  if (!a.has_target || a.held || a.pending || a.override_stopped || a.con || a.srm || a.homing || follow_[i].active)
    return;
  const double ipu = inc_per_iu(axis);
  // [decided] the correction of one move never exceeds its own length (or one wheel revolution,
  // if longer): a lifted wheel cannot run the motor away even with Ax16 off.
  const double circumference = axis == 1 ? settings_.me1.feed_constant : settings_.me2.feed_constant;
  const double bound = std::max(w.move_length, circumference);
  if (std::abs(w.offset - w.move_offset) > bound) {
    raise(axis_code(ClmError::encoder_fault, axis),
          fmt::format("axis {}: the wheel correction of the move reached {:.3f} IU (bound {:.3f} IU): the measuring "
                      "wheel does not follow",
                      axis, std::abs(w.offset - w.move_offset), bound));
    return;
  }
  // The motor target follows the difference through a first-order lag (the loop's gain).
  w.applied += (w.offset - w.applied) / std::max(1, options_.wheel_correction_cycles);
  if (as.wheel_correction()) {
    // option 2: the correction ends inside the Ax27 window (at least one increment), with the
    // whole difference gathered up to there; what follows goes to the next move
    const double window = std::max(as.reached_window, 1.0 / ipu);
    if (std::abs(a.target - clm_position(axis)) <= window) {
      w.correcting = false;
      w.applied = w.offset;
    }
  }
  const double raw = a.target - a.base - a.sac - w.applied;
  // Below half a motor increment, or one wheel count (the position's resolution), no re-plan:
  // the loop rests instead of chasing the wheel's quantisation.
  const auto& me = axis == 1 ? settings_.me1 : settings_.me2;
  const double wheel_count = me.feed_constant / (4.0 * std::max(1, me.pulses));
  if (std::abs(raw - w.commanded) < std::max(0.5 / ipu, wheel_count)) return;
  w.commanded = raw;
  a.port->move_to(raw, limits_for(axis, a.velocity));
}

}  // namespace hil::controllers::clm14
