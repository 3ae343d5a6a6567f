// SPDX-License-Identifier: MIT
#pragma once
// CLM1.4 run-time errors (manual §11, digest clm14.md §6.2). The enum values are the device's
// hex codes as shown in status 53, polled by ":s" and written to the B018 output byte. Axis
// errors are per axis: base + 0x30 * (axis - 1) for axes 1/2 (0x40/0x70), then 0xA0/0xD0.

#include <cstdint>
#include <string>
#include <system_error>

namespace hil::controllers::clm14 {

enum class ClmError : std::uint8_t {
  none = 0x00,
  parameter_invalid = 0x02,
  emergency_stop = 0x03,
  division_by_zero = 0x07,
  invalid_mode = 0x08,
  invalid_program_command = 0x0A,
  jsr_nesting = 0x0B,
  rts_nesting = 0x0C,
  bcd_input = 0x0D,
  invalid_block_number = 0x0E,
  axis_number = 0x16,
  rep_command = 0x1A,
  sac_command = 0x1B,
  command_io = 0x1D,
  vcc_command = 0x1E,
  variable_number = 0x1F,
  write_system_variable = 0x31,
  variable_value = 0x32,
  logic_program = 0x38,
  logic_program_lost = 0x39,
  missing_eos = 0x35,
  not_home_position = 0x36,
  index_length = 0x3A,      ///< flying cutoff: more material than the length since the manual cut
  rapid_stop = 0x3B,        ///< flying cutoff: rapid-stop input (A136)
  max_stroke_limit = 0x3C,  ///< flying cutoff: maximum stroke (A137)
  io_number = 0x3D,
  // axis 1 codes; axis n adds axis_offset(n)
  drive_not_ready = 0x40,
  feed_angle_loss = 0x41,
  drive_runaway = 0x42,
  position_lag = 0x43,
  min_travel = 0x46,
  max_travel = 0x47,
  not_homed = 0x48,
  cam_too_short = 0x49,          ///< homing: braked past the cam, or the cam ended before its marker
  no_marker_pulse = 0x4A,        ///< homing: no marker within one revolution
  marker_pulse_position = 0x4B,  ///< homing: cam edge - marker outside 1/16 .. 15/16 revolution
  encoder_fault = 0x4C,          ///< measuring-wheel mode: the wheel does not follow the motor (Ax16 window 1)
  max_override = 0x4D,
  axis_disabled = 0x4E,
  marker_high = 0x4F,  ///< homing: the marker line stays high
  target_below_limit = 0x50,
  target_above_limit = 0x51,
  hom_command = 0x52,
};

/// Offset of axis `axis` (1..4) added to an axis-1 code: 0x00, 0x30, 0x60, 0x90.
[[nodiscard]] constexpr int axis_offset(int axis) noexcept {
  return 0x30 * (axis - 1);
}
/// The device code of an axis error for `axis` (1..4).
[[nodiscard]] constexpr int axis_code(ClmError e, int axis) noexcept {
  return static_cast<int>(e) + axis_offset(axis);
}

/// Category "clm14": values are the device's codes. The device's texts live in the profile's
/// diagnostic catalogue (profiles/devices/clm14/errors.yaml); message() only names the code.
[[nodiscard]] const std::error_category& clm_error_category() noexcept;
[[nodiscard]] inline std::error_code make_error_code(ClmError e) noexcept {
  return {static_cast<int>(e), clm_error_category()};
}

}  // namespace hil::controllers::clm14

template <>
struct std::is_error_code_enum<hil::controllers::clm14::ClmError> : std::true_type {};
