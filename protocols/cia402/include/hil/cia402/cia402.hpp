// SPDX-License-Identifier: MIT
#pragma once
// CiA 402-2 drive profile, pure: the power state machine (§6.3) from both sides. The device
// side computes the next state from the controlword; the master side decodes the statusword and
// picks the controlword that walks the drive toward a goal. No I/O, no time.

#include <cstdint>
#include <optional>
#include <string_view>

#include "hil/core/drive.hpp"

namespace hil::cia402 {

/// Modes of operation (0x6060 / 0x6061).
enum class Mode : std::int8_t {
  no_mode = 0,
  profile_position = 1,
  velocity = 2,
  profile_velocity = 3,
  profile_torque = 4,
  homing = 6,
  interpolated_position = 7,
  cyclic_sync_position = 8,
  cyclic_sync_velocity = 9,
  cyclic_sync_torque = 10,
};
[[nodiscard]] std::string_view to_string(Mode m) noexcept;
/// Bit of `m` in 0x6502 supported drive modes (nullopt for no_mode / manufacturer modes).
[[nodiscard]] std::optional<std::uint32_t> supported_mode_bit(Mode m) noexcept;

namespace cw {  // controlword bits (0x6040)
inline constexpr std::uint16_t switch_on = 1u << 0;
inline constexpr std::uint16_t enable_voltage = 1u << 1;
inline constexpr std::uint16_t quick_stop = 1u << 2;  ///< active LOW
inline constexpr std::uint16_t enable_operation = 1u << 3;
inline constexpr std::uint16_t new_set_point = 1u << 4;  ///< PP; HM: start homing
inline constexpr std::uint16_t change_immediately = 1u << 5;
inline constexpr std::uint16_t relative = 1u << 6;
inline constexpr std::uint16_t fault_reset = 1u << 7;
inline constexpr std::uint16_t halt = 1u << 8;
// Device control commands (CiA 402-2 table 6.x), low bits only.
inline constexpr std::uint16_t cmd_shutdown = 0x0006;
inline constexpr std::uint16_t cmd_switch_on = 0x0007;
inline constexpr std::uint16_t cmd_enable_operation = 0x000F;
inline constexpr std::uint16_t cmd_disable_voltage = 0x0000;
inline constexpr std::uint16_t cmd_quick_stop = 0x0002;
inline constexpr std::uint16_t cmd_disable_operation = 0x0007;
inline constexpr std::uint16_t cmd_fault_reset = 0x0080;
}  // namespace cw

namespace sw {  // statusword bits (0x6041)
inline constexpr std::uint16_t ready_to_switch_on = 1u << 0;
inline constexpr std::uint16_t switched_on = 1u << 1;
inline constexpr std::uint16_t operation_enabled = 1u << 2;
inline constexpr std::uint16_t fault = 1u << 3;
inline constexpr std::uint16_t voltage_enabled = 1u << 4;
inline constexpr std::uint16_t quick_stop = 1u << 5;  ///< 0 = quick stop active
inline constexpr std::uint16_t switch_on_disabled = 1u << 6;
inline constexpr std::uint16_t warning = 1u << 7;
inline constexpr std::uint16_t remote = 1u << 9;
inline constexpr std::uint16_t target_reached = 1u << 10;
inline constexpr std::uint16_t internal_limit = 1u << 11;
inline constexpr std::uint16_t op_specific_12 = 1u << 12;  ///< PP: set-point acknowledge; HM: homing attained
inline constexpr std::uint16_t op_specific_13 = 1u << 13;  ///< PP/CSP: following error; HM: homing error
inline constexpr std::uint16_t state_mask = 0x006F;
}  // namespace sw

/// State from a statusword (CiA 402-2 table 30; masks 0x4F / 0x6F).
[[nodiscard]] DriveState decode_state(std::uint16_t statusword) noexcept;
/// The state bits (0..3, 5, 6) of `s`; the caller ORs in voltage_enabled, remote, mode bits.
[[nodiscard]] std::uint16_t encode_state(DriveState s) noexcept;
/// Device side: the statusword of a drive in `s` under remote control: the state bits, remote
/// (bit 9), voltage enabled (bit 4) while powered, target reached (bit 10). The caller ORs in the
/// mode-specific bits 12/13.
[[nodiscard]] std::uint16_t device_statusword(DriveState s, bool target_reached) noexcept;

/// Device side: the state after controlword `cw` in state `s` (transitions 2..12, 15, 16;
/// `fault_reset_edge` = bit 7 rose since the previous controlword). Transitions 0/1 (power-up),
/// 13/14 (fault) and the automatic end of a quick stop are driven by the device itself.
/// `quick_stop_stays` = quick-stop option code 5..8 (stay in Quick Stop Active, transition 16 allowed).
[[nodiscard]] DriveState next_state(DriveState s, std::uint16_t cw, bool fault_reset_edge,
                                    bool quick_stop_stays) noexcept;

/// Master side: the controlword (state bits only) that moves a drive in `s` one transition
/// toward `goal` (operation_enabled, switch_on_disabled or quick_stop_active). A drive in Fault
/// or Fault Reaction Active gets Disable Voltage (0x0000) whatever the goal: a fault stays latched
/// until the master is asked for a reset, which then sends fault_reset_controlword().
[[nodiscard]] std::uint16_t controlword_toward(DriveState s, DriveState goal) noexcept;
/// Master side, only while a fault reset was requested: bit 7 low first (`previous` has it
/// high -> 0x0000), then 0x0080, the rising edge of transition 15.
[[nodiscard]] std::uint16_t fault_reset_controlword(std::uint16_t previous) noexcept;

}  // namespace hil::cia402
