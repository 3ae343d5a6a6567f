// SPDX-License-Identifier: MIT
// Step 7: the axis cycle. drive.read -> drive checks -> state machine -> trajectory sample ->
// backlash -> supervision -> drive.write. Commands only plan; update() executes.
#include "hil/motion/axis.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "hil/motion/plan.hpp"

namespace hil::motion {
namespace {

// A move's own limits may only lower the configured (machine) limits, and to no less than a
// billionth of them: smaller ones (found by fuzzing: 1e-270 units/s, denormal accelerations) make
// the planner's squares and quotients underflow, and a move would then jump to its target in one
// cycle.
constexpr double min_limit_ratio = 1e-9;

bool valid_limits(const Limits& l, const Limits& machine) {
  const double min_jerk =
      machine.jerk_limited() ? machine.jerk * min_limit_ratio : machine.acceleration * min_limit_ratio;
  return std::isfinite(l.velocity) && l.velocity >= machine.velocity * min_limit_ratio &&
         std::isfinite(l.acceleration) && l.acceleration >= machine.acceleration * min_limit_ratio &&
         l.jerk >= min_jerk && l.velocity <= machine.velocity && l.acceleration <= machine.acceleration &&
         l.jerk <= machine.jerk && (l.jerk_limited() || !machine.jerk_limited());
}

// The increment nearest `units` (a position within the soft limits) that does not lie beyond
// them: a coarse increment rounded outward would put the axis past a limit (found by fuzzing).
std::int64_t inc_within_soft_limits(double units, const Scaling& scaling, const AxisConfig& c) {
  std::int64_t inc = scaling.to_inc(units);
  if (c.soft_limit_max && scaling.to_units(inc) > *c.soft_limit_max) --inc;
  if (c.soft_limit_min && scaling.to_units(inc) < *c.soft_limit_min) ++inc;
  return inc;
}

bool drive_faulted(const hil::DriveFeedback& fb) {
  return fb.state == hil::DriveState::fault || fb.state == hil::DriveState::fault_reaction_active ||
         static_cast<bool>(fb.fault);
}

Limits upper(const Limits& a, const Limits& b) {
  return Limits{std::max(a.velocity, b.velocity), std::max(a.acceleration, b.acceleration), std::max(a.jerk, b.jerk)};
}

constexpr int kHomingStartCycles = 10;

// Positions and distances must stay far inside int64 increments (and exact in a double).
bool in_range(double units, const Scaling& s) {
  return std::isfinite(units) && std::fabs(units * s.inc_per_unit()) < 1e15;
}

long long to_ms(hil::Duration d) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
}

}  // namespace

Axis::Axis(AxisConfig config, hil::DrivePtr drive)
    : config_(std::move(config)),
      drive_(std::move(drive)),
      scaling_(config_.inc_per_unit, config_.rotary, config_.modulo) {
  active_limits_ = config_.limits;
  entry_limits_ = config_.limits;
  if (auto ok = validate(config_); !ok) {
    status_.state = AxisState::error;
    status_.fault =
        hil::Fault{make_error_code(MotionFault::invalid_command), "invalid axis configuration: " + ok.error()};
  }
  if (!drive_) {
    status_.state = AxisState::error;
    status_.fault =
        hil::Fault{make_error_code(MotionFault::drive_lost), fmt::format("axis '{}': no drive", config_.name)};
  }
}

void Axis::set_drive_move(hil::DriveMove::Kind kind, std::int64_t target_inc, double velocity, const Limits& limits) {
  const double ipu = scaling_.inc_per_unit();
  drive_move_.kind = kind;
  ++drive_move_.id;
  drive_move_.target_inc = target_inc;
  drive_move_.velocity_inc_per_s = velocity * ipu;
  drive_move_.acceleration_inc_per_s2 = limits.acceleration * ipu;
  drive_move_.deceleration_inc_per_s2 = limits.acceleration * ipu;
}

Limits Axis::effective(const std::optional<Limits>& limits) const {
  return limits ? *limits : config_.limits;
}

