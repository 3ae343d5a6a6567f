// SPDX-License-Identifier: MIT
#pragma once
// What an axis shows after each update().

#include <cstdint>

#include "hil/core/drive.hpp"
#include "hil/core/fault.hpp"

namespace hil::motion {

/// PLCopen-like axis state.
enum class AxisState { disabled, enabling, standstill, moving, stopping, homing, error };

/// Positions in user units; rotary axes show [0, modulo). Following error = command (with
/// backlash compensation) minus actual, in units.
struct AxisStatus {
  double position = 0.0;              ///< actual
  double command_position = 0.0;      ///< trajectory set-point, without backlash compensation
  double velocity = 0.0;              ///< actual, units/s
  double command_velocity = 0.0;      ///< units/s
  double command_acceleration = 0.0;  ///< units/s^2
  double following_error = 0.0;       ///< units
  std::int64_t position_inc = 0;      ///< actual, drive increments (unwrapped)
  std::int64_t command_inc = 0;       ///< set-point, drive increments (unwrapped, without backlash)
  hil::DriveState drive_state = hil::DriveState::not_ready;
  AxisState state = AxisState::disabled;
  bool in_position = false;  ///< inside in_position_window of the target after the profile ended
  bool busy = false;         ///< a profile (move, stop) or homing is running
  bool referenced = false;   ///< from the drive
  hil::Fault fault;          ///< the axis fault (MotionFault) while state == error
};

[[nodiscard]] const char* to_string(AxisState s) noexcept;

}  // namespace hil::motion
