// SPDX-License-Identifier: MIT
#include "hil/mocks/cia402_node.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "hil/cia402/error_code.hpp"

namespace hil::mocks {
namespace {

using cia402::Mode;
namespace cw = cia402::cw;
namespace sw = cia402::sw;

canopen::ObjectDictionary load_od(const Cia402NodeOptions& o) {
  auto d = o.eds_text.empty() ? load_node_eds(cia402_node_eds(), "hil_cia402_drive.eds (compiled in)", o.node)
                              : load_node_eds(o.eds_text, o.eds_name, o.node);
  if (!d) throw std::runtime_error("simulated CiA 402 node: " + d.error().describe());
  return std::move(d->od);
}

/// An object the drive model reads, or `fallback` when the EDS lacks it.
std::int64_t value_or(const canopen::ObjectDictionary& od, std::uint16_t index, std::int64_t fallback) {
  return od.find(index, 0) != nullptr ? od.get_int(index, 0) : fallback;
}

double sign(double v) {
  return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
}

/// One step of a trapezoidal velocity profile toward `target` (positions in increments).
/// Returns true when the target is reached.
bool profile_step(double& pos, double& vel, double target, double vmax, double acc, double dec, double dt) {
  const double dist = target - pos;
  if (std::abs(dist) < 0.5 && std::abs(vel) < dec * dt + 1e-9) {
    pos = target;
    vel = 0.0;
    return true;
  }
  const double v_stop = std::sqrt(2.0 * dec * std::abs(dist));
  const double want = sign(dist) * std::min(vmax, v_stop);
  const double limit = (std::abs(want) > std::abs(vel) && sign(want) == sign(vel) ? acc : dec) * dt;
  vel += std::clamp(want - vel, -limit, limit);
  double step = vel * dt;
  if (sign(step) == sign(dist) && std::abs(step) >= std::abs(dist)) {
    pos = target;
    vel = 0.0;
    return true;
  }
  pos += step;
  return false;
}

}  // namespace

std::expected<canopen::DeviceDescription, ConfigError> load_node_eds(std::string_view eds_text,
                                                                     std::string_view eds_name, canopen::NodeId node) {
  auto d = canopen::parse_eds(eds_text, eds_name, node);
  if (!d) return d;
  std::string missing;
  for (std::uint16_t idx : {std::uint16_t{0x6040}, std::uint16_t{0x6041}})
    if (d->od.find(idx, 0) == nullptr)
      missing +=
          fmt::format("{}0x{:04X} {}", missing.empty() ? "" : ", ", idx, idx == 0x6040 ? "controlword" : "statusword");
  if (!missing.empty()) {
    ConfigError e;
    e.file = std::string(eds_name);
    e.message = fmt::format("cannot simulate a CiA 402 drive from this EDS: it lacks {}", missing);
    return std::unexpected(e);
  }
  return d;
}

can::FilterSet predefined_filters(canopen::NodeId node) {
  can::FilterSet f;
  f.filters = {can::Filter::exact(0x000), can::Filter::exact(0x080), can::Filter::exact(0x600u + node),
               can::Filter::exact(0x700u + node)};
  for (std::uint32_t base : {0x200u, 0x300u, 0x400u, 0x500u}) f.filters.push_back(can::Filter::exact(base + node));
  return f;
}

Cia402Node::Cia402Node(can::Channel& channel, Cia402NodeOptions options)
    : channel_(channel),
      options_(options),
      slave_(
          load_od(options), options.node, [this](const can::Frame& f) { (void)channel_.send(f); }, options.sdo),
      plant_(options.plant),
      inputs_(options.switches) {
  channel_.set_receive_handler([this](const can::Frame& f, TimePoint t) { on_frame(f, t); });
  slave_.on_sync = [this](std::optional<std::uint8_t>, TimePoint now) { on_sync(now); };
  slave_.on_heartbeat = [this](canopen::NodeId, canopen::HeartbeatEvent e, TimePoint now) {
    // Lost master: a drive that is powered stops (CiA 402 fault reaction, error 0x8130, with its
    // EMCY "heartbeat error").
    if (e == canopen::HeartbeatEvent::timeout && state_ != DriveState::fault &&
        state_ != DriveState::fault_reaction_active && state_ != DriveState::switch_on_disabled &&
        state_ != DriveState::not_ready)
      enter_fault(0x8130, now);
  };
  slave_.on_reset = [this](bool application) {
    if (application) {
      state_ = DriveState::not_ready;
      injected_code_ = 0;
      following_offset_ = 0;
    }
  };
  auto& od = slave_.od();
  od.add_observer(0x2100, [this](const canopen::Variable& v) {
    inject_error_code(static_cast<std::uint16_t>(v.as_uint()), last_);
  });
  od.add_observer(0x2101, [this](const canopen::Variable& v) { set_heartbeat_lost(v.as_uint() != 0); });
  od.add_observer(0x2102, [this](const canopen::Variable& v) {
    const auto ms = v.as_uint();
    pending_sdo_delay_ = ms == 0xFFFF ? Duration::max() : std::chrono::milliseconds(ms);
    sdo_delay_pending_ = true;  // applied after this write's own answer went out
  });
  od.add_observer(0x2103,
                  [this](const canopen::Variable& v) { following_offset_ = static_cast<std::int32_t>(v.as_int()); });
}

Cia402Node::~Cia402Node() {
  channel_.set_receive_handler({});
}

std::vector<std::string> Cia402Node::fault_names() {
  return {"encoder",  "not_ready",   "following_blowup", "following_error", "heartbeat_loss", "sdo_timeout",
          "sdo_slow", "overcurrent", "undervoltage",     "overtemperature", "motor_blocked"};
}

bool Cia402Node::inject_fault(std::string_view name, bool active, TimePoint now) {
  if (name == "encoder")
    plant_.inject(PlantFault::encoder, active);
  else if (name == "not_ready")
    plant_.inject(PlantFault::not_ready, active);
  else if (name == "following_blowup")
    plant_.inject(PlantFault::following_blowup, active);
  else if (name == "following_error")
    following_offset_ =
        active ? static_cast<std::int32_t>(std::min<std::int64_t>(slave_.od().get_int(0x6065, 0) * 2 + 1, 1 << 30)) : 0;
  else if (name == "heartbeat_loss")
    set_heartbeat_lost(active);
  else if (name == "sdo_timeout")
    set_sdo_delay(active ? Duration::max() : Duration{});
  else if (name == "sdo_slow")
    set_sdo_delay(active ? Duration(std::chrono::milliseconds(300)) : Duration{});
  else if (name == "overcurrent")
    inject_error_code(active ? 0x2310 : 0, now);
  else if (name == "undervoltage")
    inject_error_code(active ? 0x3220 : 0, now);
  else if (name == "overtemperature")
    inject_error_code(active ? 0x4310 : 0, now);
  else if (name == "motor_blocked")
    inject_error_code(active ? 0x7121 : 0, now);
  else
    return false;
  return true;
}

void Cia402Node::inject_error_code(std::uint16_t code, TimePoint now) {
  injected_code_ = code;
  if (code != 0 && started_ && state_ != DriveState::fault && state_ != DriveState::fault_reaction_active)
    enter_fault(code, now);
}

void Cia402Node::set_heartbeat_lost(bool lost) {
  slave_.set_heartbeat_muted(lost);
}

void Cia402Node::set_sdo_delay(Duration delay) {
  if (delay == Duration::max()) {
    slave_.sdo().set_muted(true);
    slave_.sdo().set_response_delay({});
  } else {
    slave_.sdo().set_muted(false);
    slave_.sdo().set_response_delay(delay);
  }
}

void Cia402Node::start(TimePoint now) {
  last_ = now;
  started_ = true;
  state_ = DriveState::not_ready;
  slave_.start(now);
  run_device(0.0, now);
}

void Cia402Node::on_frame(const can::Frame& f, TimePoint now) {
  if (!started_) return;  // not powered on: deaf
  slave_.on_frame(f, now);
  if (sdo_delay_pending_) {
    sdo_delay_pending_ = false;
    set_sdo_delay(pending_sdo_delay_);
  }
}

void Cia402Node::step(TimePoint now) {
  ++stats_.steps;
  slave_.step(now);
  advance(now);
}

void Cia402Node::on_sync(TimePoint now) {
  ++stats_.syncs;
  advance(now);
}

void Cia402Node::advance(TimePoint now) {
  if (!started_) return;
  const double dt = now > last_ ? to_seconds(now - last_) : 0.0;
  if (now > last_) last_ = now;
  run_device(dt, now);
}

std::uint16_t Cia402Node::active_fault_code() const noexcept {
  if (plant_.has(PlantFault::encoder)) return 0x7305;
  if (plant_.has(PlantFault::not_ready)) return 0x3220;
  return injected_code_;
}

void Cia402Node::enter_fault(std::uint16_t code, TimePoint now) {
  state_ = DriveState::fault_reaction_active;
  fault_code_ = code;
  fault_since_ = now;
  ++stats_.faults;
  pp_active_ = homing_running_ = false;
  slave_.od().set_int(0x603F, 0, code);
  slave_.raise_emcy(code, cia402::error_register_for(code), {}, now);
}

void Cia402Node::run_device(double dt, TimePoint now) {
  auto& od = slave_.od();
  const auto cwv = static_cast<std::uint16_t>(od.get_int(0x6040, 0));
  const bool edge_reset = (cwv & cw::fault_reset) && !(last_cw_ & cw::fault_reset);
  const bool edge_start = (cwv & cw::new_set_point) && !(last_cw_ & cw::new_set_point);
  last_cw_ = cwv;

  // Mode: follows 0x6060 when supported (0x6502); 0x6061 shows the mode in effect.
  const auto requested = static_cast<Mode>(static_cast<std::int8_t>(od.get_int(0x6060, 0)));
  if (requested != mode_) {
    const auto bit = cia402::supported_mode_bit(requested);
    const auto supported = static_cast<std::uint32_t>(value_or(od, 0x6502, 0xFFFFFFFF));
    if (requested == Mode::no_mode || (bit && (supported & *bit))) {
      mode_ = requested;
      pp_active_ = homing_running_ = false;
      homing_attained_ = homing_error_ = false;
      demand_ = static_cast<double>(plant_.encoder_position_inc());
      demand_velocity_ = plant_.velocity_inc_per_s();
    }
  }
  od.set_int(0x6061, 0, static_cast<std::int8_t>(mode_));

  const double actual = static_cast<double>(plant_.encoder_position_inc()) + following_offset_;
  if (const auto code = active_fault_code();
      code != 0 && state_ != DriveState::fault && state_ != DriveState::fault_reaction_active)
    enter_fault(code, now);

  const auto prev = state_;
  const auto qs_option = od.get_int(0x605A, 0);
  const bool qs_stays = qs_option >= 5 && qs_option <= 8;
  switch (state_) {
    case DriveState::not_ready:
      state_ = DriveState::switch_on_disabled;
      break;  // transition 1
    case DriveState::fault_reaction_active:
      if (now - fault_since_ >= options_.fault_reaction_time) state_ = DriveState::fault;  // 14
      break;
    case DriveState::fault:
      if (edge_reset && active_fault_code() == 0) {  // 15 only once the cause is gone
        state_ = DriveState::switch_on_disabled;
        fault_code_ = 0;
        following_since_.reset();
        od.set_int(0x603F, 0, 0);
        slave_.raise_emcy(0x0000, 0, {}, now);
      }
      break;
    default:
      state_ = cia402::next_state(state_, cwv, edge_reset, qs_stays);
      break;
  }
  if (state_ == DriveState::operation_enabled && prev != DriveState::operation_enabled) {
    demand_ = actual;  // take over the actual position: no jump on enable
    demand_velocity_ = 0.0;
    pp_active_ = false;
  }
  if (state_ == DriveState::quick_stop_active && prev != DriveState::quick_stop_active)
    demand_velocity_ = plant_.velocity_inc_per_s();

  PlantInput in;
  in.powered = false;
  bool reached = false, bit12 = false, bit13 = false;
  const double window = static_cast<double>(value_or(od, 0x6067, 10));
  const bool halt = (cwv & cw::halt) != 0;
  const double vmax = std::max(1.0, static_cast<double>(value_or(od, 0x6081, 100'000)));
  const double acc = std::max(1.0, static_cast<double>(value_or(od, 0x6083, 1'000'000)));
  const double dec = std::max(1.0, static_cast<double>(value_or(od, 0x6084, 1'000'000)));
  bool position_controlled = false;
  if (state_ == DriveState::operation_enabled) {
    in.powered = true;
    switch (mode_) {
      case Mode::cyclic_sync_position: {
        demand_ = static_cast<double>(od.get_int(0x607A, 0) + od.get_int(0x60B0, 0));
        in.mode = CommandMode::position;
        in.position_inc = demand_;
        in.velocity_inc_per_s = static_cast<double>(od.get_int(0x60B1, 0));
        reached = std::abs(demand_ - actual) <= window;
        position_controlled = true;
        break;
      }
      case Mode::cyclic_sync_velocity:
        in.mode = CommandMode::velocity;
        in.velocity_inc_per_s = static_cast<double>(od.get_int(0x60FF, 0) + od.get_int(0x60B1, 0));
        reached = true;
        break;
      case Mode::profile_position: {
        if (edge_start && (!pp_active_ || (cwv & cw::change_immediately))) {
          const auto target = static_cast<double>(od.get_int(0x607A, 0));
          pp_target_ = (cwv & cw::relative) ? demand_ + target : target;
          pp_active_ = true;
          setpoint_ack_ = true;
        }
        if (!(cwv & cw::new_set_point)) setpoint_ack_ = false;
        bool done = !pp_active_;
        if (pp_active_) {
          const double goal = halt ? demand_ + demand_velocity_ * std::abs(demand_velocity_) / (2 * dec) : pp_target_;
          done = profile_step(demand_, demand_velocity_, goal, vmax, acc, dec, dt) && !halt;
          if (done) pp_active_ = false;
        }
        in.mode = CommandMode::position;
        in.position_inc = demand_;
        in.velocity_inc_per_s = demand_velocity_;
        reached = done && std::abs(pp_target_ - actual) <= window;
        if (!pp_active_ && !setpoint_ack_ && std::abs(pp_target_ - actual) > window && !halt) reached = false;
        bit12 = setpoint_ack_;
        position_controlled = true;
        break;
      }
      case Mode::profile_velocity: {
        const double target = halt ? 0.0 : static_cast<double>(od.get_int(0x60FF, 0));
        const double rate = (std::abs(target) > std::abs(demand_velocity_) ? acc : dec) * dt;
        demand_velocity_ += std::clamp(target - demand_velocity_, -rate, rate);
        in.mode = CommandMode::velocity;
        in.velocity_inc_per_s = demand_velocity_;
        reached = std::abs(plant_.velocity_inc_per_s() - target) <= std::max(10.0, std::abs(target) * 0.01);
        break;
      }
      case Mode::homing: {
        if (edge_start && !homing_running_) {
          homing_running_ = true;
          homing_attained_ = homing_error_ = false;
          const auto method = od.get_int(0x6098, 0);
          if (method == 35 || method == 37) {
            // Homing on the current position (CiA 402-2 methods 35 / 37): the position becomes the home offset.
            plant_.set_position(static_cast<double>(od.get_int(0x607C, 0)));
            demand_ = static_cast<double>(od.get_int(0x607C, 0));
            homing_attained_ = true;
          } else {
            homing_error_ = true;  // the plant has no switches: other methods cannot complete
          }
          homing_running_ = false;
        }
        in.mode = CommandMode::position;
        in.position_inc = demand_;
        reached = homing_attained_ || homing_error_;
        bit12 = homing_attained_;
        bit13 = homing_error_;
        break;
      }
      default:
        in.mode = CommandMode::position;
        in.position_inc = demand_;
        break;
    }
  } else if (state_ == DriveState::quick_stop_active) {
    in.powered = true;
    const double qsd = std::max(1.0, static_cast<double>(value_or(od, 0x6085, 1'000'000)));
    demand_velocity_ -= std::clamp(demand_velocity_, -qsd * dt, qsd * dt);
    in.mode = CommandMode::velocity;
    in.velocity_inc_per_s = demand_velocity_;
    if (std::abs(demand_velocity_) < 1e-6) {
      reached = true;
      if (!qs_stays) state_ = DriveState::switch_on_disabled;  // transition 12 after the stop
    }
  }
  if (dt > 0) plant_.step(from_seconds(dt), in);

  const double new_actual = static_cast<double>(plant_.encoder_position_inc()) + following_offset_;
  if (position_controlled) {
    const auto fe_window = static_cast<std::uint32_t>(value_or(od, 0x6065, 0xFFFFFFFF));
    if (fe_window != 0xFFFFFFFFu && std::abs(demand_ - new_actual) > static_cast<double>(fe_window)) {
      bit13 = true;
      if (!following_since_) following_since_ = now;
      if (now - *following_since_ >= std::chrono::milliseconds(od.get_int(0x6066, 0))) enter_fault(0x8611, now);
    } else {
      following_since_.reset();
    }
  } else {
    following_since_.reset();
  }
  od.set_int(0x6062, 0, static_cast<std::int64_t>(std::llround(demand_)));
  od.set_int(0x6064, 0, static_cast<std::int64_t>(new_actual));
  od.set_int(0x606C, 0, static_cast<std::int64_t>(std::llround(plant_.measured_velocity_inc_per_s())));
  if (od.find(0x60FD, 0) != nullptr) od.set_int(0x60FD, 0, inputs_.inputs(plant_.position_inc()));
  publish(reached, bit12, bit13);
}

std::uint32_t Cia402Node::digital_outputs() const {
  const auto& od = slave_.od();
  if (od.find(0x60FE, 1) == nullptr) return 0;
  const auto outputs = static_cast<std::uint32_t>(od.get_int(0x60FE, 1));
  return od.find(0x60FE, 2) == nullptr ? outputs : outputs & static_cast<std::uint32_t>(od.get_int(0x60FE, 2));
}

void Cia402Node::publish(bool target_reached, bool bit12, bool bit13) {
  std::uint16_t s = cia402::device_statusword(state_, target_reached);
  if (bit12) s |= sw::op_specific_12;
  if (bit13) s |= sw::op_specific_13;
  slave_.od().set_int(0x6041, 0, s);
}

}  // namespace hil::mocks