Limits Axis::quick_stop_limits() const {
  Limits l = config_.limits;
  const double k = config_.quick_stop_deceleration / config_.limits.acceleration;
  l.acceleration = config_.quick_stop_deceleration;
  if (l.jerk_limited()) l.jerk *= k;  // same jerk time as a normal ramp
  return l;
}

std::error_code Axis::check_can_move() const {
  switch (status_.state) {
    case AxisState::standstill:
    case AxisState::moving:
    case AxisState::stopping:
      return {};
    case AxisState::disabled:
    case AxisState::enabling:
      return make_error_code(MotionFault::not_enabled);
    case AxisState::homing:
    case AxisState::error:
      return make_error_code(MotionFault::invalid_command);
  }
  return make_error_code(MotionFault::invalid_command);
}

// ---- commands -------------------------------------------------------------------------------

std::error_code Axis::enable() {
  if (!drive_) return make_error_code(MotionFault::drive_lost);
  switch (status_.state) {
    case AxisState::disabled:
      break;
    case AxisState::error:
      return make_error_code(MotionFault::invalid_command);
    default:
      return {};
  }
  if (!drive_->request(hil::DriveRequest::enable)) return make_error_code(MotionFault::not_enabled);
  status_.state = AxisState::enabling;
  enable_started_ = last_now_;
  return {};
}

std::error_code Axis::disable() {
  if (!drive_) return make_error_code(MotionFault::drive_lost);
  drive_->request(hil::DriveRequest::disable);
  profile_active_ = false;
  mode_ = Mode::hold;
  if (status_.state != AxisState::error) status_.state = AxisState::disabled;
  status_.busy = false;
  return {};
}

std::error_code Axis::reset() {
  if (status_.state != AxisState::error) return {};
  if (!drive_) return make_error_code(MotionFault::drive_lost);
  if (status_.fault.code == make_error_code(MotionFault::invalid_command) && !validate(config_))
    return make_error_code(MotionFault::invalid_command);  // a bad configuration cannot be reset
  const auto& fb = drive_->feedback();
  if (drive_faulted(fb)) drive_->request(hil::DriveRequest::fault_reset);
  if (fb.state == hil::DriveState::operation_enabled && !drive_faulted(fb)) {
    if (profile_active_) {
      status_.state = AxisState::stopping;  // the fault reaction's stop runs to its end
    } else {
      // A software-limit stop left the set-point exactly on the limit: keep it there. After a
      // supervision or drive fault the set-point takes over the actual position (no jump).
      if (status_.fault.code != make_error_code(MotionFault::software_limit)) hold_at_actual();
      supervisor_.hold();
      status_.state = AxisState::standstill;
    }
  } else {
    hold_at_actual();
    profile_active_ = false;
    mode_ = Mode::hold;
    status_.state = AxisState::disabled;
  }
  status_.fault = {};
  return {};
}

std::error_code Axis::home() {
  if (!drive_) return make_error_code(MotionFault::drive_lost);
  if (status_.state == AxisState::disabled || status_.state == AxisState::enabling)
    return make_error_code(MotionFault::not_enabled);
  if (status_.state != AxisState::standstill) return make_error_code(MotionFault::invalid_command);
  if (!drive_->capabilities().homing || !drive_->request(hil::DriveRequest::home))
    return make_error_code(MotionFault::invalid_command);
  status_.state = AxisState::homing;
  status_.busy = true;
  home_cycles_ = 0;
  home_seen_active_ = false;
  profile_active_ = false;
  mode_ = Mode::hold;
  return {};
}

