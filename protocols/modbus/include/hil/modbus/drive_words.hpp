// SPDX-License-Identifier: MIT
#pragma once
// The state machine behind a profile's control and status words, as pure functions for both
// ends: the client (ModbusDrive) decodes status words and chooses control words; the simulated
// drive server encodes status words and steps its device state machine.
//   cia402: CiA 402-2 §6.3 finite state automaton, the same functions the CANopen drive and the
//           simulated CiA 402 node use (hil::cia402, protocols/cia402); this file adds what a
//           register drive decides itself: the fault reaction, the quick stop option (code 2:
//           ramp, then switch on disabled) and the fault-reset edge made over two cycles.
//   vendor: level bits enable / quick_stop, rising edge of fault_reset; status bits ready /
//           enabled / fault (bit numbers from the profile).

#include <cstdint>

#include "hil/core/drive.hpp"
#include "hil/modbus/profile.hpp"

namespace hil::modbus {

/// Where the client wants the power stage to go.
enum class PowerTarget : std::uint8_t { disabled, enabled, quick_stop };

struct StatusInfo {
  DriveState state = DriveState::not_ready;
  bool referenced = false;
};

/// Client: the drive state a status word shows. CiA 402 masks per CiA 402-2 Table 30.
[[nodiscard]] StatusInfo decode_status(const Profile& profile, std::uint16_t status_word) noexcept;

/// Client: the control word that moves a drive in `current` one transition towards `target`.
/// `fault_reset_high`: hold the fault-reset bit (the caller makes the 0 -> 1 edge over two cycles).
[[nodiscard]] std::uint16_t make_control_word(const Profile& profile, DriveState current, PowerTarget target,
                                              bool fault_reset_high) noexcept;

/// Server: the status word for a device state.
[[nodiscard]] std::uint16_t make_status_word(const Profile& profile, DriveState state, bool referenced,
                                             bool target_reached) noexcept;

/// Server: one step of the device state machine after the control word changed from `prev_cw`
/// to `cw` (or on a plant step with cw == prev_cw). `fault_active`: the plant reports a fault
/// now; `stopped`: the axis is at standstill (ends quick_stop_active).
[[nodiscard]] DriveState next_device_state(const Profile& profile, DriveState state, std::uint16_t cw,
                                           std::uint16_t prev_cw, bool fault_active, bool stopped) noexcept;

}  // namespace hil::modbus
