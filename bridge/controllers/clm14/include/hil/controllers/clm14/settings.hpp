// SPDX-License-Identifier: MIT
#pragma once
// The parameter values the CLM1.4 model runs on (manual §8, digest clm14.md §3.7-§3.9), taken
// from the parameter texts as the device stores them ("B011" -> "0200 0000 0"). The texts are
// checked field by field against the profile elsewhere (DeviceData::check_parameter); this
// reads them. A text that cannot be read is error 02 naming the parameter, and nothing of the
// set is taken over.

#include <array>
#include <expected>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "hil/controllers/clm14/address.hpp"
#include "hil/controllers/clm14/instruction.hpp"

namespace hil::controllers::clm14 {

enum class MotionType : std::uint8_t { rotary = 0, linear = 1, rotary_table = 2 };

struct AxisSettings {
  bool enabled = false;                    ///< axis 1 always; 2..4 per B000
  MotionType motion = MotionType::linear;  ///< Ax00 field 1
  int mode = 0;                            ///< Ax00 field 2 (0 normal .. 5 flying cutoff)
  int master = 0;                          ///< Ax00 field 3: 0 none, 1..3 axis, 5 master encoder 1 (profile decision)
  bool test_mode = false;                  ///< Ax00 field 4: flying cutoff test mode (internal material clock)
  bool wheel_option2 = false;              ///< Ax00 field 5: measuring-wheel option 2 (with mode 3 [decided])
  double feed_constant = 10.0;             ///< Ax01, IU per encoder revolution
  double min_limit = -111111.111;          ///< Ax03, IU
  double max_limit = 100000.0;             ///< Ax04, IU
  double modulo = 0.0;                     ///< Ax05 value (rotary table), IU
  int modulo_path = 0;                     ///< Ax05 m: 0 programmed direction, 1 shortest path
  double vmax = 100.0;                     ///< Ax06, IU/s
  double jog_velocity = 100.0;             ///< Ax07, IU/s
  double acceleration = 10.0;              ///< Ax08, IU/s²
  int accel_permille = 0;                  ///< Ax09 (0 = 1000 ‰)
  int decel_permille = 0;
  double jerk_time_s = 0.0;                           ///< Ax10 as entered (rounded up to 2^n cycles when used)
  std::optional<BitAddress> feed_angle_input;         ///< Ax15 field 1
  std::optional<BitAddress> interrupt_input;          ///< Ax15 field 2
  int wheel_window1 = 0;                              ///< Ax16 ww 1: wheel-motor difference -> 4C/7C (0 = off)
  int wheel_window2 = 0;                              ///< Ax16 ww 2: -> the "Tolerance 2 exceeded" output (0 = off)
  std::optional<BitAddress> tolerance2_output;        ///< Ax16 field 3
  int encoder_pulses = 1024;                          ///< Ax19 pulses/rev
  int encoder_revolutions = 1024;                     ///< Ax19 revolutions / ratio
  int encoder_type = 0;                               ///< Ax20 field 1: 0 incremental, 1/2 absolute, 3 controlled
  std::optional<BitAddress> homing_start_input;       ///< Ax23 field 1
  std::optional<BitAddress> home_switch_input;        ///< Ax23 field 2
  std::optional<BitAddress> homed_output;             ///< Ax24 field 1
  int homing_velocity_permille = -100;                ///< Ax24 field 2 (sign = direction)
  int homing_type = 0;                                ///< Ax24 field 3
  double home_offset = 0.0;                           ///< Ax25, IU
  std::optional<BitAddress> reached_output;           ///< Ax27 "position reached"
  double reached_window = 0.0;                        ///< Ax27 window, IU
  std::optional<BitAddress> presignal_output;         ///< Ax29
  double presignal_pulse_s = 0.0;                     ///< 0 = steady
  double presignal_distance = 0.0;                    ///< IU
  std::optional<BitAddress> open_feed_roll_input;     ///< Ax30 field 1
  std::optional<BitAddress> open_feed_roll_output;    ///< Ax30 field 2: "open feed roll enabled"
  std::optional<BitAddress> wheel_input;              ///< Ax31 "measuring wheel active" (none = always, modes 3/4)
  std::optional<BitAddress> velocity_reached_output;  ///< Ax32 left
  std::optional<BitAddress> decelerating_output;      ///< Ax32 right
  int feedforward = 0;                                ///< Ax11 f: 0 off, 1 on, 2..9 averaging of 2..256 values
  // Flying cutoff (axis 1, mode 5)
  std::optional<BitAddress> cut_inhibit_input;      ///< Ax33 field 1: a pulse suppresses sync until Immediate cut
  std::optional<BitAddress> cut_inhibit_output;     ///< Ax33 field 2: on while the cut is inhibited
  std::optional<BitAddress> immediate_cut_input;    ///< Ax34 field 1: Immediate cut (Auto) / manual cut vector (Manual)
  int manual_cut_line = 0;                          ///< Ax34 field 2: the manual-cut program (ends with RTS)
  bool indexing = false;                            ///< Ax34 field 3: material since the manual cut counts
  std::optional<BitAddress> reverse_inhibit_input;  ///< Ax35: after EOS the carriage waits for it
  std::optional<BitAddress> rapid_stop_input;       ///< Ax36 field 1
  int rapid_stop_line = 0;                          ///< Ax36 field 2: program ending with EOS (0 = none)
  double max_stroke = 0.0;                          ///< Ax37 field 1, IU (0 = off)
  int max_stroke_line = 0;                          ///< Ax37 field 2: program ending with EOS (0 = none)
  std::optional<BitAddress> reverse_opt_input;      ///< Ax39 field 1: reverse optimisation on while set
  std::optional<BitAddress> reverse_opt_output;     ///< Ax39 field 2: on while an optimised return runs
  double reverse_wait_s = 0.0;                      ///< Ax40 field 1: wait at the origin, s
  int reverse_min_accel_permille = 0;               ///< Ax40 field 2: minimum reverse acceleration, ‰ of Ax08
  int reverse_velocity_window_permille = 0;         ///< Ax40 field 3: material speed rise, ‰ of Ax06
  std::optional<BitAddress> start_0000_input;       ///< Ax38 field 1: a rising edge restarts task 1 at 0000
  bool raster_edge = false;                         ///< Ax38 field 2: raster detection 0 level / 1 edge
  bool always_0000 = false;                         ///< Ax38 field 3: Manual -> Automatic always begins at 0000
  double tool_width = 0.0;                          ///< Ax41, IU: added to the LML length
  double crop_length = 0.0;                         ///< Ax42 field 1, IU
  std::optional<BitAddress> crop_input;             ///< Ax42 field 2: rising edge at home = crop cut

