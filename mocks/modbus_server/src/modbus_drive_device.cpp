// SPDX-License-Identifier: MIT
#include "hil/mocks/modbus_drive_device.hpp"

#include <cmath>

#include "hil/cia402/cia402.hpp"
#include "hil/modbus/drive_words.hpp"

namespace hil::mocks {

using modbus::FieldRole;

DriveDevice::DriveDevice(modbus::Profile profile, DriveDeviceConfig config)
    : profile_(std::move(profile)), config_(config), plant_(config.plant) {
  modbus::define_registers(profile_, table_);
  hold_position_inc_ = static_cast<double>(plant_.encoder_position_inc());
  // Targets start at the actual position so an enable does not jump.
  const auto& tp = profile_.field(FieldRole::target_position);
  write_field(FieldRole::target_position, std::llround(hold_position_inc_ / tp.scale));
  write_field(FieldRole::mode, profile_.mode_position);
  state_ = DriveState::switch_on_disabled;  // self-test passed at power-on
  publish();
}

std::int64_t DriveDevice::read_field(FieldRole r) const noexcept {
  const auto& f = profile_.field(r);
  if (!f.present) return 0;
  const auto space = profile_.space_of(r);
  const std::uint16_t regs[2] = {table_.get(space, f.address),
                                 table_.get(space, static_cast<std::uint16_t>(f.address + 1))};
  return modbus::unpack_value(std::span<const std::uint16_t>(regs, f.words()), f.format);
}

void DriveDevice::write_field(FieldRole r, std::int64_t raw) noexcept {
  const auto& f = profile_.field(r);
  if (!f.present) return;
  std::uint16_t regs[2] = {0, 0};
  modbus::pack_value(raw, f.format, std::span<std::uint16_t>(regs, f.words()));
  const auto space = profile_.space_of(r);
  for (std::uint16_t i = 0; i < f.words(); ++i) table_.set(space, static_cast<std::uint16_t>(f.address + i), regs[i]);
}

std::uint32_t DriveDevice::fault_code_for(PlantFault f) const noexcept {
  if (profile_.state_machine == modbus::StateMachineKind::cia402) {
    switch (f) {
      case PlantFault::encoder:
        return 0x7305;
      case PlantFault::not_ready:
        return 0x3100;
      case PlantFault::following_blowup:
        return 0x8611;
      case PlantFault::none:
        return 0;
    }
  }
  return static_cast<std::uint32_t>(f);
}

modbus::HandleResult DriveDevice::handle(std::span<const std::uint8_t> adu, std::span<std::uint8_t> out,
                                         const modbus::HandlerOptions& options) noexcept {
  auto r = responder_.handle(adu, table_, out, options);
  if (r.written_count > 0) {
    const auto& cw = profile_.field(FieldRole::control_word);
    if (cw.address >= r.written_first && cw.address < r.written_first + r.written_count) {
      apply_control(std::fabs(plant_.velocity_inc_per_s()) < config_.standstill_velocity_inc_per_s);
      run_homing();
      publish();
    }
  }
  return r;
}

void DriveDevice::apply_control(bool stopped) noexcept {
  const auto cw = static_cast<std::uint16_t>(read_field(FieldRole::control_word));
  const PlantFault pf = plant_.fault();
  const DriveState before = state_;
  // Walk until stable (a fault reaction completes in one step; QSA ends at standstill).
  for (int i = 0; i < 4; ++i) {
    const DriveState next = modbus::next_device_state(profile_, state_, cw, prev_cw_, pf != PlantFault::none, stopped);
    prev_cw_ = cw;
    if (next == state_) break;
    if (next == DriveState::fault_reaction_active ||
        (next == DriveState::fault && state_ != DriveState::fault_reaction_active))
      latched_fault_code_ = fault_code_for(pf);
    if (state_ == DriveState::fault && next != DriveState::fault) latched_fault_code_ = 0;
    if (next == DriveState::quick_stop_active) qs_velocity_ = plant_.velocity_inc_per_s();
    state_ = next;
  }
  if (before != DriveState::operation_enabled && state_ == DriveState::operation_enabled) {
    hold_position_inc_ = plant_.position_inc();
  }
}

void DriveDevice::step(Duration dt) noexcept {
  const double dt_s = to_seconds(dt);
  PlantInput in;
  in.powered = state_ == DriveState::operation_enabled || state_ == DriveState::quick_stop_active;
  if (state_ == DriveState::operation_enabled && in_homing_mode()) {
    in.mode = CommandMode::position;  // homing on the current position: stand still
    in.position_inc = hold_position_inc_;
  } else if (state_ == DriveState::operation_enabled) {
    const std::int64_t mode = read_field(FieldRole::mode);
    const bool velocity_mode = profile_.field(FieldRole::mode).present && mode == profile_.mode_velocity;
    in.mode = velocity_mode ? CommandMode::velocity : CommandMode::position;
    in.position_inc =
        static_cast<double>(read_field(FieldRole::target_position)) * profile_.field(FieldRole::target_position).scale;
    in.velocity_inc_per_s = velocity_mode ? static_cast<double>(read_field(FieldRole::target_velocity)) *
                                                profile_.field(FieldRole::target_velocity).scale
                                          : 0.0;
    hold_position_inc_ = plant_.position_inc();
  } else if (state_ == DriveState::quick_stop_active) {
    const double dv = config_.quick_stop_deceleration_inc_per_s2 * dt_s;
    qs_velocity_ = std::fabs(qs_velocity_) <= dv ? 0.0 : qs_velocity_ - std::copysign(dv, qs_velocity_);
    in.mode = CommandMode::velocity;
    in.velocity_inc_per_s = qs_velocity_;
  } else {
    in.mode = CommandMode::position;
    in.position_inc = hold_position_inc_;
  }
  plant_.step(dt, in);
  const bool stopped = std::fabs(plant_.velocity_inc_per_s()) < config_.standstill_velocity_inc_per_s &&
                       (state_ != DriveState::quick_stop_active || qs_velocity_ == 0.0);
  apply_control(stopped);
  publish();
}

void DriveDevice::inject(PlantFault fault, bool active) noexcept {
  plant_.inject(fault, active);
  apply_control(std::fabs(plant_.velocity_inc_per_s()) < config_.standstill_velocity_inc_per_s);
  publish();
}

bool DriveDevice::in_homing_mode() const noexcept {
  return profile_.mode_homing.has_value() && read_field(FieldRole::mode) == *profile_.mode_homing;
}

void DriveDevice::run_homing() noexcept {
  const bool start = (read_field(FieldRole::control_word) & cia402::cw::new_set_point) != 0;
  const bool edge = start && !prev_start_bit_;
  prev_start_bit_ = start;
  if (!in_homing_mode() || state_ != DriveState::operation_enabled) {
    homing_attained_ = false;
    return;
  }
  if (edge) {
    plant_.set_position(0.0);  // the current position is the reference point
    hold_position_inc_ = 0.0;
    homing_attained_ = true;
  }
}

void DriveDevice::publish() noexcept {
  const std::int64_t pos = plant_.encoder_position_inc();
  const auto& ap = profile_.field(FieldRole::actual_position);
  write_field(FieldRole::actual_position, std::llround(static_cast<double>(pos) / ap.scale));
  const auto& av = profile_.field(FieldRole::actual_velocity);
  write_field(FieldRole::actual_velocity, std::llround(plant_.measured_velocity_inc_per_s() / av.scale));
  const double target =
      static_cast<double>(read_field(FieldRole::target_position)) * profile_.field(FieldRole::target_position).scale;
  const bool reached = std::fabs(target - static_cast<double>(pos)) <= static_cast<double>(config_.target_window_inc);
  if (!in_homing_mode()) homing_attained_ = false;
  std::uint16_t sw = modbus::make_status_word(profile_, state_, true, in_homing_mode() ? homing_attained_ : reached);
  if (homing_attained_) sw |= cia402::sw::op_specific_12;
  write_field(FieldRole::status_word, sw);
  write_field(FieldRole::fault_code, latched_fault_code_);
}

}  // namespace hil::mocks
