// SPDX-License-Identifier: MIT
#include "hil/drives/stepdir/stepdir_drive.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace hil::drives::stepdir {

using hil::stepdir::Ip247Error;
using hil::stepdir::PlannerMode;

namespace {
constexpr std::int64_t far_away = std::int64_t{1} << 50;  // "keep going" target for homing moves
}

StepDirDrive::StepDirDrive(std::string name, const StepDirConfig& config,
                           std::shared_ptr<const hil::stepdir::Ip247Ramp> ramp, gpio::LineBank& outputs,
                           gpio::LineBank* inputs, gpio::EdgeSink& sink)
    : name_(std::move(name)),
      cfg_(config),
      planner_(config.timing, std::move(ramp), config.backlash_steps, {out_step, out_dir}),
      out_(outputs),
      in_(inputs),
      sink_(sink) {
  planner_.set_mode(cfg_.profile);
  int i = 0;
  if (cfg_.ready) idx_ready_ = i++;
  if (cfg_.limit_start) idx_lstart_ = i++;
  if (cfg_.limit_end) idx_lend_ = i++;
  if (cfg_.reference) idx_ref_ = i++;
  if (!in_) idx_ready_ = idx_lstart_ = idx_lend_ = idx_ref_ = -1;
  // Idle levels: step idle, dir forward, reset asserted (no power until enabled).
  (void)out_.set_value(out_step, cfg_.timing.step_idle_level());
  (void)out_.set_value(out_dir, cfg_.timing.dir_forward_level);
  if (cfg_.enable) (void)out_.set_value(out_enable, true);
  fb_.state = DriveState::switch_on_disabled;
  batch_.reserve(4096);
}

DriveCapabilities StepDirDrive::capabilities() const noexcept {
  DriveCapabilities c;
  c.closed_loop = false;
  c.velocity_mode = false;
  c.homing = true;
  // The `ip247` profile generates the trajectory itself (the module's exponential ramp to each
  // target at the move's own speed): the motion core hands it DriveCommand::move and supervises
  // the end position only.
  c.drive_profile = cfg_.profile == PlannerMode::ramp;
  // The limit and reference inputs, as CiA 402 0x60FD bits (a digital input of the axis).
  c.digital_inputs = idx_lstart_ >= 0 || idx_lend_ >= 0 || idx_ref_ >= 0;
  return c;
}

int StepDirDrive::pattern_counter() const noexcept {
  const std::int64_t p = cfg_.homing.patterns;
  return static_cast<int>(((planner_.motor_position() - phase_base_) % p + p) % p);
}

void StepDirDrive::raise(Ip247Error e, std::string what) {
  if (fb_.fault) return;  // latched: the first error stays until acknowledged
  fb_.fault.code = make_error_code(e);
  fb_.fault.text = fmt::format("{}: {}", name_, what);
  if (homing_ != HomingPhase::idle) finish_homing(false);
}

void StepDirDrive::sample_inputs() {
  auto get = [&](int idx, bool def) {
    if (idx < 0) return def;
    auto v = in_->get_value(static_cast<std::size_t>(idx));
    if (!v) {
      ++input_errors_;
      return def;
    }
    return *v;
  };
  inputs_.ready = get(idx_ready_, true);
  // NO: actuated = 1. NC: actuated = 0, so a broken wire reads as actuated (overrun).
  const bool nc = cfg_.limits_normally_closed;
  inputs_.limit_start = idx_lstart_ >= 0 && (get(idx_lstart_, nc) != nc);
  inputs_.limit_end = idx_lend_ >= 0 && (get(idx_lend_, nc) != nc);
  inputs_.cam = get(idx_ref_, false);
  // 0x60FD layout: the start limit is the negative one, the end limit the positive one.
  fb_.digital_inputs = (inputs_.limit_start ? digital_input::negative_limit : 0U) |
                       (inputs_.limit_end ? digital_input::positive_limit : 0U) |
                       (inputs_.cam ? digital_input::home_switch : 0U);
}

bool StepDirDrive::limit_actuated(int direction) const noexcept {
  return direction > 0 ? inputs_.limit_end : (direction < 0 ? inputs_.limit_start : false);
}

