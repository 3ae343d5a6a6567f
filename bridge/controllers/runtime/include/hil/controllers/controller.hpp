// SPDX-License-Identifier: MIT
#pragma once
// The controller interface: a device model (CLM1.4, IP247, WF 725/726, AMKASYN, ELG) that owns
// its parameter set, its program store, its I/O image and commands its axes
// (hil::motion::Axis), stepped once per controller cycle by the run's scheduler.
//
// Life cycle (the runtime drives it; docs/controllers.md):
//   1. construction by the device's factory from a ControllerSpec: the device loads and
//      validates its parameter file with the profile engine, lays out its IoImage, names its
//      signals, and declares its axes with add_axis() (AxisConfig from the parameters);
//   2. the runtime builds one motion::Axis per declared axis on the drive the scenario's
//      `machine:` block gives it, then calls bind_axes() (the axes outlive the controller's
//      run; the controller is the only one that commands them);
//   3. the runtime attaches I/O sources and sinks (scenario stimuli, cams, GPIO, Modbus,
//      CiA 402, the trace) to io();
//   4. every controller cycle (cycle_period(), a whole multiple of the run period, e.g. CLM
//      B010, WF 4/6/8 ms, the IP247 module cycle) the runtime calls step() after the axes'
//      update() of that run cycle.
//
// step() is final (non-virtual) and does, in this order: io().read_inputs(now); hard-limit
// switches (LimitSwitches) stop an axis moving onto an active switch; a new axis fault or
// limit-switch hit becomes a device error through map_axis_fault() and its reaction is applied
// to the axes; on_cycle(cycle) (the device logic); io().write_outputs(now).
//
// Thread: every member runs on the cycle thread; step() and on_cycle() never throw, never block
// and are deterministic on virtual time (no clock other than the CycleTime passed in).

#include <cstdint>
#include <expected>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "hil/controllers/analog_stimulus.hpp"
#include "hil/controllers/device_error.hpp"
#include "hil/controllers/io_address_s5.hpp"
#include "hil/controllers/io_image.hpp"
#include "hil/core/clock.hpp"
#include "hil/core/drive.hpp"
#include "hil/core/fault.hpp"
#include "hil/motion/axis.hpp"
#include "hil/motion/axis_config.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/profile.hpp"

namespace hil::controllers {

/// What a scenario's `controller:` block gives the device's factory.
struct ControllerSpec {
  std::string device;                                       ///< profile name: "clm14", "ip247", "wf725-726", ...
  std::filesystem::path parameters;                         ///< parameter file in the device's own format
  std::vector<std::filesystem::path> programs;              ///< program files (device format), may be empty
  std::map<std::string, std::string, std::less<>> options;  ///< further device keys, as text
  std::optional<Duration> cycle;                            ///< overrides the device's cycle time
  std::string file;                                         ///< scenario file (for ConfigError)
  int line = 0;                                             ///< line of the `controller:` block
};

/// Hard-limit switch inputs of one axis (WF 725/726 range-limit switches, IP247 limit switches
/// with NO/NC, CLM travel-limit inputs). A switch is active when its input is 1 (NO) or 0 (NC).
struct LimitSwitches {
  std::optional<BitAddress> negative;
  std::optional<BitAddress> positive;
  bool normally_closed = false;
};

/// Reference-point (homing) settings a device defines for an axis; the device logic uses them.
struct ReferencePoint {
  double position = 0.0;          ///< units: coordinate the reference point takes
  int direction = +1;             ///< +1 / -1: direction of the approach to the cam
  double velocity = 0.0;          ///< units/s approach velocity (0 = the device's default)
  std::optional<BitAddress> cam;  ///< reference cam input
  bool normally_closed = false;   ///< the cam input is active at 0
};

/// One axis as the device's parameters define it.
struct ControllerAxis {
  std::string name;           ///< the axis' name in the scenario, the trace and messages ("1", "X")
  std::string units = "mm";   ///< user unit of `config` ("mm", "deg", "inch", "inc")
  motion::AxisConfig config;  ///< passed motion::validate(); name == `name`
  LimitSwitches limit_switches;
  std::optional<ReferencePoint> reference;
  std::vector<std::string> warnings;  ///< parameters the motion core does not honour (documented)
};

/// Faults the runtime raises itself for an axis (passed to map_axis_fault like MotionFault).
enum class ControllerFault : int {
  none = 0,
  hard_limit_negative = 1,  ///< the negative limit switch became active while moving negative
  hard_limit_positive = 2,  ///< the positive limit switch became active while moving positive
};
const std::error_category& controller_category() noexcept;
inline std::error_code make_error_code(ControllerFault f) noexcept {
  return {static_cast<int>(f), controller_category()};
}

/// A device error number in one of the device's catalogues.
struct DeviceErrorCode {
  const profiles::ErrorCatalogue* catalogue = nullptr;
  int code = 0;
};

/// Result of one controller cycle.
enum class ControllerStatus : std::uint8_t {
  ok,     ///< no device error that blocks motion is active
  error,  ///< a device error with reaction stop, drive_off or needs_reset is latched
};

class Controller {
 public:
  /// `profile` non-null; `parameters` already validated by the device's factory; `cycle` > 0.
  Controller(std::shared_ptr<const profiles::Profile> profile, profiles::ParameterSet parameters, IoLayout layout,
             Duration cycle);
  virtual ~Controller();
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  [[nodiscard]] const profiles::Profile& profile() const noexcept { return *profile_; }
  [[nodiscard]] const std::string& device() const noexcept { return profile_->device; }
  [[nodiscard]] const profiles::ParameterSet& parameters() const noexcept { return parameters_; }
  /// The controller cycle (the runtime steps it every cycle / run period run cycles).
  [[nodiscard]] Duration cycle_period() const noexcept { return cycle_; }
  [[nodiscard]] IoImage& io() noexcept { return io_; }
  [[nodiscard]] const IoImage& io() const noexcept { return io_; }

