// SPDX-License-Identifier: MIT
#pragma once
// The state machine behind a profile's control and status words, as pure functions for both
// ends: the client (ModbusDrive) decodes status words and chooses control words; the simulated
// drive server encodes status words and steps its device state machine.
//   cia402: CiA 402-2 §6.3 finite state automaton; control word 6040h commands Shutdown 0x06,
//           Switch on 0x07, Enable operation 0x0F, Disable voltage 0x00, Quick stop 0x02,
//           Fault reset = rising edge of bit 7; status word 6041h state bits 0-3, 5, 6.
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

namespace cia402 {
inline constexpr std::uint16_t cw_disable_voltage = 0x0000;
inline constexpr std::uint16_t cw_quick_stop = 0x0002;
inline constexpr std::uint16_t cw_shutdown = 0x0006;
inline constexpr std::uint16_t cw_switch_on = 0x0007;
inline constexpr std::uint16_t cw_enable_operation = 0x000F;
inline constexpr std::uint16_t cw_fault_reset = 0x0080;
inline constexpr std::uint16_t sw_voltage_enabled = 0x0010;
inline constexpr std::uint16_t sw_remote = 0x0200;
inline constexpr std::uint16_t sw_target_reached = 0x0400;
}  // namespace cia402

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
