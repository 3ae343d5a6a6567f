// SPDX-License-Identifier: MIT
#include "hil/modbus/drive_words.hpp"

namespace hil::modbus {
namespace {

constexpr bool bit(std::uint16_t w, int n) noexcept { return n >= 0 && ((w >> n) & 1u) != 0; }
constexpr std::uint16_t mask(int n) noexcept { return n >= 0 ? static_cast<std::uint16_t>(1u << n) : 0; }

bool referenced_from(const Profile& p, std::uint16_t sw) noexcept {
  return p.bits.referenced < 0 ? true : bit(sw, p.bits.referenced);
}

DriveState cia402_state(std::uint16_t sw) noexcept {
  if ((sw & 0x4F) == 0x00) return DriveState::not_ready;
  if ((sw & 0x4F) == 0x40) return DriveState::switch_on_disabled;
  if ((sw & 0x6F) == 0x21) return DriveState::ready_to_switch_on;
  if ((sw & 0x6F) == 0x23) return DriveState::switched_on;
  if ((sw & 0x6F) == 0x27) return DriveState::operation_enabled;
  if ((sw & 0x6F) == 0x07) return DriveState::quick_stop_active;
  if ((sw & 0x4F) == 0x0F) return DriveState::fault_reaction_active;
  if ((sw & 0x4F) == 0x08) return DriveState::fault;
  return DriveState::not_ready;  // undefined pattern: treat as not ready
}

// CiA 402 device FSA (CiA 402-2 §6.3.2, Figure 13), quick stop option code 2 (ramp, then
// switch on disabled).
DriveState cia402_next(DriveState s, std::uint16_t cw, std::uint16_t prev_cw, bool fault_active, bool stopped) {
  const bool disable_voltage = (cw & 0x02) == 0;                  // xxxx xx0x
  const bool quick_stop = (cw & 0x06) == 0x02;                    // xxxx x01x
  const bool shutdown = (cw & 0x87) == 0x06;                      // 0xxx x110
  const bool switch_on = (cw & 0x8F) == 0x07;                     // 0xxx 0111
  const bool enable_op = (cw & 0x8F) == 0x0F;                     // 0xxx 1111
  const bool reset_edge = (cw & 0x80) != 0 && (prev_cw & 0x80) == 0;
  if (fault_active && s != DriveState::fault && s != DriveState::fault_reaction_active)
    return DriveState::fault_reaction_active;
  switch (s) {
    case DriveState::not_ready: return DriveState::switch_on_disabled;  // self-test done
    case DriveState::switch_on_disabled: return shutdown ? DriveState::ready_to_switch_on : s;
    case DriveState::ready_to_switch_on:
      if (disable_voltage || quick_stop) return DriveState::switch_on_disabled;
      if (enable_op) return DriveState::operation_enabled;  // transitions 3 + 4
      if (switch_on) return DriveState::switched_on;
      return s;
    case DriveState::switched_on:
      if (disable_voltage || quick_stop) return DriveState::switch_on_disabled;
      if (shutdown) return DriveState::ready_to_switch_on;
      if (enable_op) return DriveState::operation_enabled;
      return s;
    case DriveState::operation_enabled:
      if (disable_voltage) return DriveState::switch_on_disabled;
      if (quick_stop) return DriveState::quick_stop_active;
      if (shutdown) return DriveState::ready_to_switch_on;
      if (switch_on) return DriveState::switched_on;
      return s;
    case DriveState::quick_stop_active:
      if (disable_voltage || stopped) return DriveState::switch_on_disabled;
      return s;
    case DriveState::fault_reaction_active: return DriveState::fault;  // reaction done
    case DriveState::fault: return (reset_edge && !fault_active) ? DriveState::switch_on_disabled : s;
  }
  return s;
}

DriveState vendor_next(const Profile& p, DriveState s, std::uint16_t cw, std::uint16_t prev_cw, bool fault_active,
                       bool stopped) {
  const bool reset_edge = bit(cw, p.bits.fault_reset) && !bit(prev_cw, p.bits.fault_reset);
  if (fault_active && s != DriveState::fault) return DriveState::fault;
  if (s == DriveState::fault) return (reset_edge && !fault_active) ? DriveState::switch_on_disabled : s;
  if (s == DriveState::not_ready) return DriveState::switch_on_disabled;
  if (bit(cw, p.bits.quick_stop)) {
    if (s == DriveState::operation_enabled) return DriveState::quick_stop_active;
    if (s == DriveState::quick_stop_active) return stopped ? DriveState::switch_on_disabled : s;
    return DriveState::switch_on_disabled;
  }
  if (s == DriveState::quick_stop_active && !stopped) return s;
  return bit(cw, p.bits.enable) ? DriveState::operation_enabled : DriveState::switch_on_disabled;
}

}  // namespace

StatusInfo decode_status(const Profile& p, std::uint16_t sw) noexcept {
  StatusInfo r;
  r.referenced = referenced_from(p, sw);
  if (p.state_machine == StateMachineKind::cia402) {
    r.state = cia402_state(sw);
    return r;
  }
  if (bit(sw, p.bits.fault)) r.state = DriveState::fault;
  else if (bit(sw, p.bits.enabled)) r.state = DriveState::operation_enabled;
  else if (bit(sw, p.bits.ready)) r.state = DriveState::switch_on_disabled;
  else r.state = DriveState::not_ready;
  return r;
}

std::uint16_t make_control_word(const Profile& p, DriveState current, PowerTarget target, bool fault_reset_high) noexcept {
  if (p.state_machine == StateMachineKind::vendor) {
    std::uint16_t cw = 0;
    if (current == DriveState::fault || current == DriveState::fault_reaction_active) {
      return fault_reset_high ? mask(p.bits.fault_reset) : 0;
    }
    if (target == PowerTarget::enabled) cw |= mask(p.bits.enable);
    if (target == PowerTarget::quick_stop) cw |= mask(p.bits.quick_stop);
    return cw;
  }
  using namespace cia402;
  switch (current) {
    case DriveState::fault:
    case DriveState::fault_reaction_active: return fault_reset_high ? cw_fault_reset : cw_disable_voltage;
    case DriveState::not_ready: return cw_disable_voltage;
    default: break;
  }
  if (target == PowerTarget::disabled) return cw_disable_voltage;
  if (target == PowerTarget::quick_stop)
    return (current == DriveState::operation_enabled || current == DriveState::quick_stop_active) ? cw_quick_stop
                                                                                                    : cw_disable_voltage;
  switch (current) {
    case DriveState::switch_on_disabled: return cw_shutdown;
    case DriveState::ready_to_switch_on: return cw_switch_on;
    case DriveState::switched_on:
    case DriveState::operation_enabled: return cw_enable_operation;
    case DriveState::quick_stop_active: return cw_disable_voltage;  // leave QSA via switch on disabled
    default: return cw_disable_voltage;
  }
}

std::uint16_t make_status_word(const Profile& p, DriveState s, bool referenced, bool target_reached) noexcept {
  if (p.state_machine == StateMachineKind::vendor) {
    std::uint16_t sw = 0;
    if (s != DriveState::fault && s != DriveState::not_ready) sw |= mask(p.bits.ready);
    if (s == DriveState::operation_enabled || s == DriveState::quick_stop_active) sw |= mask(p.bits.enabled);
    if (s == DriveState::fault || s == DriveState::fault_reaction_active) sw |= mask(p.bits.fault);
    if (referenced) sw |= mask(p.bits.referenced);
    return sw;
  }
  using namespace cia402;
  std::uint16_t sw = 0;
  switch (s) {
    case DriveState::not_ready: sw = 0x0000; break;
    case DriveState::switch_on_disabled: sw = 0x0040; break;
    case DriveState::ready_to_switch_on: sw = 0x0021; break;
    case DriveState::switched_on: sw = 0x0023 | sw_voltage_enabled; break;
    case DriveState::operation_enabled: sw = 0x0027 | sw_voltage_enabled; break;
    case DriveState::quick_stop_active: sw = 0x0007 | sw_voltage_enabled; break;
    case DriveState::fault_reaction_active: sw = 0x000F; break;
    case DriveState::fault: sw = 0x0008; break;
  }
  sw |= sw_remote;
  if (target_reached) sw |= sw_target_reached;
  if (referenced && p.bits.referenced >= 0) sw |= mask(p.bits.referenced);
  return sw;
}

DriveState next_device_state(const Profile& p, DriveState s, std::uint16_t cw, std::uint16_t prev_cw,
                             bool fault_active, bool stopped) noexcept {
  return p.state_machine == StateMachineKind::cia402 ? cia402_next(s, cw, prev_cw, fault_active, stopped)
                                                     : vendor_next(p, s, cw, prev_cw, fault_active, stopped);
}

}  // namespace hil::modbus
