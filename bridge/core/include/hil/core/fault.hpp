// SPDX-License-Identifier: MIT
#pragma once
// A drive or device fault as the spec names it: the value of `code` *is* the spec's number
// (CiA 402 error code 0x603F, Modbus exception code, a legacy controller's error number) and
// its category names the domain, so a log line and the manual line up.

#include <string>
#include <system_error>

namespace hil {

struct Fault {
  std::error_code code;  ///< spec number + domain; empty when there is no fault
  std::string text;      ///< what happened, where, and what to do

  [[nodiscard]] explicit operator bool() const noexcept { return static_cast<bool>(code); }
  /// "cia402:0x7305 Incremental encoder 1 broken (node 5): check the encoder cable"; codes below
  /// 256 print in decimal ("modbus:2", "motion:1"), larger ones in hex as their specs write them.
  [[nodiscard]] std::string describe() const;
};

/// Faults the motion core raises itself (supervision); values are stable and documented in
/// docs/ARCHITECTURE.md.
enum class MotionFault : int {
  none = 0,
  following_error = 1,          ///< static window exceeded
  following_error_dynamic = 2,  ///< speed-dependent window (1.5 v/Kv, clamped) exceeded
  standstill = 3,               ///< left the standstill window while holding
  in_position_timeout = 4,      ///< target not inside the in-position window in time
  software_limit = 5,           ///< a target or velocity move would cross a software limit
  drive_fault = 6,              ///< the drive reported a fault (details in the drive's Fault)
  drive_lost = 7,               ///< communication with the drive lost / stale feedback
  not_enabled = 8,              ///< motion commanded while the drive is not enabled
  invalid_command = 9,          ///< command rejected (bad limits, NaN, unknown mode)
};
const std::error_category& motion_category() noexcept;
inline std::error_code make_error_code(MotionFault f) noexcept {
  return {static_cast<int>(f), motion_category()};
}

/// Simulated-plant faults (mocks/sim_drive), used by every transport mock behind the plant.
enum class PlantFault : int {
  none = 0,
  encoder = 1,           ///< encoder signal lost
  not_ready = 2,         ///< power stage not ready
  following_blowup = 3,  ///< the plant stops following its command (e.g. mechanical jam)
};
const std::error_category& plant_category() noexcept;
inline std::error_code make_error_code(PlantFault f) noexcept {
  return {static_cast<int>(f), plant_category()};
}

}  // namespace hil

template <>
struct std::is_error_code_enum<hil::MotionFault> : std::true_type {};
template <>
struct std::is_error_code_enum<hil::PlantFault> : std::true_type {};