std::error_code Axis::start_position(std::int64_t target_inc, const Limits& limits) {
  const State from{cmd_p_, cmd_v_, cmd_a_, 0.0};
  const Limits entry = upper(entry_limits_, limits);
  if (!config_.rotary && (config_.soft_limit_min || config_.soft_limit_max)) {
    // Reject only if braking ends beyond a limit *and* further out than the axis is now (an
    // axis standing outside its range, e.g. after power-up, may always move back in).
    const double sp = stop_position(from, limits, entry);
    if ((config_.soft_limit_max && sp > *config_.soft_limit_max && sp > from.p) ||
        (config_.soft_limit_min && sp < *config_.soft_limit_min && sp < from.p))
      return make_error_code(MotionFault::software_limit);
  }
  plan_position(from, scaling_.to_units(target_inc), limits, entry, profile_);
  if (drive_profile_) {
    const double approach = target_inc > cmd_inc_ ? 0.0 : target_inc < cmd_inc_ ? -config_.backlash : backlash_goal_;
    set_drive_move(hil::DriveMove::Kind::position, target_inc + scaling_.to_inc_fast(approach), limits.velocity,
                   limits);
  }
  target_inc_ = target_inc;
  active_limits_ = limits;
  entry_limits_ = entry;
  mode_ = Mode::position;
  profile_active_ = true;
  profile_start_ = last_now_;
  profile_hint_ = 0;
  programmed_feed_ = profile_.peak_velocity();
  supervisor_.start_move();
  status_.state = AxisState::moving;
  status_.busy = true;
  status_.in_position = false;
  return {};
}

std::error_code Axis::move_absolute(double position, Direction direction, std::optional<Limits> limits) {
  if (auto ec = check_can_move()) return ec;
  const Limits lim = effective(limits);
  if (!in_range(position, scaling_) || !valid_limits(lim, config_.limits))
    return make_error_code(MotionFault::invalid_command);
  std::int64_t target = 0;
  if (config_.rotary) {
    const int dir = direction == Direction::positive ? 1 : direction == Direction::negative ? -1 : 0;
    target = cmd_inc_ + scaling_.rotary_step(cmd_inc_, position, dir);
  } else {
    if ((config_.soft_limit_max && position > *config_.soft_limit_max) ||
        (config_.soft_limit_min && position < *config_.soft_limit_min))
      return make_error_code(MotionFault::software_limit);
    target = inc_within_soft_limits(position, scaling_, config_);
  }
  if (auto ec = start_position(target, lim)) return ec;
  relative_carry_inc_ = 0.0;
  return {};
}

std::error_code Axis::move_relative(double distance, std::optional<Limits> limits) {
  if (auto ec = check_can_move()) return ec;
  const Limits lim = effective(limits);
  if (!in_range(distance, scaling_) || !valid_limits(lim, config_.limits))
    return make_error_code(MotionFault::invalid_command);
  const std::int64_t base = mode_ == Mode::position ? target_inc_ : cmd_inc_;
  double carry = mode_ == Mode::position || status_.state == AxisState::standstill ? relative_carry_inc_ : 0.0;
  const std::int64_t target = base + scaling_.delta_to_inc(distance, carry);
  if (!config_.rotary) {
    const double t = scaling_.to_units(target);
    if ((config_.soft_limit_max && t > *config_.soft_limit_max) ||
        (config_.soft_limit_min && t < *config_.soft_limit_min))
      return make_error_code(MotionFault::software_limit);
  }
  if (auto ec = start_position(target, lim)) return ec;
  relative_carry_inc_ = carry;
  return {};
}

