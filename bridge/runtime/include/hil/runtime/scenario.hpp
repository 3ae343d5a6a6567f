// SPDX-License-Identifier: MIT
#pragma once
// A scenario as loaded from YAML (docs/scenarios.md documents every key): a machine (axes,
// each with its scaling, limits, supervision windows and a `drive:` block for its transport),
// a program (steps run in order on the cycle thread) and expectations (checked while it runs).
// Pure data; the loader (scenario_loader.hpp) fills it, the runner (runner.hpp) executes it.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "hil/core/clock.hpp"
#include "hil/runtime/coupling_spec.hpp"
#include "hil/runtime/realtime.hpp"

namespace hil::runtime {

/// Where a scenario element came from, for messages ("demo.yaml:42: program[3]").
struct SourceRef {
  int line = 0;      ///< 1-based; 0 when unknown
  std::string path;  ///< key path, e.g. "program[3].move_absolute"
};

enum class FaultReaction : std::uint8_t { quick_stop, stop, disable };

struct AxisSpec {
  std::string name;
  std::string units = "mm";
  std::int64_t inc_per_unit_num = 1000;  ///< drive increments per user unit = num / den, exact
  std::int64_t inc_per_unit_den = 1;
  bool rotary = false;
  double modulo = 360.0;  ///< units per turn (rotary only)
  // Limits (units/s, units/s², units/s³). jerk 0 = trapezoidal (no jerk limit).
  double max_velocity = 0.0;
  double max_acceleration = 0.0;
  double max_jerk = 0.0;
  double quick_stop_deceleration = 0.0;  ///< 0 = 4 x max_acceleration
  double jog_velocity = 0.0;             ///< 0 = max_velocity / 10
  std::optional<double> soft_limit_min;
  std::optional<double> soft_limit_max;
  double backlash = 0.0;  ///< units, compensated on direction reversal
  // Supervision (units, seconds).
  double following_error_window = 0.0;   ///< static window; 0 = 10 x in_position window, at least 1 unit
  bool following_error_dynamic = false;  ///< window = clamp(1.5 v / Kv, min, max)
  double following_error_kv_per_s = 0.0;
  double following_error_min = 0.0;
  double following_error_max = 0.0;
  double standstill_window = 0.0;   ///< 0 = 2 x in_position window
  double in_position_window = 0.0;  ///< 0 = 0.01 units
  std::optional<Duration> in_position_timeout;
  std::optional<Duration> enable_timeout;
  std::optional<Duration> feedback_timeout;
  FaultReaction fault_reaction = FaultReaction::quick_stop;
  bool from_controller = false;  ///< scaling, limits and supervision come from the controller's parameters
  YAML::Node drive;              ///< the `drive:` map, handed to the transport factory
  std::string transport;         ///< drive.transport
  SourceRef source;
};

enum class MoveDirection : std::uint8_t { shortest, positive, negative };

/// Optional per-move limits; unset fields fall back to the axis limits.
struct MoveLimits {
  std::optional<double> velocity;
  std::optional<double> acceleration;
  std::optional<double> jerk;  ///< 0 = trapezoidal
};

// ---- program steps --------------------------------------------------------------------------
struct EnableStep {
  std::vector<std::string> axes;
};
struct DisableStep {
  std::vector<std::string> axes;
};
struct ResetStep {
  std::vector<std::string> axes;
};
struct HomeStep {
  std::vector<std::string> axes;
};
struct MoveAbsoluteStep {
  std::string axis;
  double position = 0.0;  ///< units
  MoveLimits limits;
  std::optional<MoveDirection> direction;  ///< rotary modulo axes
};
struct MoveRelativeStep {
  std::string axis;
  double distance = 0.0;  ///< units
  MoveLimits limits;
};
struct MoveVelocityStep {
  std::string axis;
  double velocity = 0.0;  ///< signed units/s
  MoveLimits limits;      ///< acceleration/jerk
};
struct JogStep {
  std::string axis;
  bool positive = true;  ///< at the axis' jog_velocity
  Duration duration{};   ///< jog this long, then stop
};
struct StopStep {
  std::vector<std::string> axes;
};
struct QuickStopStep {
  std::vector<std::string> axes;
};
struct WaitStep {
  Duration duration{};
};
struct WaitInPositionStep {
  std::vector<std::string> axes;
};

enum class Quantity : std::uint8_t { position, velocity, following_error };
enum class Comparison : std::uint8_t { above, below };
/// `wait_until`: one condition on one axis.
struct Condition {
  std::string axis;
  enum class Kind : std::uint8_t { compare, state, fault, no_motion, in_position } kind = Kind::compare;
  Quantity quantity = Quantity::position;
  Comparison comparison = Comparison::above;
  double value = 0.0;
  std::string state;       ///< Kind::state: axis state name
  std::string fault_code;  ///< Kind::fault: "" = any fault, else "category:value"
};
struct WaitUntilStep {
  Condition condition;
};
struct InjectFaultStep {
  std::string axis;
  std::string fault;
  bool active = true;
};
/// `acknowledge: acknowledge | reset | power_cycle`: the operator's acknowledgement of the
/// controller's device errors (Controller::acknowledge); axes whose device errors are all cleared
/// are reset. Needs a `controller:` block.
struct AcknowledgeStep {
  enum class How : std::uint8_t { acknowledge, reset, power_cycle } how = How::acknowledge;
};
/// `plc:` the PLC side of a controller's S5 data blocks (Controller::read_data_word /
/// write_data_word; docs/scenarios.md "PLC steps"): write a command word or bit, wait for a status
/// word or bit, or check one at once. Needs a `controller:` block.
struct PlcOperand {
  enum class Kind : std::uint8_t {
    word,         ///< DW dw (`value`), 0..0xFFFF or -32768..-1 (two's complement)
    double_word,  ///< DW dw (high) and DW dw+1 (low) as one signed 32-bit value (`dd`), e.g. the actual value
    bit,          ///< bit 0..15 of DW dw (`bit`, `state`)
    left_byte,    ///< DL dw (`dl`): bits 15..8
    right_byte,   ///< DR dw (`dr`): bits 7..0
  } kind = Kind::word;
  int db = 0;
  int dw = 0;
  int bit = 0;
};
struct PlcStep {
  enum class Action : std::uint8_t { write, wait, expect } action = Action::write;
  PlcOperand operand;
  std::int64_t value = 0;  ///< word / dd / byte value, or 0/1 for a bit
};
struct Step;
struct ParallelStep {
  std::vector<Step> steps;
};

using StepAction = std::variant<EnableStep, DisableStep, ResetStep, HomeStep, MoveAbsoluteStep, MoveRelativeStep,
                                MoveVelocityStep, JogStep, StopStep, QuickStopStep, WaitStep, WaitInPositionStep,
                                WaitUntilStep, InjectFaultStep, ParallelStep, CoupleStep, AcknowledgeStep, PlcStep>;

struct Step {
  StepAction action;
  std::optional<Duration> at;       ///< start no earlier than this scenario time
  std::optional<Duration> timeout;  ///< fail the run when the step has not completed in time
  bool wait = true;                 ///< false: start it and go on at once
  std::string name;                 ///< "move_absolute x" for messages
  SourceRef source;
};

// ---- expectations ---------------------------------------------------------------------------
struct PositionExpectation {
  double value = 0.0;
  double tolerance = 0.0;
  std::optional<Duration> at;  ///< checked at exactly this time
  std::optional<Duration> by;  ///< inside tolerance at some cycle up to this time
};
struct FaultExpectation {
  std::string code;            ///< "" = any fault; else "motion:1", "cia402:0x7305"
  std::optional<Duration> by;  ///< the fault must appear no later than this
};
struct StateExpectation {
  std::string state;
  std::optional<Duration> at;  ///< default: end of run
};
struct NoFaultExpectation {};
struct MaxFollowingErrorExpectation {
  double value = 0.0;
};

/// `moves: N`: the axis started exactly N moves over the run (entries into state `moving` from
/// rest, i.e. from a state other than `moving` and `stopping`: a stop and a resume are two moves;
/// a move commanded on top of a running one, or while the axis still brakes, is none).
struct MovesExpectation {
  std::uint64_t count = 0;
};

using ExpectationKind = std::variant<PositionExpectation, FaultExpectation, StateExpectation, NoFaultExpectation,
                                     MaxFollowingErrorExpectation, MovesExpectation>;
struct Expectation {
  std::string axis;  ///< one axis (a list in the file becomes one expectation per axis)
  ExpectationKind kind;
  SourceRef source;
};

// ---- controller and I/O (docs/controllers.md) ------------------------------------------------
/// `controller: {device: wf725-726, parameters: md.txt, ...}`: the axes named like the device's
/// axes take their configuration from its parameter file.
struct ControllerBlock {
  std::string device;
  std::string parameters;             ///< path, relative paths resolved against the scenario's folder
  std::vector<std::string> programs;  ///< same
  std::optional<Duration> cycle;      ///< overrides the device's controller cycle
  std::map<std::string, std::string, std::less<>> options;  ///< the block's other keys, as text
  SourceRef source;
};

/// One entry of `io:` (a stimulus the scenario drives into the controller's inputs).
struct IoStimulus {
  enum class Kind : std::uint8_t { set, pulse, cam, mark } kind = Kind::set;
  std::string signal;  ///< an I/O name or the device's address ("I0.00.3", "E 4.1")
  bool value = true;
  std::optional<Duration> at;      ///< set/pulse at this scenario time
  std::optional<Condition> when;   ///< ... or once this condition holds
  Duration width{};                ///< pulse width (0 = one controller cycle); mark pulse width
  std::string axis;                ///< cam / mark
  std::optional<double> from, to;  ///< cam: active position range (either may be open)
  bool active_low = false;         ///< cam: normally-closed contact
  double position = 0.0;           ///< mark position
  double accuracy = 0.0;           ///< mark: latch accuracy in units
  SourceRef source;
};

/// One analog entry of `io:` (`{analog: NAME, value: V, at: T, ramp: D}`): from scenario time
/// `at` the device's analog input NAME (the CLM1.4's AE1..AE4, in volts) ramps linearly to `value`
/// over `ramp` (0 = a step) and holds it (hil::controllers::AnalogSchedule). Entries of one input
/// come in increasing `at`.
struct AnalogStimulus {
  std::string input;   ///< the device's name of the input ("AE1")
  double value = 0.0;  ///< in the input's unit (Controller::resolve_analog)
  Duration at{};
  Duration ramp{};
  SourceRef source;
};

/// One I/O entry of `expect:` (`io: <signal>` with state / edges / first_edge).
struct IoExpectation {
  std::string signal;
  enum class Kind : std::uint8_t { state, edges, first_edge } kind = Kind::state;
  enum class Edge : std::uint8_t { rising, falling, any } edge = Edge::rising;
  bool state = true;
  std::optional<Duration> at;         ///< state: at this time (default: end of run)
  std::uint64_t count = 0;            ///< edges: exact number over the run
  std::optional<Duration> after, by;  ///< first_edge: inside [after, by]
  SourceRef source;
};

/// A controller entry of `expect:` (needs a `controller:` block): `{controller: NAME, value: V}`
/// checks a value the device shows by name (Controller::resolve_value: a variable, a counter, a
/// task's program line, an I/O byte); `{device_error: CODE}` that the device raised this error
/// (on any of its axes or on the whole controller).
struct ControllerExpectation {
  enum class Kind : std::uint8_t { value, device_error } kind = Kind::value;
  std::string name;            ///< value: the device's name of the value ("V600", "task1.line")
  double value = 0.0;          ///< value: expected (exact unless `tolerance`)
  std::string value_text;      ///< value: as the file writes it ("0x73", "-87654321.654321")
  double tolerance = 0.0;      ///< value: |actual - value| <= tolerance passes
  std::optional<Duration> at;  ///< value: at this time (default: the end of the run)
  std::optional<Duration> by;  ///< value: at some cycle up to this time; device_error: raised by then
  std::string code;            ///< device_error: "clm14.diagnostic:0E" (as the manual writes it)
  SourceRef source;
};

/// `io_links:` (docs/scenarios.md): real I/O wired to the controller's image. One entry = one
/// device (a GPIO chip, a Modbus I/O terminal, an axis' drive); its `inputs:` feed image input (or
/// data) bits, its `outputs:` are fed by image output (or marker) bits.
struct GpioLinkDevice {
  std::string chip;  ///< libgpiod chip (name, path, label or number); "mock": in-process mock lines
  std::string consumer = "hilbridge";
};
struct GpioLinkBit {
  std::optional<unsigned> offset;  ///< chip offset, or
  std::string name;                ///< a line name (gpioinfo)
  bool active_low = false;         ///< image bit = !line level (inputs), line = !bit (outputs)
  std::string bias;                ///< inputs: as-is (also when empty), disabled, pull-up, pull-down
  /// `chip: mock` inputs: the line level over scenario time (level before the first entry: 0).
  std::vector<std::pair<Duration, bool>> mock;
};

/// `modbus:` (docs/scenarios.md): a Modbus/TCP digital I/O terminal.
struct ModbusLinkDevice {
  std::string bus = "sim";  ///< "sim" (the in-process simulated terminal) or "tcp://HOST[:PORT]"
  std::string listen;       ///< sim only: "HOST:PORT" where peers reach the simulated terminal ("": none)
  int unit = 1;             ///< unit id 0..255 (tcp)
  Duration poll{std::chrono::milliseconds(10)};
  Duration timeout{std::chrono::milliseconds(100)};  ///< response timeout (and connect timeout)
  std::optional<Duration> stale_after;               ///< default: timeout + 2 poll
  std::string status;                                ///< a signal set to 1 while the terminal answers ("": none)
  SourceRef status_source;
};
struct ModbusLinkBit {
  bool coil = false;          ///< coil (FC 1/5/15), else discrete input (FC 2)
  std::uint16_t address = 0;  ///< 0-based protocol address
};

/// `- drive: AXIS`: the digital I/O of the axis' drive (DriveFeedback::digital_inputs, CiA 402
/// 0x60FD layout; DriveCommand::digital_outputs, 0x60FE:1 layout).
struct DriveLinkDevice {
  std::string axis;  ///< a machine axis
};
struct DriveLinkBit {
  unsigned bit = 0;  ///< 0..31
};

struct IoLinkBit {
  std::string signal;  ///< an I/O name or the device's address
  std::variant<GpioLinkBit, ModbusLinkBit, DriveLinkBit> where;
  SourceRef source;
};

struct IoLink {
  std::variant<GpioLinkDevice, ModbusLinkDevice, DriveLinkDevice> device;
  std::vector<IoLinkBit> inputs;   ///< device -> image (input or data bits)
  std::vector<IoLinkBit> outputs;  ///< image (output or marker bits) -> device
  SourceRef source;
};

struct Scenario {
  std::string file;  ///< as given (for messages, and relative paths of transports)
  std::string name;
  std::string description;
  Duration period{std::chrono::milliseconds(1)};
  std::optional<Duration> duration;             ///< fixed run length; default: until the program is done and axes rest
  Duration timeout{std::chrono::seconds(600)};  ///< the run fails when it lasts longer
  /// `cut_off: expected`: a `duration:` that ends the run while program steps are left or an axis
  /// still moves is intended (reported, not a failure). Default `cut_off: fail`.
  bool cut_off_expected = false;
  /// `realtime:` (true/false or a map); applies to runs on real time only (`hilbridge run`
  /// options override it). Unset: normal scheduling.
  std::optional<RealtimeOptions> realtime;
  std::vector<AxisSpec> axes;
  std::vector<VirtualMasterSpec> masters;  ///< machine.masters (coupling)
  std::vector<CamSpec> cams;               ///< machine.cams (coupling)
  std::vector<CouplingSpec> couplings;     ///< machine.couplings
  std::vector<Step> program;
  std::vector<Expectation> expectations;
  std::optional<ControllerBlock> controller;
  std::vector<IoStimulus> io;
  std::vector<AnalogStimulus> analog;  ///< `io:` entries with `analog:`
  std::vector<IoLink> io_links;
  std::vector<IoExpectation> io_expectations;
  std::vector<ControllerExpectation> controller_expectations;
  YAML::Node document;  ///< keeps the drive nodes' document alive

  [[nodiscard]] const AxisSpec* find_axis(const std::string& name) const noexcept;
};

[[nodiscard]] std::string_view to_string(FaultReaction r) noexcept;
[[nodiscard]] std::string_view to_string(MoveDirection d) noexcept;

}  // namespace hil::runtime