void StepDirDrive::check_limits(int travel) {
  // Unlock: moving away from the locked side with its switch released.
  if (lock_dir_ != 0 && travel == -lock_dir_ && !limit_actuated(lock_dir_)) lock_dir_ = 0;
  if (travel == 0 || !limit_actuated(travel)) return;
  if (homing_ != HomingPhase::idle && travel == -cfg_.homing.direction) return;  // reversal switch of the run
  lock_dir_ = travel;
  if (planner_.mode() == PlannerMode::ramp) {
    planner_.halt();
  } else {
    planner_.stop_now();
  }
  raise(travel > 0 ? Ip247Error::limit_end_overrun : Ip247Error::limit_start_overrun,
        fmt::format("hardware limit {} actuated while moving {} at position {}: move the other way to release it",
                    travel > 0 ? "end" : "start", travel > 0 ? "forward" : "backward", planner_.position()));
}

void StepDirDrive::read(const CycleTime& cycle) {
  now_ = cycle.now.time_since_epoch().count();
  sample_inputs();
  // Ready (BB) handling.
  if (inputs_.ready && !prev_ready_) phase_base_ = planner_.motor_position();  // drive counter is 0 at power-on
  prev_ready_ = inputs_.ready;
  if (power_ == Power::wait_ready) {
    if (inputs_.ready) {
      power_ = Power::enabled;
    } else if (now_ >= ready_deadline_) {
      raise(Ip247Error::power_section_off, "ready input stayed low after the reset pulse: switch the power section on");
    }
  } else if (power_ == Power::enabled && !inputs_.ready) {
    planner_.stop_now();
    fb_.referenced = false;  // synchronisation lost
    raise(Ip247Error::power_section_off, "ready input went low: power section off, synchronisation lost");
  }
  if (power_ == Power::enabled) check_limits(planner_.moving() ? planner_.direction() : 0);

  const std::int64_t pos = planner_.position();
  fb_.position_inc = pos;
  fb_.velocity_inc_per_s = cycle.period.count() > 0
                               ? static_cast<double>(pos - last_pos_) * 1e9 / static_cast<double>(cycle.period.count())
                               : 0.0;
  last_pos_ = pos;
  // A finished run still shows as active in the first image with the new position, so the motion
  // core (holding at actual while homing) takes the new position before it supervises again.
  fb_.homing_active = homing_ != HomingPhase::idle || homing_tail_;
  homing_tail_ = false;
  if (fb_.fault) {
    fb_.state = DriveState::fault;
  } else {
    switch (power_) {
      case Power::disabled:
        fb_.state = DriveState::switch_on_disabled;
        break;
      case Power::resetting:
        fb_.state = DriveState::ready_to_switch_on;
        break;
      case Power::wait_ready:
        fb_.state = DriveState::switched_on;
        break;
      case Power::enabled:
        fb_.state = DriveState::operation_enabled;
        break;
    }
  }
}

void StepDirDrive::emit_enable(std::int64_t t, bool level) {
  if (!cfg_.enable || enable_level_ == level) return;
  enable_level_ = level;
  batch_.push_back({t, out_enable, level});
}

void StepDirDrive::start_reset_pulse(std::int64_t now) {
  emit_enable(now, true);
  reset_release_at_ = now + cfg_.reset_pulse.count();
  phase_base_ = planner_.motor_position();  // module counter set to 0 with the pulse
}

bool StepDirDrive::request(DriveRequest r) {
  switch (r) {
    case DriveRequest::enable:
      if (power_ == Power::disabled && !fb_.fault) {
        power_ = Power::resetting;
        reset_release_at_ = -2;  // pulse starts at the next write
      }
      return true;
    case DriveRequest::disable:
    case DriveRequest::quick_stop:
      if (homing_ != HomingPhase::idle) finish_homing(false);
      planner_.stop_now();
      power_ = Power::disabled;
      reset_release_at_ = -1;
      return true;
    case DriveRequest::fault_reset:
      if (fb_.fault && (power_ != Power::enabled || inputs_.ready)) {
        fb_.fault = {};
        if (power_ == Power::wait_ready) ready_deadline_ = now_ + cfg_.ready_timeout.count();
      }
      return true;
    case DriveRequest::home:
      if (power_ != Power::enabled || fb_.fault || homing_ != HomingPhase::idle) return false;
      mode_before_homing_ = planner_.mode();
      planner_.set_mode(PlannerMode::ramp);
      fb_.referenced = false;  // starting BA5 deletes the reference point
      homing_ = cfg_.homing.sync ? HomingPhase::reset_pulse : HomingPhase::away;
      homing_braking_ = false;
      single_steps_ = 0;
      reset_release_at_ = homing_ == HomingPhase::reset_pulse ? -2 : -1;
      return true;
  }
  return false;
}