std::error_code Axis::move_velocity(double velocity, std::optional<Limits> limits) {
  if (auto ec = check_can_move()) return ec;
  Limits lim = effective(limits);
  if (!std::isfinite(velocity) || !valid_limits(lim, config_.limits) || std::fabs(velocity) > lim.velocity)
    return make_error_code(MotionFault::invalid_command);
  if (velocity == 0.0) return stop();
  const State from{cmd_p_, cmd_v_, cmd_a_, 0.0};
  const Limits entry = upper(entry_limits_, lim);
  const std::optional<double> limit =
      config_.rotary ? std::nullopt : (velocity > 0 ? config_.soft_limit_max : config_.soft_limit_min);
  if (limit) {
    // Dynamic software limit (WF 725/726 MD 11/13): plan the stop to land exactly on the limit.
    const bool beyond = velocity > 0 ? cmd_p_ >= *limit : cmd_p_ <= *limit;
    const double sp = stop_position(from, lim, entry);
    const bool cannot_stop = velocity > 0 ? sp > *limit : sp < *limit;
    if (beyond || cannot_stop) return make_error_code(MotionFault::software_limit);
    lim.velocity = std::fabs(velocity);
    const std::int64_t stop_inc = inc_within_soft_limits(*limit, scaling_, config_);
    plan_position(from, scaling_.to_units(stop_inc), lim, entry, profile_);
    mode_ = Mode::velocity_to_limit;
    limit_target_ = *limit;
    target_inc_ = stop_inc;
    if (drive_profile_) set_drive_move(hil::DriveMove::Kind::position, target_inc_, lim.velocity, lim);
  } else {
    plan_velocity(from, velocity, lim, entry, profile_);
    mode_ = Mode::velocity;
    if (drive_profile_) set_drive_move(hil::DriveMove::Kind::velocity, 0, velocity, lim);
  }
  active_limits_ = effective(limits);
  entry_limits_ = entry;
  profile_active_ = true;
  profile_start_ = last_now_;
  profile_hint_ = 0;
  programmed_feed_ = std::max(std::fabs(velocity), std::fabs(cmd_v_));
  relative_carry_inc_ = 0.0;
  supervisor_.start_move();
  status_.state = AxisState::moving;
  status_.busy = true;
  status_.in_position = false;
  return {};
}

std::error_code Axis::jog(int direction) {
  if (direction != 1 && direction != -1) return make_error_code(MotionFault::invalid_command);
  return move_velocity(direction * config_.jog_velocity);
}

void Axis::plan_stop(const Limits& limits, Mode after) {
  const State from{cmd_p_, cmd_v_, cmd_a_, 0.0};
  entry_limits_ = upper(entry_limits_, limits);
  plan_velocity(from, 0.0, limits, entry_limits_, profile_);
  if (drive_profile_) set_drive_move(hil::DriveMove::Kind::hold, 0, 0.0, limits);
  mode_ = after;
  profile_active_ = true;
  profile_start_ = last_now_;
  profile_hint_ = 0;
  supervisor_.start_move();
  status_.busy = true;
}

std::error_code Axis::stop() {
  switch (status_.state) {
    case AxisState::moving:
    case AxisState::stopping:
      plan_stop(active_limits_, Mode::stopping);
      status_.state = AxisState::stopping;
      return {};
    case AxisState::homing:
      drive_->request(hil::DriveRequest::quick_stop);
      return {};
    default:
      return {};  // at rest, disabled, or already braking in error
  }
}

std::error_code Axis::quick_stop() {
  switch (status_.state) {
    case AxisState::moving:
    case AxisState::stopping:
      plan_stop(quick_stop_limits(), Mode::stopping);
      status_.state = AxisState::stopping;
      return {};
    case AxisState::error:
      if (profile_active_) plan_stop(quick_stop_limits(), Mode::stopping);
      return {};
    case AxisState::homing:
      drive_->request(hil::DriveRequest::quick_stop);
      return {};
    default:
      return {};
  }
}

std::error_code Axis::set_setpoint_offset(double offset) {
  if (!std::isfinite(offset) || (drive_ && drive_->capabilities().drive_profile))
    return make_error_code(MotionFault::invalid_command);
  setpoint_offset_ = offset;
  return {};
}

