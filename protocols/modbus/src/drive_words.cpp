// SPDX-License-Identifier: MIT
#include "hil/modbus/drive_words.hpp"

#include "hil/cia402/cia402.hpp"

namespace hil::modbus {
namespace {

constexpr bool bit(std::uint16_t w, int n) noexcept {
  return n >= 0 && ((w >> n) & 1u) != 0;
}
constexpr std::uint16_t mask(int n) noexcept {
  return static_cast<std::uint16_t>(n >= 0 ? (1u << n) : 0u);
}

bool referenced_from(const Profile& p, std::uint16_t sw) noexcept {
  return p.bits.referenced < 0 ? true : bit(sw, p.bits.referenced);
}

// CiA 402 device FSA (CiA 402-2 §6.3.2, Figure 13) with what the device decides itself: a
// fault starts the fault reaction, the self-test ends at once, the reaction completes in one
// step, quick stop option code 2 (ramp, then switch on disabled at standstill), and a fault
// reset is refused while the cause persists.
DriveState cia402_next(DriveState s, std::uint16_t cw, std::uint16_t prev_cw, bool fault_active, bool stopped) {
  if (fault_active && s != DriveState::fault && s != DriveState::fault_reaction_active)
    return DriveState::fault_reaction_active;
  switch (s) {
    case DriveState::not_ready:
      return DriveState::switch_on_disabled;  // self-test done (transition 1)
    case DriveState::fault_reaction_active:
      return DriveState::fault;  // reaction done (14)
    case DriveState::quick_stop_active:
      if (stopped) return DriveState::switch_on_disabled;  // option code 2: 12 after the ramp
      break;
    case DriveState::fault:
      if (fault_active) return s;  // 15 only once the cause is gone
      break;
    default:
      break;
  }
  const bool reset_edge = (cw & cia402::cw::fault_reset) != 0 && (prev_cw & cia402::cw::fault_reset) == 0;
  return cia402::next_state(s, cw, reset_edge, /*quick_stop_stays=*/false);
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
    r.state = cia402::decode_state(sw);
    return r;
  }
  if (bit(sw, p.bits.fault))
    r.state = DriveState::fault;
  else if (bit(sw, p.bits.enabled))
    r.state = DriveState::operation_enabled;
  else if (bit(sw, p.bits.ready))
    r.state = DriveState::switch_on_disabled;
  else
    r.state = DriveState::not_ready;
  return r;
}

std::uint16_t make_control_word(const Profile& p, DriveState current, PowerTarget target,
                                bool fault_reset_high) noexcept {
  if (p.state_machine == StateMachineKind::vendor) {
    std::uint16_t cw = 0;
    if (current == DriveState::fault || current == DriveState::fault_reaction_active) {
      return fault_reset_high ? mask(p.bits.fault_reset) : 0;
    }
    if (target == PowerTarget::enabled) cw |= mask(p.bits.enable);
    if (target == PowerTarget::quick_stop) cw |= mask(p.bits.quick_stop);
    return cw;
  }
  if (current == DriveState::fault || current == DriveState::fault_reaction_active)
    return fault_reset_high ? cia402::cw::cmd_fault_reset : cia402::cw::cmd_disable_voltage;
  if (current == DriveState::not_ready) return cia402::cw::cmd_disable_voltage;  // nothing to walk yet
  const DriveState goal = target == PowerTarget::enabled      ? DriveState::operation_enabled
                          : target == PowerTarget::quick_stop ? DriveState::quick_stop_active
                                                              : DriveState::switch_on_disabled;
  return cia402::controlword_toward(current, goal);
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
  std::uint16_t sw = cia402::device_statusword(s, target_reached);
  if (referenced && p.bits.referenced >= 0) sw |= mask(p.bits.referenced);
  return sw;
}

DriveState next_device_state(const Profile& p, DriveState s, std::uint16_t cw, std::uint16_t prev_cw, bool fault_active,
                             bool stopped) noexcept {
  return p.state_machine == StateMachineKind::cia402 ? cia402_next(s, cw, prev_cw, fault_active, stopped)
                                                     : vendor_next(p, s, cw, prev_cw, fault_active, stopped);
}

}  // namespace hil::modbus
