// SPDX-License-Identifier: MIT
// CLM1.4 homing on the axes (manual §7.9, digest §5.7): HOM and the Ax23 homing input start the
// homing state machine (homing.hpp) or, with Options::drive_homing, the drive's homing; option 5
// (passive) is watched on every cycle; the Ax24 "homed" output is written when homed changes.
#include <fmt/format.h>

#include <cmath>

#include "hil/controllers/clm14/controller.hpp"
#include "hil/motion/zero_mark.hpp"

namespace hil::controllers::clm14 {

HomingInput Controller::homing_input(int axis) {
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  HomingInput in;
  in.position_inc = a.fb.position_inc;
  in.standstill = !a.fb.busy;
  in.home_switch = as.home_switch_input && image_.bit(*as.home_switch_input);
  const MarkerSource& src = options_.markers[static_cast<std::size_t>(axis - 1)];
  if (src.input) {
    const bool level = image_.bit(*src.input);
    if (level && !a.marker_input_last) in.marker = in.position_inc;
    in.marker_high = level;
    a.marker_input_last = level;
  } else {
    const motion::ZeroMarkGrid grid{4 * static_cast<std::int64_t>(std::max(1, as.encoder_pulses)), src.offset_inc};
    in.marker = grid.passed(a.marker_last_inc, in.position_inc);
    in.marker_high = grid.on_mark(in.position_inc);
  }
  a.marker_last_inc = in.position_inc;
  return in;
}

void Controller::apply_homing(int axis, const HomingCommand& c) {
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  const double ipu = inc_per_iu(axis);
  switch (c.kind) {
    case HomingCommand::Kind::none:
      return;
    case HomingCommand::Kind::run: {
      const double v = c.velocity_inc_per_s / ipu;
      a.port->run(v, limits_for(axis, std::abs(v), false));  // no override on homing (§7.3)
      return;
    }
    case HomingCommand::Kind::stop:
      a.port->stop();
      return;
    case HomingCommand::Kind::move: {
      const double target = a.fb.position + static_cast<double>(c.target_inc - a.fb.position_inc) / ipu;
      a.port->move_to(target, limits_for(axis, c.velocity_inc_per_s / ipu, false));
      return;
    }
  }
}

void Controller::set_home(int axis, std::int64_t home_inc) {
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  // The reference count reads Ax25 (§7.9 step 5: "norm the position to 0 + Ax25").
  const double raw_at_home = a.fb.position - static_cast<double>(a.fb.position_inc - home_inc) / inc_per_iu(axis);
  a.base = as.home_offset - raw_at_home;
  a.sac = 0.0;
  a.homed = true;
  reset_wheel(axis);  // homing runs on the motor encoder: axis and motor position read Ax25
}

bool Controller::start_homing(int axis, int t) {
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  const auto refuse = [&](std::string why) {
    const int code = axis_code(ClmError::hom_command, axis);
    if (t > 0)
      fail(t, code, std::move(why));
    else
      raise(code, std::move(why));
    return false;
  };
  if (as.absolute_encoder()) return refuse(fmt::format("axis {}: HOM with an absolute encoder", axis));
  a.homed = false;
  a.homing = true;
  a.homing_restart = false;
  a.has_target = a.feeding = a.held = a.pending = a.con = false;
  if (options_.drive_homing) {
    a.port->home();
    return true;
  }
  if (as.homing_type == 4) {
    a.homing = false;
    return refuse(fmt::format("axis {}: Ax24 type 4 (option 5) is passive: jog over the home switch", axis));
  }
  const double ipu = inc_per_iu(axis);
  HomingSetup s;
  s.type = as.homing_type;
  s.direction = as.homing_velocity_permille < 0 ? -1 : 1;
  // V1 = Ax24 ‰ × Ax06 without override (§7.3); 000 runs at 1 ‰ as the feeds [decided].
  s.v1_inc_per_s = std::max(std::abs(as.homing_velocity_permille), 1) / 1000.0 * as.vmax * ipu;
  s.cycle_s = settings_.cycle_ms / 1000.0;
  s.revolution_inc = 4 * static_cast<std::int64_t>(std::max(1, as.encoder_pulses));
  // [decided] the cam / switch edge is searched over the whole travel range of a linear axis
  // (Ax04 - Ax03), two table revolutions of a rotary table, without limit on a rotary axis.
  double span = 0.0;
  if (as.motion == MotionType::linear)
    span = as.max_limit - as.min_limit;
  else if (as.motion == MotionType::rotary_table)
    span = 2.0 * (as.modulo > 0.0 ? as.modulo : as.feed_constant);
  s.search_limit_inc = static_cast<std::int64_t>(std::llround(span * ipu));
  s.has_switch = as.home_switch_input.has_value();
  const HomingCommand c = a.homer.start(s, homing_input(axis));
  if (a.homer.status() == HomingStatus::failed) {
    a.homing = false;
    return refuse(fmt::format("axis {}: homing option {} needs a home switch (Ax23)", axis, as.homing_type + 1));
  }
  apply_homing(axis, c);
  return true;
}

void Controller::abort_homing(int axis, bool restart) {
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  if (!a.homing) return;
  a.homing = false;
  a.homing_restart = restart;
  a.homer.abort();
  if (a.port != nullptr) a.port->stop();
}

void Controller::step_homing(int axis) {
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  const HomingInput in = homing_input(axis);
  // Option 5 (passive, §7.9): homed where the axis leaves the switch moving forward or reaches
  // it moving backward (jog 1 in Manual, the synchronous carriage in Automatic).
  if (as.homing_type == 4 && !options_.drive_homing && !a.homed && as.home_switch_input) {
    const bool left_forward = a.home_switch_last && !in.home_switch && a.fb.velocity > 0.0;
    const bool reached_backward = !a.home_switch_last && in.home_switch && a.fb.velocity < 0.0;
    if (left_forward || reached_backward) set_home(axis, in.position_inc);
  }
  a.home_switch_last = in.home_switch;
  // Manual: a rising edge at the Ax23 homing input starts homing (not while jogging or running
  // the manual vector); Immediate Stop aborts it, to be started again (§7.9 "Termination").
  if (mode_ == Mode::manual && as.homing_start_input && error_ == 0 && a.drive_enable && !a.homing && !a.jog &&
      !tasks_[0].manual_vector && image_.bit(*as.homing_start_input) && !previous_inputs_.bit(*as.homing_start_input) &&
      image_.bit(sys::immediate_stop_ok))
    (void)start_homing(axis, 0);
  if (!a.homing) return;
  if (mode_ == Mode::manual && !image_.bit(sys::immediate_stop_ok)) {
    abort_homing(axis, false);
    return;
  }
  if (options_.drive_homing) {
    if (a.fb.referenced && !a.fb.busy) {
      a.homing = false;
      a.homed = true;
      a.base = as.home_offset - a.fb.position;
      a.sac = 0.0;
      reset_wheel(axis);
    }
    return;
  }
  apply_homing(axis, a.homer.step(in));
  switch (a.homer.status()) {
    case HomingStatus::done:
      a.homing = false;
      set_home(axis, a.homer.home_inc());
      break;
    case HomingStatus::failed: {
      a.homing = false;
      const int code = a.homer.error() + axis_offset(axis);
      const char* what = a.homer.error() == static_cast<int>(ClmError::cam_too_short)     ? "cam too short"
                         : a.homer.error() == static_cast<int>(ClmError::no_marker_pulse) ? "no marker pulse"
                         : a.homer.error() == static_cast<int>(ClmError::marker_pulse_position)
                             ? "marker pulse position"
                         : a.homer.error() == static_cast<int>(ClmError::marker_high) ? "marker high"
                                                                                      : "no home switch edge";
      raise(code,
            fmt::format("axis {} homing option {}: {} (cam edge to marker {} increments of {} per revolution)", axis,
                        as.homing_type + 1, what, a.homer.edge_to_marker_inc(), 4 * std::max(1, as.encoder_pulses)));
      break;
    }
    default:
      break;
  }
}

}  // namespace hil::controllers::clm14
