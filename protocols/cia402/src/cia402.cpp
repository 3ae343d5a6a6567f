// SPDX-License-Identifier: MIT
#include "hil/cia402/cia402.hpp"

namespace hil::cia402 {

std::string_view to_string(Mode m) noexcept {
  switch (m) {
    case Mode::no_mode:
      return "no mode";
    case Mode::profile_position:
      return "profile position (PP)";
    case Mode::velocity:
      return "velocity (VL)";
    case Mode::profile_velocity:
      return "profile velocity (PV)";
    case Mode::profile_torque:
      return "profile torque (PT)";
    case Mode::homing:
      return "homing (HM)";
    case Mode::interpolated_position:
      return "interpolated position (IP)";
    case Mode::cyclic_sync_position:
      return "cyclic synchronous position (CSP)";
    case Mode::cyclic_sync_velocity:
      return "cyclic synchronous velocity (CSV)";
    case Mode::cyclic_sync_torque:
      return "cyclic synchronous torque (CST)";
  }
  return "manufacturer-specific mode";
}

std::optional<std::uint32_t> supported_mode_bit(Mode m) noexcept {
  switch (m) {
    case Mode::profile_position:
      return 1u << 0;
    case Mode::velocity:
      return 1u << 1;
    case Mode::profile_velocity:
      return 1u << 2;
    case Mode::profile_torque:
      return 1u << 3;
    case Mode::homing:
      return 1u << 5;
    case Mode::interpolated_position:
      return 1u << 6;
    case Mode::cyclic_sync_position:
      return 1u << 7;
    case Mode::cyclic_sync_velocity:
      return 1u << 8;
    case Mode::cyclic_sync_torque:
      return 1u << 9;
    default:
      return std::nullopt;
  }
}

DriveState decode_state(std::uint16_t s) noexcept {
  if ((s & 0x4F) == 0x00) return DriveState::not_ready;
  if ((s & 0x4F) == 0x40) return DriveState::switch_on_disabled;
  if ((s & 0x6F) == 0x21) return DriveState::ready_to_switch_on;
  if ((s & 0x6F) == 0x23) return DriveState::switched_on;
  if ((s & 0x6F) == 0x27) return DriveState::operation_enabled;
  if ((s & 0x6F) == 0x07) return DriveState::quick_stop_active;
  if ((s & 0x4F) == 0x0F) return DriveState::fault_reaction_active;
  if ((s & 0x4F) == 0x08) return DriveState::fault;
  return DriveState::not_ready;  // undefined bit patterns: treat as not ready
}

std::uint16_t encode_state(DriveState s) noexcept {
  switch (s) {
    case DriveState::not_ready:
      return 0x0000;
    case DriveState::switch_on_disabled:
      return 0x0040;
    case DriveState::ready_to_switch_on:
      return 0x0021;
    case DriveState::switched_on:
      return 0x0023;
    case DriveState::operation_enabled:
      return 0x0027;
    case DriveState::quick_stop_active:
      return 0x0007;
    case DriveState::fault_reaction_active:
      return 0x000F;
    case DriveState::fault:
      return 0x0008;
  }
  return 0;
}

std::uint16_t device_statusword(DriveState s, bool target_reached) noexcept {
  std::uint16_t w = encode_state(s) | sw::remote;
  if (s == DriveState::switched_on || s == DriveState::operation_enabled || s == DriveState::quick_stop_active)
    w |= sw::voltage_enabled;
  if (target_reached) w |= sw::target_reached;
  return w;
}

namespace {
bool is_shutdown(std::uint16_t c) {
  return (c & 0x87) == 0x06;
}
bool is_switch_on(std::uint16_t c) {
  return (c & 0x8F) == 0x07;
}
bool is_enable(std::uint16_t c) {
  return (c & 0x8F) == 0x0F;
}
bool is_disable_voltage(std::uint16_t c) {
  return (c & 0x82) == 0x00;
}
bool is_quick_stop(std::uint16_t c) {
  return (c & 0x86) == 0x02;
}
}  // namespace

DriveState next_state(DriveState s, std::uint16_t c, bool fault_reset_edge, bool quick_stop_stays) noexcept {
  switch (s) {
    case DriveState::switch_on_disabled:
      return is_shutdown(c) ? DriveState::ready_to_switch_on : s;  // 2
    case DriveState::ready_to_switch_on:
      if (is_switch_on(c)) return DriveState::switched_on;                                   // 3
      if (is_enable(c)) return DriveState::operation_enabled;                                // 3 + 4
      if (is_disable_voltage(c) || is_quick_stop(c)) return DriveState::switch_on_disabled;  // 7
      return s;
    case DriveState::switched_on:
      if (is_enable(c)) return DriveState::operation_enabled;                                // 4
      if (is_shutdown(c)) return DriveState::ready_to_switch_on;                             // 6
      if (is_disable_voltage(c) || is_quick_stop(c)) return DriveState::switch_on_disabled;  // 10
      return s;
    case DriveState::operation_enabled:
      if (is_switch_on(c)) return DriveState::switched_on;               // 5 (disable operation)
      if (is_shutdown(c)) return DriveState::ready_to_switch_on;         // 8
      if (is_disable_voltage(c)) return DriveState::switch_on_disabled;  // 9
      if (is_quick_stop(c)) return DriveState::quick_stop_active;        // 11
      return s;
    case DriveState::quick_stop_active:
      if (is_disable_voltage(c)) return DriveState::switch_on_disabled;            // 12
      if (quick_stop_stays && is_enable(c)) return DriveState::operation_enabled;  // 16
      return s;
    case DriveState::fault:
      return fault_reset_edge ? DriveState::switch_on_disabled : s;  // 15
    case DriveState::not_ready:
    case DriveState::fault_reaction_active:
      return s;
  }
  return s;
}

std::uint16_t fault_reset_controlword(std::uint16_t previous) noexcept {
  return (previous & cw::fault_reset) ? cw::cmd_disable_voltage : cw::cmd_fault_reset;
}

std::uint16_t controlword_toward(DriveState s, DriveState goal) noexcept {
  if (s == DriveState::fault || s == DriveState::fault_reaction_active) return cw::cmd_disable_voltage;
  if (goal == DriveState::switch_on_disabled) return cw::cmd_disable_voltage;
  if (goal == DriveState::quick_stop_active) {
    if (s == DriveState::operation_enabled || s == DriveState::quick_stop_active) return cw::cmd_quick_stop;
    return cw::cmd_disable_voltage;
  }
  switch (s) {
    case DriveState::not_ready:
    case DriveState::switch_on_disabled:
      return cw::cmd_shutdown;
    case DriveState::ready_to_switch_on:
      return cw::cmd_switch_on;
    case DriveState::switched_on:
    case DriveState::operation_enabled:
      return cw::cmd_enable_operation;
    case DriveState::quick_stop_active:
      return cw::cmd_disable_voltage;  // 12, then walk up again
    default:
      return cw::cmd_disable_voltage;
  }
}

}  // namespace hil::cia402