void StepDirDrive::finish_homing(bool ok) {
  planner_.stop_now();
  if (ok) {
    planner_.set_position(cfg_.homing.coordinate, cfg_.homing.direction);
    last_pos_ = cfg_.homing.coordinate;
    fb_.referenced = true;
    homing_tail_ = true;
    if (lock_dir_ != 0) lock_dir_ = 0;  // passing the cam unlocks (IP247 §2.8)
  }
  homing_ = HomingPhase::idle;
  homing_braking_ = false;
  planner_.set_mode(mode_before_homing_);
}

void StepDirDrive::step_homing(std::int64_t now) {
  const int rd = cfg_.homing.direction;
  const double f_ref = cfg_.homing.speed_hz;
  const double f_ss = cfg_.ramp.f_ss_hz;
  if (homing_braking_) {
    if (planner_.moving()) return;
    homing_braking_ = false;
    homing_ = after_brake_;
  }
  auto brake_to = [&](HomingPhase next) {
    planner_.halt();
    homing_braking_ = true;
    after_brake_ = next;
  };
  switch (homing_) {
    case HomingPhase::idle:
    case HomingPhase::done:
      return;
    case HomingPhase::reset_pulse:
      if (reset_release_at_ == -2) start_reset_pulse(now);
      if (reset_release_at_ < 0) homing_ = HomingPhase::away;  // pulse over
      return;
    case HomingPhase::away:
      if (inputs_.cam && !planner_.moving()) {
        homing_ = HomingPhase::leave_cam;  // SC3: start on the cam
        return;
      }
      if (limit_actuated(-rd)) {  // SC2 or the reversal switch reached
        if (planner_.moving()) {
          brake_to(HomingPhase::search);
        } else {
          homing_ = HomingPhase::search;
        }
        return;
      }
      if (inputs_.cam) {  // SC1: cam met before the limit: reverse at its end
        homing_ = HomingPhase::away_on_cam;
        return;
      }
      planner_.move_to(planner_.position() - rd * far_away, f_ref);
      return;
    case HomingPhase::away_on_cam:
      if (!inputs_.cam) brake_to(HomingPhase::search);
      return;
    case HomingPhase::search:
      if (inputs_.cam) {
        homing_ = HomingPhase::search_on_cam;
        return;
      }
      planner_.move_to(planner_.position() + rd * far_away, f_ref);
      return;
    case HomingPhase::search_on_cam:
      if (!inputs_.cam) brake_to(HomingPhase::creep);
      return;
    case HomingPhase::creep:
      if (inputs_.cam) {
        planner_.stop_now();  // at f_ss: stop at once
        homing_braking_ = true;
        after_brake_ = HomingPhase::leave_cam;
        return;
      }
      planner_.move_to(planner_.position() - rd * far_away, f_ss);
      return;
    case HomingPhase::leave_cam:
      if (planner_.moving() || planner_.target() != planner_.position()) return;  // single step still due
      if (!inputs_.cam) {
        if (cfg_.homing.sync && pattern_counter() != 0) {
          homing_ = HomingPhase::sync;
        } else {
          finish_homing(true);
        }
        return;
      }
      if (single_steps_ >= cfg_.homing.cam_watchdog_steps) {
        raise(Ip247Error::reference_cam_defective,
              fmt::format("reference cam not left within {} single steps: check the cam and its wiring",
                          cfg_.homing.cam_watchdog_steps));
        return;
      }
      ++single_steps_;
      planner_.move_to(planner_.position() + rd, f_ss);
      return;
    case HomingPhase::sync:
      if (planner_.moving() || planner_.target() != planner_.position()) return;
      if (pattern_counter() == 0) {
        finish_homing(true);
        return;
      }
      planner_.move_to(planner_.position() + rd, f_ss);
      return;
  }
}

double StepDirDrive::move_frequency_hz(double velocity_inc_per_s) const noexcept {
  // One increment is one step: the move's speed in inc/s is its pulse frequency. move_to() clamps
  // it to [f_ss, fmax] (a speed outside is the IP247's warning 7; the move still runs).
  const double f = std::fabs(velocity_inc_per_s);
  return f > 0.0 ? f : cfg_.ramp.f_max_hz;
}