  /// The axes the device declared, in its order.
  [[nodiscard]] std::span<const ControllerAxis> axis_specs() const noexcept { return specs_; }
  /// Hands the controller its axes, one per axis_specs() entry in that order (non-null, alive for
  /// every later step()). Error text when the count differs.
  std::expected<void, std::string> bind_axes(std::span<motion::Axis* const> axes);
  [[nodiscard]] std::size_t axis_count() const noexcept { return axes_.size(); }
  /// Called by the runtime every run period just before it updates the controller's axis `axis`
  /// (index into axis_specs()), in the machine's axis order, like a coupling's slave: a device
  /// that commands one axis from another's set-point of the same period (the WF 726 split drive)
  /// does it here. The default does nothing. Must not throw or block.
  virtual void before_axis_update(std::size_t /*axis*/, const CycleTime& /*cycle*/) noexcept {}

  /// A bit of the image by name or by the device's own address text ("I0.00.3", "E 4.1"). The
  /// default looks names up only; devices override it to add their codec.
  [[nodiscard]] virtual std::expected<BitAddress, std::string> resolve_bit(std::string_view text) const;

  /// One controller cycle (see the file comment). Never throws.
  ControllerStatus step(const CycleTime& cycle) noexcept;

  /// Analog values the device shows beside its I/O, fixed at construction (the ELG: C's error
  /// against the hobbing linkage): trace columns `ctl_NAME` and one plot chart each. Names carry
  /// the unit ("C_linkage_error_deg"); trace_value(i) is read once per run cycle.
  [[nodiscard]] virtual std::vector<std::string> trace_signals() const { return {}; }
  [[nodiscard]] virtual double trace_value(std::size_t) const noexcept { return 0.0; }

  /// A value the device shows by name, for a scenario's `expect: {controller: NAME, value: V}`
  /// (docs/scenarios.md): a variable, a counter, the program line of a task, an I/O byte, in the
  /// device's own names (the CLM: "V600", "counter.0002", "task1.line", "Q1.02"). Returns a handle
  /// for value(), or what is wrong with the name (listing what the device names). Called once
  /// before the run. The default knows the trace_signals() names.
  [[nodiscard]] virtual std::expected<std::size_t, std::string> resolve_value(std::string_view name) const;
  /// The value of a resolve_value() handle now, in the device's units (exact for integers and for
  /// decimals of up to 15 significant digits); read after every controller step. NaN when the
  /// device cannot show it now. Cycle thread; never throws.
  [[nodiscard]] virtual double value(std::size_t handle) const noexcept { return trace_value(handle); }
  /// An analog input of the device by name, for a scenario's `io: - {analog: NAME, ...}`
  /// (docs/scenarios.md; the CLM1.4: AE1..AE4 in volts): its handle, range and unit, or what is
  /// wrong with the name. Called once before the run. The default: the device has none.
  [[nodiscard]] virtual std::expected<AnalogInputSpec, std::string> resolve_analog(std::string_view name) const;
  /// Sets a resolve_analog() input to `value` (in its unit, within its range), as the hardware's
  /// signal; the device samples it in its cycle. Cycle thread (called before on_cycle); never throws.
  virtual void set_analog(std::size_t /*handle*/, double /*value*/) noexcept {}
  /// The PLC side of a device commanded through S5 data blocks (IP247, WF 725/726): data word
  /// `dw` of data block `db` as the PLC's FB or a DB transfer reads and writes it (a scenario's
  /// `plc:` steps, docs/scenarios.md). A write lands at once; the device acts on it (command bits,
  /// parameters) at its next cycle and writes its status words there. The default serves the
  /// data_blocks() the device lays into the image's data area (DW w = bytes base + 2w, base + 2w
  /// + 1, high byte first), so DB bits are also image signals ("DB10 D 12.7"); devices override it
  /// for blocks kept elsewhere (the IP247's program images). Error text for a block the device
  /// does not have or a word beyond it. Cycle thread (or configuration time); never throws.
  [[nodiscard]] virtual std::expected<std::uint16_t, std::string> read_data_word(int db, int dw) const;
  virtual std::expected<void, std::string> write_data_word(int db, int dw, std::uint16_t value);
  /// The data blocks of the interface that lie in the image's data area (none by default).
  [[nodiscard]] virtual std::span<const S5DataBlock> data_blocks() const noexcept { return {}; }

