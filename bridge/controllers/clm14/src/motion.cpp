// SPDX-License-Identifier: MIT
// CLM1.4 motion commands and per-axis functions (manual §5.7, §7; digest §4.2, §5): feeds, ramps,
// override, VCC, CON, PBK, homing, SAC, RTM, SRM/REP, RMI, position reached, presignal, jog.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/controllers/clm14/controller.hpp"

namespace hil::controllers::clm14 {

namespace {

__extension__ typedef __int128 i128;

bool moves_axis(Op op) {
  switch (op) {
    case Op::con:
    case Op::hom:
    case Op::poa:
    case Op::poi:
    case Op::psa:
    case Op::psi:
    case Op::srm:
    case Op::pbk:
    case Op::vcc:
    case Op::cpl:
    case Op::sac:
    case Op::rmi:
      return true;
    default:
      return false;
  }
}

}  // namespace

double Controller::clm_position(int axis) const {
  const auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  return a.fb.position + a.base + a.sac + wheel_offset(axis);
}

double Controller::raw_of(int axis, double clm) const {
  const auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  return clm - a.base - a.sac - wheel_offset(axis);
}

double Controller::feed_velocity(int axis, int permille) const {
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  const auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  // ‰ of Ax06; 999 = 99.9 % (the PBK example). 000 runs at the slowest step, 1 ‰ [decided].
  double v = as.vmax * std::max(permille, 1) / 1000.0;
  if (a.override_permille != 1000 || a.override_master) {
    // VEO source 4: the command's value; source 5: master encoder 1 velocity / Vmax × FOL factor
    const double ov = a.override_master ? a.master_override : a.override_permille / 1000.0;
    v = a.override_limit ? std::min(v, as.vmax * ov) : v * ov;  // VEO: "as limit" / "as factor"
  }
  return std::max(v, as.vmax / 1000.0);
}

MoveLimits Controller::limits_for(int axis, double velocity, bool overridden) const {
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  const auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  const int pm = a.acc_permille != 0 ? a.acc_permille : as.accel_permille;
  MoveLimits l;
  // B017 input override (axis_inputs.cpp): a factor on every move's velocity but homing's.
  l.velocity = std::abs(velocity) * (overridden ? a.input_override : 1.0);
  l.acceleration = as.acceleration * (pm == 0 ? 1000 : pm) / 1000.0;
  if (a.aeo && master_available()) {
    // AEO (§5.7): Ax08 × (v_ME1 / Ax06)² × sss ‰, at least mmm ‰ of Ax08 (and 1 ‰ [decided]):
    // the acceleration path 0 -> material speed stays the same whatever the material speed.
    const double r = master_velocity() / as.vmax;
    l.acceleration = std::max({as.acceleration * r * r * a.aeo_scale / 1000.0, as.acceleration * a.aeo_min / 1000.0,
                               as.acceleration / 1000.0});
  }
  if (axis == 1 && cut_.phase == Cutoff::Phase::returning && cut_.return_acceleration > 0.0)
    l.acceleration = cut_.return_acceleration;  // A139: the optimised return of the carriage
  if (as.jerk_time_s > 0.0) {
    // Ax10 rounded up so that T / cycle = 2^n (§8.2); the acceleration builds up linearly over T.
    const double cycles = std::max(1.0, std::ceil(as.jerk_time_s * 1000.0 / settings_.cycle_ms - 1e-9));
    const double t = std::exp2(std::ceil(std::log2(cycles))) * settings_.cycle_ms / 1000.0;
    l.jerk = l.acceleration / t;
  }
  return l;
}

bool Controller::reached(int axis) const {
  const auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  const double window = settings_.axes[static_cast<std::size_t>(axis - 1)].reached_window;
  if (!a.has_target) return !a.fb.busy;
  const double err = std::abs(a.target - clm_position(axis));
  if (window > 0.0) return err <= window;
  return !a.fb.busy && a.fb.in_position;
}

bool Controller::command_move(int axis, double target, double velocity, int t) {
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  if (as.motion == MotionType::linear && homed(axis)) {
    // Limits stay in the original (homed) system, not the SAC-shifted one (§5.7 SAC).
    const double original = target - a.sac;
    if (original < as.min_limit) {
      fail(t, axis_code(ClmError::target_below_limit, axis),
           fmt::format("target {:.3f} below Ax03 {:.3f}", original, as.min_limit));
      return false;
    }
    if (original > as.max_limit) {
      fail(t, axis_code(ClmError::target_above_limit, axis),
           fmt::format("target {:.3f} above Ax04 {:.3f}", original, as.max_limit));
      return false;
    }
  }
  a.move_start = a.has_target && a.feeding ? a.move_start : clm_position(axis);
  if (!(a.has_target && a.feeding)) a.move_start = clm_position(axis);
  a.target = target;
  a.has_target = true;
  a.feeding = true;
  a.con = false;
  a.velocity = velocity;
  a.presignal = false;
  on_wheel_move(axis);
  if (run_ == RunState::running || tasks_[0].manual_vector) {
    a.held = false;
    a.pending = !a.fb.enabled;  // the drive is still enabling: the feed starts once it is
    a.override_stopped = !a.pending && a.input_override == 0.0;  // B017 at 0 %: the feed waits
    if (!a.pending && !a.override_stopped) a.port->move_to(raw_of(axis, target), limits_for(axis, velocity));
  } else {
    a.held = true;
  }
  return true;
}

void Controller::hold_axis(int axis) {
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  if (a.port == nullptr || follow_[static_cast<std::size_t>(axis - 1)].active) return;
  if (a.con) {
    a.port->stop();
    a.con = false;
  }
  if (a.has_target && a.feeding && !a.held) {
    if (!a.pending) a.port->stop();
    a.pending = false;
    a.held = true;
  }
}

void Controller::resume_axis(int axis) {
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  if (a.port == nullptr || !a.held || !a.has_target || !a.drive_enable) return;
  a.held = false;
  a.port->move_to(raw_of(axis, a.target), limits_for(axis, a.velocity));
}

void Controller::update_axes_in(TimePoint now) {
  (void)now;
  for (int ax = 1; ax <= 4; ++ax) {
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    if (a.port == nullptr) continue;
    a.fb = a.port->feedback();
    // Actual velocity = the travel over the last velocity_window NC cycles, as the CLM counts
    // it (a rotary position that wrapped is unwrapped by the modulo); 0 on the first cycle.
    const double position = a.fb.position;
    const std::size_t n = std::min(a.positions_seen, velocity_window);
    const double oldest = n == 0 ? position : a.positions[(a.positions_seen - n) % velocity_window];
    double travel = position - oldest;
    const double modulo = settings_.axes[static_cast<std::size_t>(ax - 1)].modulo;
    if (modulo > 0.0 && std::abs(travel) > 0.5 * modulo) travel -= std::copysign(modulo, travel);
    a.fb.velocity = n == 0 ? 0.0 : travel / (static_cast<double>(n) * settings_.cycle_ms / 1000.0);
    a.positions[a.positions_seen % velocity_window] = position;
    ++a.positions_seen;
    if (a.fb.fault && a.drive_enable && error_ == 0) {
      a.homed = false;  // Lag/Runaway clear the homed state (§8.2 Ax14)
      raise(axis_code(ClmError::position_lag, ax),
            fmt::format("axis {}: excess position lag ({:.3f} IU)", ax, a.fb.following_error));
    }
  }
}

void Controller::step_axis_functions(TimePoint now) {
  for (int ax = 1; ax <= 4; ++ax) {
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    const auto& as = settings_.axes[static_cast<std::size_t>(ax - 1)];
    if (a.port == nullptr || !as.enabled || !settings_ok_) continue;
    const double pos = clm_position(ax);
    if (a.pending && a.fb.enabled && a.has_target && run_ == RunState::running) {
      a.pending = false;
      a.port->move_to(raw_of(ax, a.target), limits_for(ax, a.velocity));
    }
    step_homing(ax);
    // The Ax24 "homed" output follows homed on a change only: the program may clear it while
    // the axis stays homed (§7.9).
    const bool homed_now = homed(ax) && !a.homing;
    if (as.homed_output && a.homed_out != homed_now) {
      write_bit(*as.homed_output, homed_now);
      a.homed_out = homed_now;
    }
    // SRM: latch the mark, then move the offset from it; REP limits the search.
    if (a.srm) {
      const bool in = image_.bit(a.srm_input);
      if (in && !a.srm_input_last) {
        a.latched = pos;
        a.srm = false;
        a.has_target = a.feeding = false;
        (void)command_move(ax, pos + a.srm_offset, a.velocity, 1);
      } else if (a.rep && std::abs(pos - a.srm_start) > a.rep_distance) {
        a.srm = false;
        a.srm_rep_hit = true;
        a.port->stop();
        a.has_target = a.feeding = false;
      }
      a.srm_input_last = in;
    }
    const bool at_target = reached(ax);
    if (a.feeding && at_target) a.feeding = false;
    if (as.reached_output) write_bit(*as.reached_output, at_target && !a.con && !a.srm);
    if (as.presignal_output) {
      const bool near = a.has_target && std::abs(a.target - pos) < as.presignal_distance;
      if (near && !a.presignal) {
        a.presignal = true;
        a.presignal_on = now;
      }
      bool out = a.presignal;
      if (as.presignal_pulse_s > 0.0)
        out = out && std::chrono::duration<double>(now - a.presignal_on).count() < as.presignal_pulse_s;
      write_bit(*as.presignal_output, out);
    }
    if (mode_ == Mode::automatic && error_ == 0 && as.motion == MotionType::linear && homed(ax)) {
      const double original = pos - a.sac;
      if (original < as.min_limit)
        raise(axis_code(ClmError::min_travel, ax), fmt::format("axis {} at {:.3f} below Ax03", ax, original));
      else if (original > as.max_limit)
        raise(axis_code(ClmError::max_travel, ax), fmt::format("axis {} at {:.3f} above Ax04", ax, original));
    }
  }
}

void Controller::jog(TimePoint now) {
  (void)now;
  for (int ax = 1; ax <= 4; ++ax) {
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    const auto& as = settings_.axes[static_cast<std::size_t>(ax - 1)];
    if (a.port == nullptr || !as.enabled || follow_[static_cast<std::size_t>(ax - 1)].active || a.homing) continue;
    // Jog is blocked by Immediate Stop, the Ax15 inputs and an open feed roll (Inhibit Operation).
    const bool blocked = feed_blocked(ax) || !image_.bit(sys::immediate_stop_ok);
    const bool allowed = mode_ == Mode::manual && error_ == 0 && a.drive_enable && !tasks_[0].manual_vector && !blocked;
    if (blocked && mode_ == Mode::manual &&
        (image_.bit(sys::jog_forward[static_cast<std::size_t>(ax - 1)]) ||
         image_.bit(sys::jog_reverse[static_cast<std::size_t>(ax - 1)])))
      inhibit_ = true;
    const bool fwd = allowed && image_.bit(sys::jog_forward[static_cast<std::size_t>(ax - 1)]);
    const bool rev = allowed && image_.bit(sys::jog_reverse[static_cast<std::size_t>(ax - 1)]);
    const int dir = fwd == rev ? 0 : fwd ? 1 : -1;
    if (dir != 0 && !a.jog) {
      double v = as.jog_velocity;
      if (a.override_permille != 1000) v = std::max(v * a.override_permille / 1000.0, as.vmax / 1000.0);
      v *= a.input_override;  // B017, taken when the jog starts [decided]
      a.port->run(dir * v, limits_for(ax, v, false));
      a.jog = true;
      a.has_target = false;
    } else if (dir == 0 && a.jog) {
      a.port->stop();
      a.jog = false;
    }
  }
}

Controller::Flow Controller::exec_motion(int t, Task& k, const Instruction& in, TimePoint now) {
  (void)now;
  if (t == 3 && moves_axis(in.op)) {
    fail(t, static_cast<int>(ClmError::invalid_program_command), "task 3 must not move axes");
    return Flow::halt;
  }
  if (k.manual_vector && moves_axis(in.op)) {
    fail(t, static_cast<int>(ClmError::invalid_program_command), "the manual vector program must not contain feeds");
    return Flow::halt;
  }
  if (in.op == Op::fak && *value(in.n[0], t) == 5 * micro_one) {
    // FAK 5: the measuring-wheel correction of the C002 feed constant (flying cutoff only).
    if (!flying_cutoff()) {
      fail(t, static_cast<int>(ClmError::invalid_program_command),
           "FAK 5 (master encoder 1 feed constant) is for the flying cutoff only (A100 mode 5)");
      return Flow::halt;
    }
    const Micro f = *value(in.n[1], t);
    if (f <= 0 || f >= 10 * micro_one) {
      fail(t, static_cast<int>(ClmError::variable_value), "FAK factor must be 0 < f < 10");
      return Flow::halt;
    }
    fak5_ = f;  // applies from the next length instruction / FOL (its ratio and lengths)
    return Flow::next;
  }
  // The axis operand: first, except REP tttt a dddddd.ddd.
  auto axis_or = integer(in.op == Op::rep ? in.n[1] : in.n[0], t, 1, 4);
  if (!axis_or) return Flow::halt;
  const int ax = *axis_or;
  auto& a = axes_[static_cast<std::size_t>(ax - 1)];
  const auto& as = settings_.axes[static_cast<std::size_t>(ax - 1)];
  if (!as.enabled || !a.software_enabled || a.port == nullptr) {
    fail(t, axis_code(ClmError::axis_disabled, ax), fmt::format("axis {} is not enabled (B000 or !M{}OFF)", ax, ax));
    return Flow::halt;
  }
  // "Do not move the axis meanwhile" (§5.7 HOM) [decided]: a command that moves a homing axis
  // waits until the homing has ended.
  if (a.homing && in.op != Op::hom && moves_axis(in.op)) return Flow::wait;
  // §7.4 / §5.13: without the Ax15 feed-angle or interrupt signal, or with the Ax30 feed roll
  // open, no feed starts: the task waits at the feed line (Inhibit Operation).
  const bool starts_feed = in.op == Op::poa || in.op == Op::poi || in.op == Op::psa || in.op == Op::psi ||
                           in.op == Op::srm || (in.op == Op::con && !(in.n[1].value == 0 && !in.n[1].is_var()));
  if (starts_feed && k.phase == 0 && feed_blocked(ax)) {
    inhibit_ = true;
    return Flow::wait;
  }
  const auto permille = [&](const Num& n, int lo) { return integer(n, t, lo, 999); };
  auto& fo = follow_[static_cast<std::size_t>(ax - 1)];
  const bool feed = in.op == Op::poi || in.op == Op::psi;
  if (feed && k.phase == 1 && k.aux == 2)  // a superimposed PSI on a following axis
    return fo.active && fo.coupling.superimposed().busy() ? Flow::wait : Flow::next;
  if (fo.active && in.op != Op::fak && in.op != Op::veo && in.op != Op::acc) {
    if (!fo.fol || !feed) {
      fail(t, static_cast<int>(ClmError::invalid_program_command),
           fmt::format("{} on axis {} while it is coupled ({}): only POI/PSI add to a FOL coupling", mnemonic(in.op),
                       ax, fo.fol ? "FOL" : "flying cutoff"));
      return Flow::halt;
    }
    // §5.7 FOL: moves programmed for the slave are added (velocity-additive): the coupling's
    // superimposed move.
    auto len = length(in.n[1], t);
    auto v = permille(in.n[2], 0);
    if (!len || !v) return Flow::halt;
    const double l = to_double(static_cast<Micro>(static_cast<i128>(*len) * a.fak / micro_one));
    if (!superimpose(ax, l, feed_velocity(ax, *v), t)) return Flow::halt;
    if (in.op == Op::poi) return Flow::next;
    k.phase = 1;
    k.aux = 2;
    return Flow::wait;
  }
  switch (in.op) {
    case Op::acc: {
      auto acc = permille(in.n[1], 0);
      auto dec = permille(in.n[2], 0);
      if (!acc || !dec) return Flow::halt;
      a.acc_permille = *acc;
      a.dec_permille = *dec;
      return Flow::next;
    }
    case Op::con: {
      auto on = integer(in.n[1], t, 0, 1);
      auto v = integer(in.n[2], t, -999, 999);
      if (!on || !v) return Flow::halt;
      if (*on == 0) {
        if (a.con) a.port->stop();
        a.con = false;
        return Flow::next;
      }
      const double vel = feed_velocity(ax, std::abs(*v)) * (*v < 0 ? -1.0 : 1.0);
      a.port->run(vel * a.input_override, limits_for(ax, vel));
      a.con = true;
      a.con_velocity = vel;
      a.has_target = a.feeding = a.held = false;
      return Flow::next;
    }
    case Op::cpl:
      // The lag is zeroed by taking the actual position as the command (§5.7 CPL).
      a.port->move_to(a.fb.position, limits_for(ax, as.vmax));
      a.target = clm_position(ax);
      a.has_target = true;
      a.feeding = false;
      return Flow::next;
    case Op::fak: {
      const Micro f = *value(in.n[1], t);
      if (f <= 0 || f >= 10 * micro_one) {
        fail(t, static_cast<int>(ClmError::variable_value), "FAK factor must be 0 < f < 10");
        return Flow::halt;
      }
      a.fak = f;
      return Flow::next;
    }
    case Op::hom:
      return start_homing(ax, t) ? Flow::next : Flow::halt;
    case Op::pbk: {
      // PBK brakes with the current deceleration and discards the rest of the motion (§5.7 PBK):
      // the target becomes the point where that braking ends, so a POI that follows adds to it
      // and runs on from the braking without a stop (vector 33: decel distance + 50 IU, a
      // continuous transition from 99.9 % to 10 %).
      const double v = a.fb.command_velocity;
      a.held = a.con = false;
      if (!a.fb.busy || v == 0.0) {
        a.port->stop();
        a.has_target = a.feeding = false;
        return Flow::next;
      }
      const MoveLimits l = limits_for(ax, std::abs(v));
      double d = v * v / (2.0 * l.acceleration);
      if (std::isfinite(l.jerk)) d += std::abs(v) * (l.acceleration / l.jerk) / 2.0;  // the jerk ramp
      a.target = a.fb.command_position + a.base + a.sac + wheel_offset(ax) + (v > 0.0 ? d : -d);
      a.has_target = a.feeding = true;
      a.port->move_to(raw_of(ax, a.target), l);
      return Flow::next;
    }
    case Op::poa:
    case Op::psa:
    case Op::poi:
    case Op::psi: {
      const bool absolute = in.op == Op::poa || in.op == Op::psa;
      const bool settle = in.op == Op::psa || in.op == Op::psi;
      // A feed suspended by RMI (task 2's offset move runs) is not reached until it resumes.
      if (k.phase == 1) {
        if (!reached(ax) || (a.rmi_suspended && t != 2)) return Flow::wait;
        if (ax == 1 && srp_.task == t && settle) {
          srp_.measuring = false;
          if (srp_.missed) {
            // SRP: no mark in the window: continue at the line in Vbase+5
            srp_.missed = false;
            Num target;
            target.var = static_cast<std::int16_t>(srp_.base + 5);
            auto line = integer(target, t, 0, 2999);
            if (!line) return Flow::halt;
            k.jump_to = *line;
            return Flow::jump;
          }
        }
        return Flow::next;
      }
      auto len = length(in.n[1], t);
      auto v = permille(in.n[2], 0);
      if (!len || !v) return Flow::halt;
      double l = to_double(static_cast<Micro>(static_cast<i128>(*len) * a.fak / micro_one));
      if (ax == 1 && srp_.mode == 1 && !absolute) {
        l += srp_.correction;  // SRP mode 1: the correction measured on the previous PSI
        srp_.correction = 0.0;
      }
      // §7.12: POI/PSI of the flying cutoff carriage always run at Vmax.
      double velocity = ax == 1 && flying_cutoff() ? as.vmax : feed_velocity(ax, *v);
      a.feed_permille = *v;
      double target = 0.0;
      if (absolute) {
        if (!homed(ax)) {
          fail(t, axis_code(ClmError::not_homed, ax), fmt::format("{} on axis {} before homing", mnemonic(in.op), ax));
          return Flow::halt;
        }
        target = l;
        if (as.motion == MotionType::rotary_table) {
          const double m = as.modulo > 0.0 ? as.modulo : as.feed_constant;
          const double cur = clm_position(ax);
          const double cur_mod = std::fmod(std::fmod(cur, m) + m, m);
          double d = std::fmod(std::fmod(l, m) + m, m) - cur_mod;
          const int path = a.rtm == 0 ? (as.modulo_path == 1 ? 1 : 2) : a.rtm;
          if (path == 1) {
            if (d > m / 2) d -= m;
            if (d < -m / 2) d += m;
          } else if (d < 0) {
            d += m;  // programmed direction [decided]: positive
          }
          target = cur + d;
        }
      } else if (t == 2 && a.rmi_offset_pending) {
        // RMI: the offset move from the raster position; velocity 000 keeps the feed velocity
        target = a.rmi_base + l;
        if (*v == 0) velocity = a.velocity;
        a.rmi_offset_pending = false;
      } else {
        target = (a.has_target ? a.target : clm_position(ax)) + l;
      }
      if (!command_move(ax, target, velocity, t)) return Flow::halt;
      if (ax == 1 && srp_.mode != 0 && in.op == Op::psi) {
        // SRP: this PSI measures the print mark (the flag and, in mode 3, Vbase+0 restart)
        srp_.measuring = true;
        srp_.missed = false;
        srp_.task = t;
        srp_.start = clm_position(1);
        srp_.raster_last = image_.bit(sys::raster1);
        image_.set_byte(srp_.flag, static_cast<std::uint8_t>(image_.byte(srp_.flag) & ~0x10U));
        if (srp_.mode == 3) vars_[static_cast<std::size_t>(srp_.base)] = 0;
      }
      if (!settle) return Flow::next;
      k.phase = 1;
      k.aux = 0;
      return Flow::wait;
    }
    case Op::rep: {
      auto line = integer(in.n[0], t, 0, 2999);
      if (!line) return Flow::halt;
      if (last_srm_axis_ != 0 && last_srm_axis_ != ax) {
        fail(t, static_cast<int>(ClmError::rep_command),
             fmt::format("REP axis {} differs from SRM axis {}", ax, last_srm_axis_));
        return Flow::halt;
      }
      const Micro d = *value(in.n[2], t);
      a.rep = true;
      a.rep_line = *line;
      a.rep_distance = std::abs(to_double(d));
      return Flow::next;
    }
    case Op::rmi: {
      if (t != 2) {
        fail(t, static_cast<int>(ClmError::invalid_program_command), "RMI runs in task 2 only");
        return Flow::halt;
      }
      auto m = integer(in.n[1], t, 0, 1);
      if (!m) return Flow::halt;
      if (*m == 1) {
        if (a.rmi_suspended) {
          a.rmi_suspended = false;
          if (!command_move(ax, a.rmi_saved_target, a.velocity, t)) return Flow::halt;
        }
        return Flow::next;
      }
      const bool in_now = image_.bit(in.bit);
      if (k.phase == 0) {
        k.phase = 1;
        k.aux = in_now ? 1 : 0;
        return Flow::wait;
      }
      const bool edge = in_now && k.aux == 0;
      k.aux = in_now ? 1 : 0;
      if (!edge) return Flow::wait;
      a.rmi_base = clm_position(ax);
      a.latched = a.rmi_base;
      a.rmi_suspended = a.has_target && a.feeding;
      a.rmi_saved_target = a.target;
      a.rmi_offset_pending = true;
      return Flow::next;
    }
    case Op::rtm: {
      auto m = integer(in.n[1], t, 0, 9);
      if (!m) return Flow::halt;
      if (as.motion != MotionType::rotary_table) {
        fail(t, static_cast<int>(ClmError::invalid_program_command), "RTM needs a rotary table axis (Ax00)");
        return Flow::halt;
      }
      if (!homed(ax)) {
        fail(t, axis_code(ClmError::not_homed, ax), "RTM before homing");
        return Flow::halt;
      }
      if (*m <= 2) a.rtm = *m;
      return Flow::next;
    }
    case Op::sac: {
      auto m = integer(in.n[1], t, 0, 9);
      if (!m) return Flow::halt;
      const double v = to_double(*value(in.n[2], t));
      if (as.encoder_type == 3 || (*m != 0 && *m != 1 && *m != 9)) {
        fail(t, static_cast<int>(ClmError::sac_command), "SAC on a controlled axis or with a mode other than 0/1/9");
        return Flow::halt;
      }
      if (!reached(ax)) return Flow::wait;  // only while "position reached"
      const double pos = clm_position(ax);
      if (as.motion == MotionType::rotary) {
        if (!homed(ax)) {
          if (*m != 9) {
            a.base += v - pos;  // set actual = value and home the axis
            a.homed = true;
          }
        } else if (*m == 0) {
          a.sac += v;
        } else if (*m == 1) {
          a.sac += v - pos;
        } else {
          a.homed = false;
          a.sac = 0.0;
          a.base -= clm_position(ax);
        }
      } else {
        if (!homed(ax)) {
          if (*m != 9) {
            fail(t, axis_code(ClmError::not_homed, ax), "SAC on a linear axis before homing");
            return Flow::halt;
          }
        } else if (*m == 0) {
          a.sac += v;
        } else if (*m == 1) {
          a.sac += v - pos;
        }
      }
      if (a.has_target) a.target = clm_position(ax) + (a.target - pos);
      return Flow::next;
    }
    case Op::srm: {
      if (k.phase == 1) {
        if (a.srm) return Flow::wait;
        if (a.srm_rep_hit) {
          a.srm_rep_hit = false;
          a.rep = false;
          k.jump_to = a.rep_line;
          return Flow::jump;
        }
        return Flow::next;
      }
      auto off = length(in.n[1], t);
      auto v = integer(in.n[2], t, -999, 999);
      if (!off || !v) return Flow::halt;
      a.velocity = feed_velocity(ax, std::abs(*v));
      a.srm = true;
      a.srm_rep_hit = false;
      a.srm_input = in.bit;
      a.srm_input_last = image_.bit(in.bit);
      a.srm_offset = to_double(*off);
      a.srm_start = clm_position(ax);
      a.has_target = a.feeding = false;
      last_srm_axis_ = ax;
      const double vel = *v < 0 ? -a.velocity : a.velocity;
      a.port->run(vel * a.input_override, limits_for(ax, vel));
      k.phase = 1;
      return Flow::wait;
    }
    case Op::vcc: {
      auto l = length(in.n[1], t);
      auto v = permille(in.n[2], 0);
      auto m = integer(in.n[3], t, 0, 1);
      if (!l || !v || !m) return Flow::halt;
      if (as.motion == MotionType::rotary_table && *l < 0) {
        fail(t, static_cast<int>(ClmError::vcc_command), "VCC with a negative switching point on a rotary table");
        return Flow::halt;
      }
      if (*m == 1 && !homed(ax)) {
        fail(t, axis_code(ClmError::not_homed, ax), "VCC mode 1 before homing");
        return Flow::halt;
      }
      if (!a.has_target || !a.feeding) return Flow::next;  // no non-blocking move running: skipped
      const double dir = a.target >= a.move_start ? 1.0 : -1.0;
      const double nv = feed_velocity(ax, *v);
      const double pos = clm_position(ax);
      bool trigger = false;
      if (*m == 0) {
        const double at = std::abs(to_double(*l));
        if (at >= std::abs(a.target - a.move_start)) return Flow::next;  // beyond the move: line skipped
        trigger = (pos - a.move_start) * dir >= at;
      } else {
        const double at = to_double(*l);
        const double acc = limits_for(ax, nv).acceleration;
        const double vcur = std::abs(a.fb.velocity);
        const double brake = vcur > nv ? (vcur * vcur - nv * nv) / (2.0 * acc) : 0.0;
        trigger = (at - pos) * dir <= brake;
      }
      if (!trigger) return Flow::wait;
      a.velocity = nv;
      if (!a.held) a.port->move_to(raw_of(ax, a.target), limits_for(ax, nv));
      return Flow::next;
    }
    case Op::veo: {
      auto s = integer(in.n[1], t, 0, 9);
      auto v = permille(in.n[3], 0);
      auto lim = integer(in.n[4], t, 0, 1);
      if (!s || !v || !lim) return Flow::halt;
      if (*s == 5 || *s == 6) {
        // 5 = master encoder 1 (§5.7); 6 = master encoder 2 [decided: the second encoder, as 5]
        if (*s == 5 ? !master_available() : !master2_available()) {
          fail(t, static_cast<int>(ClmError::invalid_program_command),
               *s == 5 ? "VEO source 5 needs master encoder 1 (C002 > 0 and an encoder attached)"
                       : "VEO source 6 needs master encoder 2 (C006 > 0 and an encoder attached)");
          return Flow::halt;
        }
        a.override_master = true;
        a.override_encoder = *s == 5 ? 1 : 2;
        a.master_override = encoder_override(ax);
        a.override_limit = *lim == 1;
        return Flow::next;
      }
      if (*s == 0) {
        // [decided] source 0 = off: the VEO is cancelled, the B017 override inputs act again
        a.override_master = false;
        a.override_permille = 1000;
        a.override_limit = false;
        return Flow::next;
      }
      if (*s != 4) {
        fail(t, static_cast<int>(ClmError::invalid_program_command),
             fmt::format("VEO source {}: not documented (0 = off, 4 = value from the command, 5 = master encoder 1, "
                         "6 = master encoder 2)",
                         *s));
        return Flow::halt;
      }
      a.override_master = false;
      a.override_permille = *v;
      a.override_limit = *lim == 1;
      return Flow::next;
    }
    default:
      fail(t, static_cast<int>(ClmError::invalid_program_command), "command not executable");
      return Flow::halt;
  }
}

}  // namespace hil::controllers::clm14
