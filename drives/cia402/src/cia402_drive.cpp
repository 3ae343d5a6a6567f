// SPDX-License-Identifier: MIT
#include "hil/cia402/cia402_drive.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "hil/cia402/error_code.hpp"

namespace hil::cia402 {
namespace {
constexpr std::uint16_t k_cw = 0x6040, k_sw = 0x6041, k_mode = 0x6060, k_mode_display = 0x6061, k_error = 0x603F,
                        k_target_pos = 0x607A, k_target_vel = 0x60FF, k_actual_pos = 0x6064, k_actual_vel = 0x606C,
                        k_profile_vel = 0x6081, k_profile_acc = 0x6083, k_profile_dec = 0x6084,
                        k_digital_inputs = 0x60FD, k_digital_outputs = 0x60FE;

std::uint32_t key_of(ObjectKey k) {
  return (std::uint32_t{k.index} << 8) | k.sub;
}

std::int32_t clamp32(double v) {
  if (!std::isfinite(v)) return 0;
  if (v > std::numeric_limits<std::int32_t>::max()) return std::numeric_limits<std::int32_t>::max();
  if (v < std::numeric_limits<std::int32_t>::min()) return std::numeric_limits<std::int32_t>::min();
  return static_cast<std::int32_t>(std::lround(v));
}
/// Profile velocity/acceleration objects are UNSIGNED32; 0 would stop a drive for good.
std::uint32_t profile_value(double v) {
  const double a = std::fabs(v);
  if (!std::isfinite(a) || a >= 4294967295.0) return 0xFFFFFFFFu;
  return std::max<std::uint32_t>(1, static_cast<std::uint32_t>(std::lround(a)));
}
}  // namespace

Cia402Drive::Cia402Drive(Network& network, canopen::NodeId node, DriveOptions options)
    : network_(network), node_(node), options_(std::move(options)) {
  if (options_.name.empty()) options_.name = fmt::format("canopen:{}/{}", network_.channel().name(), node);
  polled_ = options_.layout.polled();
  written_ = options_.layout.written();
  network_.attach(node, this);
}

Cia402Drive::~Cia402Drive() {
  *alive_ = false;
  network_.detach(node_);
}

bool Cia402Drive::routed(std::uint16_t index, std::uint8_t sub) const noexcept {
  return options_.layout.routes.empty() || options_.layout.has(index, sub);
}

Mode Cia402Drive::mode_display(const canopen::ObjectDictionary& img) const {
  if (routed(k_mode_display)) return static_cast<Mode>(img.get_int(k_mode_display, 0));
  return commanded_mode_cycles_ >= 5 && sdo_writes_settled(img) ? commanded_mode_ : Mode::no_mode;
}

bool Cia402Drive::sdo_writes_settled(const canopen::ObjectDictionary& img) const {
  if (writes_in_flight_ != 0) return false;
  for (const auto key : written_) {
    if (key.index == k_digital_outputs) continue;  // outputs do not hold up a set-point or a mode
    const auto* v = img.find(key.index, key.sub);
    const auto it = last_written_.find(key_of(key));
    if (v != nullptr && (it == last_written_.end() || it->second != v->value)) return false;
  }
  return true;
}

void Cia402Drive::sdo_service(TimePoint now, canopen::ObjectDictionary& img) {
  if (!booted_) return;
  auto& sdo = network_.master().sdo(node_);
  if (!polled_.empty() && !poll_in_flight_ && now >= next_poll_at_) {
    const auto key = polled_[next_poll_++ % polled_.size()];
    poll_in_flight_ = true;
    next_poll_at_ = now + options_.poll_period / static_cast<long>(polled_.size());
    sdo.async_upload(key.index, key.sub, now,
                     [this, alive = alive_, key](std::error_code ec, std::vector<std::uint8_t> d) {
                       if (!*alive) return;
                       poll_in_flight_ = false;
                       if (!ec) network_.master().image(node_).set_bytes(key.index, key.sub, d);
                     });
  }
  for (const auto key : written_) {
    const auto* v = img.find(key.index, key.sub);
    if (v == nullptr) continue;
    auto& last = last_written_[key_of(key)];
    if (last == v->value) continue;
    last = v->value;
    ++writes_in_flight_;
    sdo.async_download(key.index, key.sub, v->value, now,
                       [this, alive = alive_, key](std::error_code ec, std::vector<std::uint8_t>) {
                         if (!*alive) return;
                         --writes_in_flight_;
                         if (ec) {
                           last_written_[key_of(key)].clear();  // try again with the next change... or the next cycle
                           set_fault(ec, fmt::format("node {}: SDO write of 0x{:04X}:{} failed: {}", node_, key.index,
                                                     key.sub, ec.message()));
                         }
                       });
  }
}

DriveCapabilities Cia402Drive::capabilities() const noexcept {
  DriveCapabilities c;
  c.closed_loop = true;
  c.velocity_mode = true;
  c.homing = options_.homing;
  c.drive_profile = options_.setup == OperatingSetup::pp;
  c.min_period = std::chrono::microseconds(250);
  c.digital_inputs = options_.layout.has(k_digital_inputs);
  c.digital_output_mask = options_.layout.digital_output_mask;
  return c;
}

void Cia402Drive::on_boot(std::error_code ec) {
  booted_ = !ec;
  boot_error_ = ec;
  if (ec) {
    const auto& st = network_.master().status(node_);
    set_fault(ec, fmt::format("node {} boot-up failed: {}{}{}: check the node-ID, wiring and EDS", node_, ec.message(),
                              st.detail.empty() ? "" : ": ", st.detail));
  }
}

void Cia402Drive::on_emcy(std::uint16_t code, std::uint8_t) {
  emcy_code_ = code;
}

void Cia402Drive::on_heartbeat_lost(Duration) {
  heartbeat_lost_ = true;
  set_fault(make_error_code(ErrorCode::heartbeat),
            fmt::format("{} (node {}): no heartbeat within the consumer time; check the cable and the node's power",
                        describe(0x8130), node_));
}

void Cia402Drive::on_heartbeat_resumed() { /* stays latched until fault_reset */
}

void Cia402Drive::set_fault(std::error_code code, std::string text) {
  feedback_.fault.code = code;
  feedback_.fault.text = std::move(text);
}

void Cia402Drive::read(const CycleTime& cycle) {
  auto& master = network_.master();
  const auto& st = master.status(node_);
  auto& img = master.image(node_);
  if (st.last_rpdo) last_feedback_ = st.last_rpdo;
  feedback_.age = last_feedback_ ? cycle.now - *last_feedback_ : Duration::max();
  if (boot_error_) {
    feedback_.state = DriveState::not_ready;
    return;
  }
  if (!booted_ || !last_feedback_) {
    // Booting (SDO configuration in progress): not ready, and no data is not stale data.
    feedback_.state = DriveState::not_ready;
    feedback_.age = Duration::zero();
    return;
  }
  statusword_ = static_cast<std::uint16_t>(img.get_int(k_sw, 0));
  feedback_.position_inc = img.get_int(k_actual_pos, 0);
  feedback_.velocity_inc_per_s = static_cast<double>(img.get_int(k_actual_vel, 0));
  if (options_.layout.has(k_digital_inputs))
    feedback_.digital_inputs = static_cast<std::uint32_t>(img.get_int(k_digital_inputs, 0));
  const auto state = decode_state(statusword_);
  raw_state_ = state;
  if (heartbeat_lost_) {
    feedback_.state = DriveState::fault;
    return;
  }
  feedback_.state = state;
  const bool faulted = state == DriveState::fault || state == DriveState::fault_reaction_active;
  if (reset_pending_) {
    if (!reset_deadline_) reset_deadline_ = cycle.now + options_.reset_timeout;
    if (!faulted) {
      reset_pending_ = false;
    } else if (cycle.now < *reset_deadline_) {
      feedback_.state = DriveState::not_ready;  // acknowledged, the drive has not confirmed yet
      feedback_.fault = {};
      return;
    } else {
      reset_pending_ = false;
      const auto code = static_cast<std::uint16_t>(img.get_int(k_error, 0));
      set_fault(make_cia402_error(code),
                fmt::format("{} (node {}): fault reset refused, the cause persists", describe(code), node_));
      return;
    }
  }
  if (state == DriveState::fault || state == DriveState::fault_reaction_active) {
    // Latched: the drive is switched off and stays off, even if it leaves Fault by itself, until
    // a fault reset is requested; then the program enables it again.
    fault_latched_ = true;
    goal_ = DriveState::switch_on_disabled;
    auto code = static_cast<std::uint16_t>(img.get_int(k_error, 0));
    if (code == 0) code = emcy_code_;
    if (!feedback_.fault || feedback_.fault.code.value() != code)
      set_fault(make_cia402_error(code),
                fmt::format("{} (node {}): see the drive's error history 0x1003", describe(code), node_));
  } else if (feedback_.age > options_.stale_after && feedback_.state != DriveState::not_ready) {
    feedback_.state = DriveState::fault;
    set_fault(make_error_code(MotionFault::drive_lost),
              fmt::format("node {}: no process data for {} ms (SYNC or PDO lost)", node_,
                          std::chrono::duration_cast<std::chrono::milliseconds>(feedback_.age).count()));
  } else if (feedback_.fault && !fault_latched_) {
    feedback_.fault = {};
  }
  const auto display_now = mode_display(img);
  if (homing_started_ && display_now == Mode::homing) {
    const bool attained = (statusword_ & sw::op_specific_12) != 0;
    const bool reached = (statusword_ & sw::target_reached) != 0;
    const bool error = (statusword_ & sw::op_specific_13) != 0;
    if (attained && reached) {
      feedback_.referenced = true;
      feedback_.homing_active = false;
      homing_started_ = homing_requested_ = false;
    } else if (error || cycle.now > homing_deadline_) {
      feedback_.homing_active = false;
      homing_started_ = homing_requested_ = false;
      set_fault(make_error_code(MotionFault::invalid_command),
                fmt::format("node {}: homing {} (method 0x6098)", node_,
                            error ? "error reported by the drive" : "timed out"));
    }
  }
}

void Cia402Drive::write(const CycleTime& cycle, const DriveCommand& command) {
  auto& img = network_.master().image(node_);
  const auto state = raw_state_;
  const bool faulted = state == DriveState::fault || state == DriveState::fault_reaction_active;
  std::uint16_t cwv =
      reset_pending_ && faulted ? fault_reset_controlword(controlword_) : controlword_toward(state, goal_);
  if (heartbeat_lost_) cwv = cw::cmd_disable_voltage;
  Mode mode = command.mode == CommandMode::velocity ? Mode::cyclic_sync_velocity : Mode::cyclic_sync_position;
  std::int64_t target = command.position_inc;
  double velocity = command.velocity_inc_per_s;
  if (options_.setup == OperatingSetup::csv && command.mode == CommandMode::position) {
    // The master closes the position loop: feed-forward plus the gain on the position error.
    mode = Mode::cyclic_sync_velocity;
    velocity += options_.csv_position_gain_per_s * static_cast<double>(command.position_inc - feedback_.position_inc);
  }
  const bool profile = options_.setup == OperatingSetup::pp && !homing_requested_;
  if (profile && state == DriveState::operation_enabled) {
    mode = write_profile(command.move, cwv, img);
    // A hold (halt) leaves no edge on bit 4: 0x607A only matters with the next set-point.
    target = command.move.kind == DriveMove::Kind::position ? command.move.target_inc : feedback_.position_inc;
    velocity = command.move.kind == DriveMove::Kind::velocity ? command.move.velocity_inc_per_s : 0.0;
  } else if (profile) {
    mode = profile_mode_;
    set_point_ = SetPoint::acknowledged;  // a move given while not enabled is not started later
    set_point_id_ = command.move.id;
  }
  if (homing_requested_) {
    mode = Mode::homing;
    const auto display = mode_display(img);
    if (state == DriveState::operation_enabled && display == Mode::homing) {
      if (!homing_started_ && (controlword_ & cw::new_set_point) == 0) {
        homing_started_ = true;
        homing_deadline_ = cycle.now + options_.homing_timeout;
      } else if (homing_started_)
        cwv |= cw::new_set_point;  // bit 4 rising one cycle later: start homing
    }
  }
  if (state != DriveState::operation_enabled) {
    // Hold the actual position so enabling never makes the axis jump.
    target = feedback_.position_inc;
    velocity = 0.0;
  }
  img.set_int(k_cw, 0, cwv);
  img.set_int(k_mode, 0, static_cast<std::int8_t>(mode));
  img.set_int(k_target_pos, 0, clamp32(static_cast<double>(target)));
  img.set_int(k_target_vel, 0, clamp32(velocity));
  if (options_.layout.digital_output_mask != 0)  // outputs are not motion: written in every state
    img.set_int(k_digital_outputs, 1, command.digital_outputs & options_.layout.digital_output_mask);
  controlword_ = cwv;
  if (mode == commanded_mode_) {
    ++commanded_mode_cycles_;
  } else {
    commanded_mode_ = mode;
    commanded_mode_cycles_ = 0;
  }
  sdo_service(cycle.now, img);
}

Mode Cia402Drive::write_profile(const DriveMove& move, std::uint16_t& cwv, canopen::ObjectDictionary& img) {
  const auto display = mode_display(img);
  const bool acknowledged = (statusword_ & sw::op_specific_12) != 0;
  img.set_int(k_profile_acc, 0, profile_value(move.acceleration_inc_per_s2));
  img.set_int(k_profile_dec, 0, profile_value(move.deceleration_inc_per_s2));
  switch (move.kind) {
    case DriveMove::Kind::position:
      profile_mode_ = Mode::profile_position;
      img.set_int(k_profile_vel, 0, profile_value(move.velocity_inc_per_s));
      if (move.id != set_point_id_) {
        set_point_id_ = move.id;
        set_point_ = SetPoint::waiting;
      }
      cwv |= cw::change_immediately;  // a new target replaces the running one at once
      switch (set_point_) {
        case SetPoint::waiting:
          // Raise bit 4 once the drive is in PP and has dropped the previous acknowledge.
          // Set-points that go by SDO (no room in the RPDOs) must have arrived first.
          if (display == Mode::profile_position && !acknowledged && (controlword_ & cw::new_set_point) == 0 &&
              sdo_writes_settled(img)) {
            cwv |= cw::new_set_point;
            set_point_ = SetPoint::raised;
          }
          break;
        case SetPoint::raised:
          cwv |= cw::new_set_point;  // held until the drive acknowledges (bit 12)
          if (acknowledged) set_point_ = SetPoint::acknowledged;
          break;
        case SetPoint::acknowledged:
          break;  // bit 4 low again: the drive drops bit 12
      }
      break;
    case DriveMove::Kind::velocity:
      profile_mode_ = Mode::profile_velocity;
      break;
    case DriveMove::Kind::hold:
      cwv |= cw::halt;  // brake under 0x6084 and stand; stays in the mode that moved
      break;
  }
  return profile_mode_;
}

bool Cia402Drive::request(DriveRequest r) {
  switch (r) {
    case DriveRequest::enable:
      goal_ = DriveState::operation_enabled;
      return true;
    case DriveRequest::disable:
      goal_ = DriveState::switch_on_disabled;
      return true;
    case DriveRequest::quick_stop:
      goal_ = DriveState::quick_stop_active;
      return true;
    case DriveRequest::fault_reset:
      reset_pending_ = true;
      fault_latched_ = false;
      reset_deadline_.reset();
      heartbeat_lost_ = false;
      emcy_code_ = 0;
      feedback_.fault = {};
      if (goal_ == DriveState::operation_enabled) goal_ = DriveState::switch_on_disabled;
      return true;
    case DriveRequest::home:
      if (!options_.homing) return false;
      homing_requested_ = true;
      homing_started_ = false;
      feedback_.homing_active = true;
      feedback_.referenced = false;
      return true;
  }
  return false;
}

}  // namespace hil::cia402
