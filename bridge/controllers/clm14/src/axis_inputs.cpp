// SPDX-License-Identifier: MIT
// CLM1.4 per-axis input functions and outputs (manual §7.3, §7.4, §8.2; digest §5.4, §5.6,
// §5.13): the B017 override inputs (binary, Gray code), Ax15 feed-angle monitoring and interrupt,
// Ax30 open feed roll, the Ax32 outputs "target velocity reached" / "deceleration active"; the
// analog inputs AE1..AE4 (B017 averaging, V007..V010, override sources 1-4).
#include <fmt/format.h>

#include <array>
#include <cmath>

#include "hil/controllers/clm14/controller.hpp"

namespace hil::controllers::clm14 {

namespace {

/// §7.3: the override % of the reflected-Gray index 0..15 on I1.01.4 (2^0) .. I1.01.7 (2^3).
constexpr std::array<int, 16> gray_percent{0, 1, 2, 4, 6, 8, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100};

constexpr ByteAddress override_byte{Area::input, 1, 1};  // I1.01

int gray_to_binary(int g) {
  int b = g;
  for (int s = g >> 1; s != 0; s >>= 1) b ^= s;
  return b;
}

}  // namespace

double Controller::input_override(int axis) const {
  const auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  if (a.override_permille != 1000 || a.override_master) return 1.0;  // VEO has priority over B017
  const std::uint8_t in = image_.byte(override_byte);
  switch (settings_.override_source[static_cast<std::size_t>(axis - 1)]) {
    case 1:
    case 2:
    case 3:
    case 4:  // AE1..AE4: F = 0 … 1 for 0 … 10 V (§5.6), from the B017 average
      return analog_override(
          analog_avg_[static_cast<std::size_t>(settings_.override_source[static_cast<std::size_t>(axis - 1)] - 1)]
              .millivolts());
    case 5:
      return in / 255.0;  // binary on I1.01.0 (1) .. I1.01.7 (128): Vo = Vp × sum / 255
    case 6:
      return gray_percent[static_cast<std::size_t>(gray_to_binary((in >> 4) & 0x0F))] / 100.0;
    default:
      return 1.0;
  }
}

void Controller::update_analog_in() {
  for (std::size_t i = 0; i < 4; ++i) {
    AnalogAverage& f = analog_avg_[i];
    // Power-up or a new B017 averaging code: the history starts as a steady input [decided].
    if (f.code() != settings_.analog_averaging) f.reset(settings_.analog_averaging, analog_mv_[i]);
    f.push(analog_mv_[i]);
    vars_[7 + i] = to_micro(f.millivolts() / 10000.0);  // V007..V010: normalised to ±1
  }
}

double Controller::analog_average(int input) const noexcept {
  return input >= 1 && input <= 4 ? analog_avg_[static_cast<std::size_t>(input - 1)].millivolts() : 0.0;
}

bool Controller::feed_blocked(int axis) const {
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  if (as.feed_angle_input && !image_.bit(*as.feed_angle_input)) return true;
  if (as.interrupt_input && !image_.bit(*as.interrupt_input)) return true;
  return as.open_feed_roll_input && image_.bit(*as.open_feed_roll_input);
}

void Controller::step_axis_inputs() {
  inhibit_ = false;
  for (int ax = 1; ax <= 4; ++ax) {
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    const auto& as = settings_.axes[static_cast<std::size_t>(ax - 1)];
    if (a.port == nullptr || !as.enabled || !settings_ok_) continue;
    const bool active = mode_ != Mode::parameter && error_ == 0 && a.drive_enable;
    const bool moving_feed = a.has_target && a.feeding && !a.held && !a.pending;
    // Ax15 feed angle: a feed in progress that loses the signal is error 41 (axis series).
    const bool fa = !as.feed_angle_input || image_.bit(*as.feed_angle_input);
    if (active && as.feed_angle_input && a.feed_angle_last && !fa && moving_feed && a.fb.busy) {
      raise(axis_code(ClmError::feed_angle_loss, ax),
            fmt::format("axis {}: feed angle input {} lost during a feed", ax, to_string(*as.feed_angle_input)));
      a.feed_angle_last = fa;
      return;
    }
    a.feed_angle_last = fa;
    if (a.homing && mode_ == Mode::manual && !fa) abort_homing(ax, false);  // feed monitoring (§7.9)
    // Ax15 interrupt: losing it stops the move with its ramp and blocks new feeds; the move
    // resumes by itself when it returns (no Start). Homing: Manual aborts it, Automatic runs it
    // again on the return [decided].
    const bool int_ok = !as.interrupt_input || image_.bit(*as.interrupt_input);
    if (active && !int_ok && !a.interrupted) {
      a.interrupted = true;
      if (a.homing) abort_homing(ax, mode_ == Mode::automatic);
      if (moving_feed || a.con) a.port->stop();
    } else if (a.interrupted && (int_ok || !active)) {
      a.interrupted = false;
      if (active && a.has_target && a.feeding && !a.held && !a.pending && !a.override_stopped)
        a.port->move_to(raw_of(ax, a.target), limits_for(ax, a.velocity));
      else if (active && a.con)
        a.port->run(a.con_velocity * a.input_override, limits_for(ax, std::abs(a.con_velocity)));
      if (active && a.homing_restart && mode_ == Mode::automatic && run_ == RunState::running) {
        a.homing_restart = false;
        (void)start_homing(ax, 0);
      }
    }
    if (a.interrupted || (!fa && (moving_feed || a.jog))) inhibit_ = true;
    // Ax30 open feed roll: input set while the axis stands in position -> command 0 (the drive is
    // disabled, it may drift), the output shows it; feeds wait until the input drops.
    if (as.open_feed_roll_input) {
      const bool in = image_.bit(*as.open_feed_roll_input);
      const bool open = in && a.drive_enable && (a.roll_open || (!a.fb.busy && !a.feeding && !a.con && !a.homing));
      if (open && !a.roll_open) a.port->set_enabled(false);
      if (!open && a.roll_open && a.drive_enable) a.port->set_enabled(true);
      a.roll_open = open;
      if (as.open_feed_roll_output) write_bit(*as.open_feed_roll_output, open);
    }
    // B017: the override inputs scale feeds and CON; a running feed is re-planned when the
    // factor moves by more than 0.1 %, stopped (target kept) at 0 % and resumed above it.
    const double f = input_override(ax);
    if (std::abs(f - a.input_override) > 0.001 || (f == 0.0) != (a.input_override == 0.0)) {
      a.input_override = f;
      if (moving_feed && !a.interrupted) {
        if (f == 0.0) {
          a.port->stop();
          a.override_stopped = true;
        } else {
          a.override_stopped = false;
          a.port->move_to(raw_of(ax, a.target), limits_for(ax, a.velocity));
        }
      } else if (a.con && !a.interrupted) {
        a.port->run(a.con_velocity * f, limits_for(ax, std::abs(a.con_velocity)));
      }
    }
    if (!moving_feed) a.override_stopped = false;
    // Ax32: "target velocity reached" while the set-point runs at a constant, non-zero velocity;
    // "deceleration active" while its magnitude falls.
    const double v = std::abs(a.fb.command_velocity);
    const double dv = v - a.command_velocity_last;
    const double eps = 1e-6 * as.vmax;
    a.command_velocity_last = v;
    if (as.velocity_reached_output) write_bit(*as.velocity_reached_output, a.fb.busy && v > eps && std::abs(dv) <= eps);
    if (as.decelerating_output) write_bit(*as.decelerating_output, a.fb.busy && dv < -eps);
  }
}

}  // namespace hil::controllers::clm14