std::error_code Axis::follow(std::int64_t position_inc, double velocity_inc_per_s, double acceleration_inc_per_s2) {
  if (auto ec = check_can_move()) return ec;
  if (drive_profile_ || !std::isfinite(velocity_inc_per_s) || !std::isfinite(acceleration_inc_per_s2))
    return make_error_code(MotionFault::invalid_command);
  if (mode_ != Mode::external) {
    supervisor_.start_move();
    profile_start_ = last_now_;
  }
  mode_ = Mode::external;
  profile_active_ = true;
  target_inc_ = position_inc;
  ext_v_inc_ = velocity_inc_per_s;
  ext_a_inc_ = acceleration_inc_per_s2;
  relative_carry_inc_ = 0.0;
  active_limits_ = config_.limits;
  // A stop from the coupled state may have to start outside the axis' limits (the coupling
  // monitor watches them): plan it from an envelope that contains the state.
  {
    const double upi = 1.0 / scaling_.inc_per_unit();
    entry_limits_ =
        Limits{std::max(config_.limits.velocity, std::fabs(velocity_inc_per_s) * upi),
               std::max(config_.limits.acceleration, std::fabs(acceleration_inc_per_s2) * upi), config_.limits.jerk};
  }
  programmed_feed_ = std::fabs(velocity_inc_per_s) / scaling_.inc_per_unit();
  status_.state = AxisState::moving;
  status_.busy = true;
  status_.in_position = false;
  return {};
}

void Axis::raise_fault(hil::Fault fault) {
  if (status_.state == AxisState::error || status_.state == AxisState::disabled) return;
  raise(fault.code, std::move(fault.text));
  react_to_fault();
}

// ---- cycle ----------------------------------------------------------------------------------

void Axis::raise(std::error_code code, std::string text) {
  if (status_.state == AxisState::error) return;  // keep the first fault
  status_.state = AxisState::error;
  status_.fault = hil::Fault{code, std::move(text)};
  status_.in_position = false;
}

void Axis::react_to_fault() {
  if (cmd_v_ == 0.0 && cmd_a_ == 0.0 && config_.reaction != FaultReaction::disable) {
    profile_active_ = false;  // already at rest: hold the set-point
    mode_ = Mode::hold;
    status_.busy = false;
    // A drive running its own profile may still be on its way: it brakes (CiA 402 halt).
    if (drive_profile_) set_drive_move(hil::DriveMove::Kind::hold, 0, 0.0, quick_stop_limits());
    return;
  }
  switch (config_.reaction) {
    case FaultReaction::quick_stop:
      plan_stop(quick_stop_limits(), Mode::stopping);
      break;
    case FaultReaction::stop:
      plan_stop(active_limits_, Mode::stopping);
      break;
    case FaultReaction::disable:
      drive_->request(hil::DriveRequest::disable);
      hold_at_actual();
      break;
  }
}

void Axis::hold_at_actual() {
  const auto& fb = drive_->feedback();
  profile_active_ = false;
  mode_ = Mode::hold;
  cmd_inc_ = fb.position_inc - scaling_.to_inc_fast(backlash_offset_);
  cmd_p_ = scaling_.to_units(cmd_inc_);
  cmd_v_ = 0.0;
  cmd_a_ = 0.0;
  target_inc_ = cmd_inc_;
  relative_carry_inc_ = 0.0;
  entry_limits_ = config_.limits;
  last_drive_cmd_inc_ = fb.position_inc;  // the set-point is the actual: no following error
  status_.busy = false;
  if (drive_move_.kind != hil::DriveMove::Kind::hold)
    set_drive_move(hil::DriveMove::Kind::hold, 0, 0.0, quick_stop_limits());
}

void Axis::finish_profile() {
  profile_active_ = false;
  const State& e = profile_.end();
  cmd_v_ = 0.0;
  cmd_a_ = 0.0;
  switch (mode_) {
    case Mode::position:
    case Mode::velocity_to_limit:
      cmd_inc_ = target_inc_;
      cmd_p_ = scaling_.to_units(target_inc_);
      break;
    default:
      cmd_p_ = e.p;
      cmd_inc_ = scaling_.to_inc(e.p);
      target_inc_ = cmd_inc_;
      relative_carry_inc_ = 0.0;
      break;
  }
  const Mode done = mode_;
  mode_ = Mode::hold;
  entry_limits_ = config_.limits;
  status_.busy = false;
  if (status_.state == AxisState::error) return;
  status_.state = AxisState::standstill;
  if (done == Mode::velocity_to_limit) {
    raise(make_error_code(MotionFault::software_limit),
          fmt::format("axis '{}': {} software limit {:.6g} reached; axis stopped on the limit (reset, then move back)",
                      config_.name,
                      config_.soft_limit_max && limit_target_ == *config_.soft_limit_max ? "positive" : "negative",
                      limit_target_));
  }
}

