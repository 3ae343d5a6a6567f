// SPDX-License-Identifier: MIT
#include "hil/mocks/sim_drive.hpp"

#include "hil/mocks/key_range.hpp"

#include <cmath>

#include <fmt/format.h>

namespace hil::mocks {

std::expected<SimDriveConfig, ConfigError> parse_sim_drive_config(const YAML::Node& node, const yaml::Where& where) {
  SimDriveConfig c;
  if (!node.IsDefined() || node.IsNull()) return c;
  if (auto k = yaml::check_keys(
          node, where,
          {"transport", "kv", "max_velocity", "velocity_lag", "feedforward", "encoder_step", "initial_position",
           "transition_time", "quick_stop_deceleration", "homing_time", "home_position", "switches"});
      !k)
    return std::unexpected(k.error());
  // Every numeric key has its documented range (docs/scenarios.md, the `sim` drive block).
  auto number = [&](const KeyRange& range, double& out) -> std::expected<void, ConfigError> {
    auto v = yaml::get_double(node, where, range.key);
    if (!v) return std::unexpected(v.error());
    if (!v->has_value()) return {};
    if (auto bad = range.check(**v); !bad.empty())
      return std::unexpected(yaml::error_at(node[std::string(range.key)], where.key(range.key), bad));
    out = **v;
    return {};
  };
  double transition_s = to_seconds(c.transition_time);
  double homing_s = to_seconds(c.homing_time);
  double encoder_step = static_cast<double>(c.plant.encoder_step_inc);
  double home = 0.0;
  for (auto r :
       {number(kv_range, c.plant.kv_per_s), number(max_velocity_range, c.plant.max_velocity_inc_per_s),
        number(velocity_lag_range, c.plant.velocity_lag_s), number(feedforward_range, c.plant.velocity_feedforward),
        number(encoder_step_range, encoder_step), number(position_range, c.plant.initial_position_inc),
        number({"transition_time", 0.0, 60.0, false, "s"}, transition_s),
        number({"quick_stop_deceleration", 0.0, 1e15, true, "inc/s²"}, c.quick_stop_deceleration_inc_per_s2),
        number({"homing_time", 0.0, 3600.0, false, "s"}, homing_s),
        number({"home_position", -1e15, 1e15, false, "inc"}, home)})
    if (!r) return std::unexpected(r.error());
  if (encoder_step != std::floor(encoder_step))
    return std::unexpected(
        yaml::error_at(node["encoder_step"], where.key("encoder_step"), "must be a whole number of increments"));
  c.plant.encoder_step_inc = static_cast<std::int64_t>(encoder_step);
  c.transition_time = from_seconds(transition_s);
  c.homing_time = from_seconds(homing_s);
  if (node["home_position"]) {
    auto whole = yaml::get_int(node, where, "home_position");
    if (!whole) return std::unexpected(whole.error());
    c.home_position_inc = **whole;
  }
  if (const auto sw = node["switches"]) {
    auto parsed = parse_switches(sw, where.key("switches"));
    if (!parsed) return std::unexpected(parsed.error());
    c.switches = *parsed;
  }
  return c;
}

SimDrive::SimDrive(SimDriveConfig config)
    : config_(std::move(config)), name_("sim:" + config_.name), plant_(config_.plant), inputs_(config_.switches) {
  hold_position_inc_ = static_cast<double>(plant_.encoder_position_inc());
  feedback_.position_inc = plant_.encoder_position_inc();
  feedback_.state = state_;
}

DriveCapabilities SimDrive::capabilities() const noexcept {
  return DriveCapabilities{.closed_loop = true,
                           .velocity_mode = true,
                           .homing = true,
                           .min_period = {},
                           .digital_inputs = true,
                           .digital_output_mask = 0xFFFFFFFFu};
}

std::vector<std::string> SimDrive::injectable_faults() const {
  return {"encoder", "not_ready", "following_blowup", "stale_feedback"};
}

bool SimDrive::inject_fault(std::string_view fault, bool active) {
  if (fault == "encoder")
    plant_.inject(PlantFault::encoder, active);
  else if (fault == "not_ready")
    plant_.inject(PlantFault::not_ready, active);
  else if (fault == "following_blowup")
    plant_.inject(PlantFault::following_blowup, active);
  else if (fault == "stale_feedback") {
    if (active && !stale_) stale_since_ = last_;
    stale_ = active;
  } else {
    return false;
  }
  return true;
}

bool SimDrive::request(DriveRequest r) {
  pending_ = r;
  has_pending_ = true;
  return true;
}

void SimDrive::enter_fault(PlantFault f) {
  state_ = DriveState::fault;
  homing_ = false;
  fault_.code = make_error_code(f);
  switch (f) {
    case PlantFault::encoder:
      fault_.text = fmt::format("{}: encoder signal lost; check the encoder cable, then reset the fault", name_);
      break;
    case PlantFault::not_ready:
      fault_.text = fmt::format("{}: power stage not ready; check mains and enable input, then reset", name_);
      break;
    default:
      fault_.text = fmt::format("{}: {}", name_, make_error_code(f).message());
      break;
  }
}

void SimDrive::advance_state(TimePoint now) {
  // Faults the drive itself detects (a jam is not detected here: the motion core's
  // following-error monitor has to catch it).
  const PlantFault pf = plant_.has(PlantFault::encoder)     ? PlantFault::encoder
                        : plant_.has(PlantFault::not_ready) ? PlantFault::not_ready
                                                            : PlantFault::none;
  if (pf != PlantFault::none && state_ != DriveState::fault) enter_fault(pf);

  if (has_pending_) {
    has_pending_ = false;
    switch (pending_) {
      case DriveRequest::enable:
        if (state_ == DriveState::quick_stop_active)
          state_ = DriveState::operation_enabled;  // CiA 402 transition 16
        else if (state_ != DriveState::fault && state_ != DriveState::operation_enabled) {
          pending_ = DriveRequest::enable;
          has_pending_ = true;  // keep walking until enabled
          if (now >= next_transition_) {
            state_ = state_ == DriveState::switch_on_disabled   ? DriveState::ready_to_switch_on
                     : state_ == DriveState::ready_to_switch_on ? DriveState::switched_on
                                                                : DriveState::operation_enabled;
            next_transition_ = now + config_.transition_time;
            if (state_ == DriveState::operation_enabled) {
              has_pending_ = false;
              hold_position_inc_ = static_cast<double>(plant_.encoder_position_inc());
            }
          }
        }
        break;
      case DriveRequest::disable:
        if (state_ != DriveState::fault) state_ = DriveState::switch_on_disabled;
        homing_ = false;
        break;
      case DriveRequest::quick_stop:
        if (state_ == DriveState::operation_enabled) {
          state_ = DriveState::quick_stop_active;
          qs_velocity_ = plant_.velocity_inc_per_s();
          hold_position_inc_ = plant_.position_inc();
          homing_ = false;
        } else if (state_ != DriveState::fault) {
          state_ = DriveState::switch_on_disabled;
        }
        break;
      case DriveRequest::fault_reset:
        if (state_ == DriveState::fault && pf == PlantFault::none) {
          state_ = DriveState::switch_on_disabled;
          fault_ = {};
        }
        break;
      case DriveRequest::home:
        if (state_ == DriveState::operation_enabled) {
          homing_ = true;
          homing_done_ = now + config_.homing_time;
        }
        break;
    }
  }
  if (homing_ && now >= homing_done_) {
    homing_ = false;
    referenced_ = true;
    plant_.set_position(static_cast<double>(config_.home_position_inc));
    hold_position_inc_ = static_cast<double>(config_.home_position_inc);
  }
}

void SimDrive::read(const CycleTime& cycle) {
  if (!started_) {
    started_ = true;
    last_ = cycle.now;
  }
  if (stale_) {  // the image freezes; only its age moves
    feedback_.age = cycle.now - stale_since_;
    return;
  }
  feedback_.position_inc = plant_.encoder_position_inc();
  feedback_.velocity_inc_per_s = plant_.measured_velocity_inc_per_s();
  feedback_.state = state_;
  feedback_.referenced = referenced_;
  feedback_.homing_active = homing_;
  feedback_.fault = fault_;
  feedback_.age = Duration::zero();
  feedback_.digital_inputs = inputs_.inputs(plant_.position_inc());
}

void SimDrive::write(const CycleTime& cycle, const DriveCommand& command) {
  if (!started_) {
    started_ = true;
    last_ = cycle.now;
  }
  digital_outputs_ = command.digital_outputs;
  const bool was_homing = homing_;
  advance_state(cycle.now);
  // The motion core learns of a finished homing run at its next read: hold until then.
  const bool hold = homing_ || was_homing;
  const Duration dt = cycle.now + cycle.period - last_;
  PlantInput in;
  switch (state_) {
    case DriveState::operation_enabled:
      in.powered = true;
      if (hold) {
        in.position_inc = hold_position_inc_;
      } else {
        in.mode = command.mode;
        in.position_inc = static_cast<double>(command.position_inc);
        in.velocity_inc_per_s = command.velocity_inc_per_s;
        hold_position_inc_ = in.position_inc;
      }
      break;
    case DriveState::quick_stop_active: {
      // Drive-side ramp to rest at the quick-stop deceleration, then hold.
      const double dv = config_.quick_stop_deceleration_inc_per_s2 * to_seconds(dt);
      const double v_next = std::abs(qs_velocity_) <= dv ? 0.0 : qs_velocity_ - std::copysign(dv, qs_velocity_);
      hold_position_inc_ += 0.5 * (qs_velocity_ + v_next) * to_seconds(dt);
      qs_velocity_ = v_next;
      in.powered = true;
      in.position_inc = hold_position_inc_;
      in.velocity_inc_per_s = qs_velocity_;
      break;
    }
    default:
      in.powered = false;
      break;
  }
  if (dt > Duration::zero()) plant_.step(dt, in);
  last_ = cycle.now + cycle.period;
}

}  // namespace hil::mocks