std::int64_t StepDirDrive::move_goal(const DriveMove& m, std::int64_t pos) const noexcept {
  switch (m.kind) {
    case DriveMove::Kind::position:
      return m.target_inc;
    case DriveMove::Kind::velocity:
      return m.velocity_inc_per_s > 0.0 ? pos + far_away : (m.velocity_inc_per_s < 0.0 ? pos - far_away : pos);
    case DriveMove::Kind::hold:
      break;
  }
  return pos;
}

void StepDirDrive::ramp_to(const DriveMove& m, bool blocked) {
  const bool new_move = m.id != move_id_;
  move_id_ = m.id;
  if (blocked) {
    // Held back by the direction lock or a limit fault: the limit check has braked the planner.
    if (planner_.moving()) planner_.halt();
    return;
  }
  const std::int64_t pos = planner_.position();
  switch (m.kind) {
    case DriveMove::Kind::hold:
      if (new_move && planner_.moving()) planner_.halt();  // brake along the ramp
      return;
    case DriveMove::Kind::position:
      // The programmed speed reaches the pulse train: f = the move's velocity in steps/s.
      // Only a new move starts the planner (a move id the drive has run, e.g. after a homing run
      // re-referenced the planner, never moves it again).
      if (new_move) (void)planner_.move_to(m.target_inc, move_frequency_hz(m.velocity_inc_per_s));
      return;
    case DriveMove::Kind::velocity:
      if (m.velocity_inc_per_s == 0.0) {
        if (planner_.moving()) planner_.halt();
      } else if (new_move) {
        (void)planner_.move_to(move_goal(m, pos), move_frequency_hz(m.velocity_inc_per_s));
      }
      return;
  }
}

void StepDirDrive::write(const CycleTime& cycle, const DriveCommand& command) {
  const std::int64_t now = cycle.now.time_since_epoch().count();
  const std::int64_t horizon = now + cycle.period.count();
  now_ = now;
  batch_.clear();
  // Power: reset pulse on enable, then wait for ready.
  if (power_ == Power::disabled) {
    emit_enable(now, true);
  } else if (power_ == Power::resetting && reset_release_at_ == -2) {
    start_reset_pulse(now);
  }
  if (reset_release_at_ >= 0 && reset_release_at_ <= horizon) {
    emit_enable(reset_release_at_, false);
    reset_release_at_ = -1;
    if (power_ == Power::resetting) {
      power_ = Power::wait_ready;
      ready_deadline_ = horizon + cfg_.ready_timeout.count();
    }
  }

  const bool can_move = power_ == Power::enabled && !fb_.fault;
  if (!can_move) {
    planner_.stop_now();
  } else if (homing_ != HomingPhase::idle) {
    step_homing(now);
  } else {
    const bool profile = planner_.mode() == PlannerMode::ramp && command.move.id != 0;
    std::int64_t target = command.position_inc;
    const std::int64_t pos = planner_.position();
    if (profile) target = move_goal(command.move, pos);
    const int about = target > pos ? 1 : (target < pos ? -1 : 0);
    bool blocked = false;
    if (about != 0 && about == lock_dir_) {
      blocked = true;  // direction locked after a limit overrun
    } else if (about != 0) {
      check_limits(about);  // moving or about to move toward an actuated switch
      blocked = static_cast<bool>(fb_.fault);
    }
    if (blocked) target = pos;
    if (planner_.mode() == PlannerMode::follow) {
      planner_.follow(target);
    } else if (!profile) {
      // A raw position command (no move from a motion core): nothing says how fast, so fmax.
      if (target != planner_.target()) (void)planner_.move_to(target, cfg_.ramp.f_max_hz);
    } else {
      ramp_to(command.move, blocked);
    }
  }
  const std::size_t fixed = batch_.size();
  if (planner_.plan(now, horizon, batch_) == hil::stepdir::PlanStatus::lagging) ++lag_cycles_;
  if (fixed != 0 && batch_.size() != fixed) {
    std::stable_sort(batch_.begin(), batch_.end(),
                     [](const gpio::Edge& a, const gpio::Edge& b) { return a.t_ns < b.t_ns; });
  }
  sink_.output(batch_);
}

}  // namespace hil::drives::stepdir