  [[nodiscard]] bool absolute_encoder() const noexcept { return encoder_type == 1 || encoder_type == 2; }
  /// Ax00 mode 3 or 4: the measuring wheel (axis 1: master encoder 1, axis 2: master encoder 2).
  [[nodiscard]] bool measuring_wheel() const noexcept { return mode == 3 || mode == 4; }
  /// Option 2 (motor loop + correction): mode 4, or mode 3 with the option-2 digit [decided].
  [[nodiscard]] bool wheel_correction() const noexcept { return mode == 4 || (mode == 3 && wheel_option2); }
};

/// Master encoder 1 (C000-C002, §8.4). C002 = 0: not used.
struct MasterEncoderSettings {
  int pulses = 1250;                            ///< C000 pulses/rev (× 4 quadrature counts)
  bool inverted = false;                        ///< C001 d
  int averaging = 0;                            ///< C001 a: 0 off, 1..7 = 2..128 values
  double feed_constant = 20.0;                  ///< C002, IU per revolution
  std::optional<BitAddress> no_material_input;  ///< C008 field 1: "No Material"
  int no_material_variable = 0;                 ///< C008 field 2: V600..V999 holding the material speed, IU/s
  [[nodiscard]] bool used() const noexcept { return feed_constant > 0.0 && pulses > 0; }
};

struct Settings {
  MasterEncoderSettings me1{};
  /// Master encoder 2 (C004-C006: the measuring wheel of axis 2, FUN's channel 6). C006 = 0: not used.
  MasterEncoderSettings me2{.pulses = 0,
                            .inverted = false,
                            .averaging = 0,
                            .feed_constant = 0.0,
                            .no_material_input = std::nullopt,
                            .no_material_variable = 0};
  std::array<AxisSettings, 4> axes{};
  int axis_count = 1;               ///< highest enabled axis
  double cycle_ms = 2.0;            ///< B010 (0.0 = auto: 2 ms for 1-2 axes, 3 for 3, 4 for 4)
  std::array<int, 5> task_start{};  ///< B011/B012 start lines of tasks 2..5 (index 1..4); task 1 = 0
  std::array<bool, 5> task_used{true, false, false, false, false};  ///< a start line 0000 = task not used
  std::optional<BitAddress> manual_vector_input;                    ///< B014
  bool manual_vector_on_mode_change = false;
  int manual_vector_line = 0;
  std::optional<BitAddress> interrupt_vector_input;  ///< B015
  int interrupt_vector_edge = 0;                     ///< 0..3 (rising/falling, inhibited in JSR or not)
  bool interrupt_vector_aborts_move = false;
  int interrupt_vector_line = 0;
  int restart_line = 0;               ///< B016; 0 = no restart program
  int error_code_byte = 0;            ///< B018 f: 0 off, 1..6 = Q1.00..Q1.05
  std::array<int, 7> output_clear{};  ///< B018 g per output byte Q1.00..Q1.06: 0 clear, 1 keep until cleared, 2 never
  /// B017 override source of axes 1..4: 0 off, 1-4 analog input 1-4, 5 binary I1.01.0-7, 6 Gray I1.01.4-7.
  std::array<int, 4> override_source{};
  /// B017 first digit: the analog inputs' moving average over 2^(code + 3) NC cycles (analog_input.hpp).
  int analog_averaging = 0;
};

/// Reads a parameter's stored text ("" when the set has none).
using ParameterLookup = std::function<std::string(std::string_view number)>;

/// Build the settings from a whole parameter set. Error 02 names the first parameter that
/// cannot be read (ProgramError::message starts with its number, line = -1).
[[nodiscard]] std::expected<Settings, ProgramError> make_settings(const ParameterLookup& lookup);

}  // namespace hil::controllers::clm14