  /// Latched and past device errors.
  [[nodiscard]] const DeviceErrorLatch& errors() const noexcept { return errors_; }
  /// Clears what `how` may clear; axes in error whose device errors are all gone are reset
  /// (motion::Axis::reset). Returns the number of device errors cleared.
  std::size_t acknowledge(Acknowledgement how) noexcept;

 protected:
  /// The device logic of one cycle: program, modes, outputs. Inputs are fresh, outputs are
  /// written after it returns. Must not throw or block.
  virtual void on_cycle(const CycleTime& cycle) noexcept = 0;
  /// The device's number for a supervision fault of axis `axis`: `fault.code` is a MotionFault
  /// (motion category) or a ControllerFault; `status` is the axis' status in that cycle. Return
  /// empty to report it as it is (no device error; the axis fault stays visible as motion:N).
  [[nodiscard]] virtual std::optional<DeviceErrorCode> map_axis_fault(
      std::size_t axis, const hil::Fault& fault, const motion::AxisStatus& status) const noexcept = 0;

  /// Called by bind_axes() once the axes are bound: a device refuses axes it cannot drive (error
  /// text, e.g. a drive that generates its own trajectory where the device needs cyclic set-points).
  [[nodiscard]] virtual std::expected<void, std::string> check_axes() { return {}; }
  /// Declares an axis (construction time only).
  void add_axis(ControllerAxis axis);
  [[nodiscard]] motion::Axis& axis(std::size_t i) noexcept { return *axes_[i]; }
  [[nodiscard]] const motion::Axis& axis(std::size_t i) const noexcept { return *axes_[i]; }
  /// Raises a device error from the device logic and applies its reaction (stop / drive off)
  /// to axis `axis` (-1: every axis). `context` is appended to the catalogue text.
  /// `react` false: the device has applied the reaction itself (a module that brakes its own
  /// pulse output); the error is only latched and reported.
  void raise(const profiles::ErrorCatalogue& catalogue, int code, TimePoint now, int axis = -1,
             std::string_view context = {}, std::optional<AckRule> ack = {}, bool react = true) noexcept;
  /// A self-clearing error whose cause went away.
  bool clear_error(const profiles::ErrorCatalogue& catalogue, int code, int axis = -1) noexcept {
    return errors_.clear(catalogue, code, axis);
  }
  /// Power-up of a device that enables its own drives (the PS, the ELG's PC): the first call enables
  /// every axis; each call returns whether every axis has left disabled / enabling, i.e. takes
  /// set-points. Enabling moves nothing.
  [[nodiscard]] bool power_up_axes() noexcept;
  /// The catalogue `id` of this device's profile; nullptr when it has none by that id.
  [[nodiscard]] const profiles::ErrorCatalogue* catalogue(std::string_view id) const noexcept;

 private:
  void supervise_axes(TimePoint now) noexcept;
  void apply_reaction(const DeviceError& e) noexcept;

  std::shared_ptr<const profiles::Profile> profile_;
  profiles::ParameterSet parameters_;
  Duration cycle_;
  IoImage io_;
  std::vector<ControllerAxis> specs_;
  std::vector<motion::Axis*> axes_;
  std::vector<std::error_code> seen_fault_;  ///< per axis: the fault already turned into an error
  std::vector<std::uint8_t> limit_hit_;      ///< per axis: bit 0 negative, bit 1 positive active
  DeviceErrorLatch errors_;
  bool axes_enabled_ = false;  ///< power_up_axes() has enabled the axes
};

}  // namespace hil::controllers

template <>
struct std::is_error_code_enum<hil::controllers::ControllerFault> : std::true_type {};