void Axis::step_trajectory(const hil::CycleTime& cycle) {
  if (!profile_active_) return;
  if (mode_ == Mode::external) {
    const double upi = 1.0 / scaling_.inc_per_unit();
    cmd_inc_ = target_inc_;
    cmd_p_ = scaling_.to_units(cmd_inc_);
    cmd_v_ = ext_v_inc_ * upi;
    cmd_a_ = ext_a_inc_ * upi;
    return;
  }
  const double t = hil::to_seconds(cycle.now - profile_start_);
  if (profile_.end().v == 0.0 && t >= profile_.duration()) {
    finish_profile();
    return;
  }
  const State s = profile_.sample(t, profile_hint_);
  cmd_p_ = s.p;
  cmd_v_ = s.v;
  cmd_a_ = s.a;
  cmd_inc_ = scaling_.to_inc_fast(s.p);
}

CycleResult Axis::update(const hil::CycleTime& cycle) {
  if (!drive_) return CycleResult::fault;
  drive_->read(cycle);
  const auto& fb = drive_->feedback();
  if (first_cycle_) {
    first_cycle_ = false;
    drive_profile_ = drive_->capabilities().drive_profile;  // a transport may settle it until the first cycle
    last_now_ = cycle.now;
    hold_at_actual();
    enable_started_ = cycle.now;
  }
  const double upi = 1.0 / scaling_.inc_per_unit();

  // Drive-side faults and staleness (only while the axis expects the drive to be on).
  const AxisState st = status_.state;
  if (st != AxisState::disabled && st != AxisState::error) {
    if (drive_faulted(fb)) {
      raise(make_error_code(MotionFault::drive_fault),
            fmt::format("axis '{}': drive {} reports a fault (state {}): {}", config_.name, drive_->name(),
                        hil::to_string(fb.state), fb.fault.describe()));
      hold_at_actual();
    } else if (fb.age > config_.feedback_timeout) {
      raise(make_error_code(MotionFault::drive_lost),
            fmt::format("axis '{}': feedback from drive {} is {} ms old (feedback_timeout {} ms)", config_.name,
                        drive_->name(), to_ms(fb.age), to_ms(config_.feedback_timeout)));
      react_to_fault();
    } else if (st != AxisState::enabling && fb.state != hil::DriveState::operation_enabled) {
      raise(make_error_code(MotionFault::drive_fault),
            fmt::format("axis '{}': drive {} left operation_enabled (now {})", config_.name, drive_->name(),
                        hil::to_string(fb.state)));
      hold_at_actual();
    }
  }

  switch (status_.state) {
    case AxisState::disabled:
      hold_at_actual();
      break;
    case AxisState::enabling:
      hold_at_actual();
      if (fb.state == hil::DriveState::operation_enabled) {
        status_.state = AxisState::standstill;
        supervisor_.hold();
      } else if (cycle.now - enable_started_ > config_.enable_timeout) {
        raise(make_error_code(MotionFault::not_enabled),
              fmt::format("axis '{}': drive {} did not reach operation_enabled within {} ms (state {})", config_.name,
                          drive_->name(), to_ms(config_.enable_timeout), hil::to_string(fb.state)));
        drive_->request(hil::DriveRequest::disable);
      }
      break;
    case AxisState::homing:
      hold_at_actual();
      status_.busy = true;
      ++home_cycles_;
      if (fb.homing_active) home_seen_active_ = true;
      // Done when homing_active fell again, or (drives that never show it) when the drive is
      // referenced and still not homing after kHomingStartCycles.
      if (!fb.homing_active && (home_seen_active_ || (home_cycles_ > kHomingStartCycles && fb.referenced))) {
        status_.busy = false;
        if (fb.referenced) {
          status_.state = AxisState::standstill;
          supervisor_.hold();
        } else {
          raise(make_error_code(MotionFault::drive_fault),
                fmt::format("axis '{}': homing on drive {} ended without a reference", config_.name, drive_->name()));
        }
      }
      break;
    default:
      step_trajectory(cycle);
      break;
  }

  // Backlash: after a reversal of the commanded motion the drive command carries -backlash
  // (negative approach) or 0 (positive approach), slewed at limits.velocity.
  if (config_.backlash > 0.0) {
    if (cmd_v_ > 1e-9)
      backlash_goal_ = 0.0;
    else if (cmd_v_ < -1e-9)
      backlash_goal_ = -config_.backlash;
    const double dt = std::max(0.0, hil::to_seconds(cycle.now - last_now_));
    const double step = config_.limits.velocity * std::max(dt, hil::to_seconds(cycle.period));
    backlash_offset_ += std::clamp(backlash_goal_ - backlash_offset_, -step, step);
  }
  const std::int64_t drive_cmd = cmd_inc_ + (config_.backlash > 0.0 ? scaling_.to_inc_fast(backlash_offset_) : 0);

  // Following error against the command the drive has had (last cycle's).
  const double fe = static_cast<double>(last_drive_cmd_inc_ - fb.position_inc) * upi;
  status_.following_error = fe;
  const AxisState now_state = status_.state;
  if (now_state == AxisState::standstill || now_state == AxisState::moving || now_state == AxisState::stopping) {
    const std::int64_t tgt =
        profile_active_ && mode_ == Mode::velocity ? drive_cmd : target_inc_ + (drive_cmd - cmd_inc_);
    const double target_error = static_cast<double>(tgt - fb.position_inc) * upi;
    hil::Fault f =
        supervisor_.check(config_, fe, programmed_feed_, profile_active_, target_error, cycle.now, !drive_profile_);
    if (f) {
      raise(f.code, std::move(f.text));
      react_to_fault();
    }
  }

  hil::DriveCommand cmd;
  cmd.mode = hil::CommandMode::position;
  const bool follows_actual = status_.state == AxisState::disabled || status_.state == AxisState::enabling ||
                              status_.state == AxisState::homing;
  // The set-point offset (a drift, its compensation) reaches the drive but is not the command the
  // following error is measured against.
  const std::int64_t offset_inc =
      setpoint_offset_ != 0.0 && !drive_profile_ ? scaling_.to_inc_fast(setpoint_offset_) : 0;
  cmd.position_inc = follows_actual ? fb.position_inc : drive_cmd + offset_inc;
  cmd.velocity_inc_per_s = cmd_v_ * scaling_.inc_per_unit();
  cmd.acceleration_inc_per_s2 = cmd_a_ * scaling_.inc_per_unit();
  cmd.move = drive_move_;
  cmd.digital_outputs = digital_outputs_;
  drive_->write(cycle, cmd);
  last_drive_cmd_inc_ = follows_actual ? fb.position_inc : drive_cmd;
  last_now_ = cycle.now;

  // Status.
  status_.position_inc = fb.position_inc;
  status_.drive_state = fb.state;
  status_.referenced = fb.referenced;
  status_.position = scaling_.to_units_fast(scaling_.wrap_inc(fb.position_inc));
  status_.command_position = scaling_.to_units_fast(scaling_.wrap_inc(cmd_inc_));
  status_.command_inc = cmd_inc_;
  status_.velocity = fb.velocity_inc_per_s * upi;
  status_.command_velocity = cmd_v_;
  status_.command_acceleration = cmd_a_;
  status_.in_position = status_.state == AxisState::standstill && supervisor_.in_position();
  return status_.state == AxisState::error ? CycleResult::fault : CycleResult::ok;
}

}  // namespace hil::motion
