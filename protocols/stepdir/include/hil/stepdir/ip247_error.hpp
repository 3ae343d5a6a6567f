// SPDX-License-Identifier: MIT
#pragma once
// SIMATIC S5 IP247 error numbers (manual 6ES5 998-5SB12 §7.2). The enum values ARE the manual's
// numbers, so `hil::Fault::code.value()` lines up with the manual (COM247 shows 80h + value).
//   - Ip247Error: module (axis) errors, category "ip247" (§7.2.2, digest §6.1).
//   - Ip247MdError: machine-data errors, category "ip247-md" (§7.2.1, digest §6.2).

#include <system_error>

namespace hil::stepdir {

enum class Ip247Error : int {
  none = 0,
  speed_out_of_range = 7,    ///< warning: frequency clamped to 1 Hz..fmax, move still runs
  reference_missing = 10,    ///< absolute move without a reference point
  no_machine_data = 14,      ///< no or wrong MD (no valid configuration)
  faulty_machine_data = 15,  ///< MD rejected (detail: Ip247MdError)
  traversing_range_exceeded = 23,
  limit_start_overrun = 25,  ///< HW limit "Anfang" (backward side) seen while moving toward it
  limit_end_overrun = 26,    ///< HW limit "Ende" (forward side)
  external_stop = 27,
  sw_limit_start_overrun = 28,
  sw_limit_end_overrun = 29,
  pulse_generator_defective = 34,  ///< we use it for a GPIO write failure on the step/dir lines
  power_section_off = 53,          ///< BB (ready) input low: switch the power section on
  ramp_table_generation = 54,      ///< fmax/fss/a cannot form a ramp
  reference_cam_defective = 59,    ///< cam not left within 2500 single steps
  // Operating modes and traversing programs (bridge/controllers/s5):
  pg_job_list_full = 1,           ///< warning
  job_not_allowed = 2,            ///< undefined BA or nonsensical command; aborts the running BA
  block_stored = 3,               ///< warning: teach-in block stored
  axis_running = 4,               ///< axis running, input impossible
  ag_job_list_full = 5,           ///< warning
  waits_for_external_start = 6,   ///< warning: external start/stop input is 1
  state_after_power_failure = 8,  ///< warning
  module_number_locked = 12,      ///< module number cannot be changed while a correct MD set exists
  db_not_present = 13,            ///< DB (program, MD) not present
  max_programs = 18,              ///< 255 programs stored
  teach_in_exclusive = 22,        ///< another axis in teach-in / VP change during teach-in
  program_memory_full = 24,       ///< not enough memory for the VP (6000 chars)
  mode_not_allowed_in_teach_in = 30,
  block_start = 35,             ///< error at block start
  subprogram_number = 36,       ///< subprogram DB number too large
  g_not_allowed = 37,           ///< G function not allowed (e.g. G70/G71 on a degree axis)
  endless_loop_not_outer = 38,  ///< endless loop only as the outermost loop (and with a motion or dwell)
  nesting_too_deep = 39,        ///< loops plus subprogram calls deeper than 5
  x_wrong = 40,
  f_wrong = 41,
  path_too_long = 42,
  speed_too_high = 43,  ///< programmed speed above vmax
  block_end = 44,
  program_end_before_loop_end = 45,
  mode_not_allowed_on_axis = 46,              ///< wrong tile (VP jobs on an axis, axis BAs on the data channel)
  no_direction_change_in_flying_change = 47,  ///< rotary G10 chain needs G26/G27
  program_faulty = 48,                        ///< VP rejected by the syntax check (number in VP DB DW3)
  program_exists = 49,                        ///< no overwrite: delete the program first
  program_active = 51,                        ///< a running program cannot be changed or deleted
  flying_change_failed = 52,                  ///< one of the G10 conditions violated
  plc_failed = 55,                            ///< BASP: all axes aborted
  ramp_table_access = 56,
  block_not_interpreted = 57,
  speed_too_low = 58,
  deleted_from_directory_only = 61,
  illegal_path = 62,         ///< |value| >= 100 m (rotary relative > 200 m)
  illegal_tool_offset = 63,  ///< rotary: |T| >= range
  program_waits_for_continuation = 65,
  path_not_bcd = 66,
  speed_not_bcd = 67,
};
/// Codes 1..9 are warnings/messages: they are latched like errors but abort nothing (§7.2).
[[nodiscard]] constexpr bool ip247_is_warning(Ip247Error e) noexcept {
  return static_cast<int>(e) >= 1 && static_cast<int>(e) <= 9;
}

enum class Ip247MdError : int {
  none = 0,
  pulse_duration = 2,         ///< not 1..31 µs, or more than half the period of fmax
  max_frequency = 3,          ///< fmax outside 12 Hz..100 kHz (see docs/stepdir.md on the range)
  speed = 4,                  ///< jog/incremental speed frequency not within 1 Hz..fmax
  frequency_increase = 6,     ///< a not 20..2 599 999 Hz/s (= mHz/ms), or tau not 5..2600 ms
  reference_direction = 15,   ///< reference direction / synchronisation value invalid
  ramp_generation = 16,       ///< ramp table could not be generated (e.g. fss >= fmax)
  reference_speed = 17,       ///< f_ref <= fss or > fmax
  edge_polarity = 18,         ///< polarity not positive/negative edge
  limit_polarity = 19,        ///< the configured limit switches are not present (read as actuated)
  backlash = 20,              ///< not 0..64 999
  start_stop_frequency = 22,  ///< fss not 1 Hz..10 kHz
  patterns = 10,              ///< energisation patterns not 4..40
};

const std::error_category& ip247_category() noexcept;
const std::error_category& ip247_md_category() noexcept;
inline std::error_code make_error_code(Ip247Error e) noexcept {
  return {static_cast<int>(e), ip247_category()};
}
inline std::error_code make_error_code(Ip247MdError e) noexcept {
  return {static_cast<int>(e), ip247_md_category()};
}

}  // namespace hil::stepdir

template <>
struct std::is_error_code_enum<hil::stepdir::Ip247Error> : std::true_type {};
template <>
struct std::is_error_code_enum<hil::stepdir::Ip247MdError> : std::true_type {};
