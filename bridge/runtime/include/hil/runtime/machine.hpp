// SPDX-License-Identifier: MIT
#pragma once
// The machine of a run: one hil::motion::Axis per scenario axis, each on the hil::Drive its
// transport factory built from the axis' `drive:` block, and one factory instance per transport
// used (so a factory can share a bus between its axes).
//
// One cycle (docs/runtime.md): every factory's begin_cycle, the virtual masters, each axis' update
// (a coupled slave first takes its coupling's set-point; drive read -> trajectory + supervision ->
// drive write) in scenario order, every factory's end_cycle.
// With a scenario `controller:` block the machine also owns the controller (docs/controllers.md):
// the controller's axes take their AxisConfig from its parameter file, the scenario's `io:`
// stimuli are attached to its image, and cycle() steps it every cycle_period() / period cycles
// (the first cycle included), after the axes' update and the factories' end_cycle.
// Thread: the cycle thread only; cycle() never throws.

#include <expected>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hil/controllers/controller.hpp"
#include "hil/controllers/controller_registry.hpp"
#include "hil/controllers/gpio_link.hpp"
#include "hil/controllers/io_image.hpp"
#include "hil/controllers/modbus_io_link.hpp"
#include "hil/core/config_error.hpp"
#include "hil/core/fault_injection.hpp"
#include "hil/core/transport.hpp"
#include "hil/motion/axis.hpp"
#include "hil/runtime/machine_coupling.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime {

/// motion::AxisConfig from a scenario axis; errors name the axis' file and line.
[[nodiscard]] std::expected<motion::AxisConfig, ConfigError> make_axis_config(const AxisSpec& spec,
                                                                              const std::string& file);

struct MachineAxis {
  const AxisSpec* spec = nullptr;
  std::unique_ptr<motion::Axis> axis;
  FaultInjectable* injectable = nullptr;  ///< the drive's fault injection, when it has one
  std::string transport;
};

/// An `io_links: - modbus:` entry at run time: its key path ("io_links[1]") and the link.
struct GpioLinkEntry {
  std::string name;  ///< "io_links[0]"
  std::unique_ptr<controllers::GpioLink> link;
};

struct ModbusLinkEntry {
  std::string name;
  std::unique_ptr<controllers::ModbusIoLink> link;
};

struct NamedReport {
  std::string transport;
  TransportReport report;
};

class Machine {
 public:
  /// Build every axis' drive through `registry` (unknown transports and factory errors are
  /// ConfigErrors naming the axis' `drive:` line). `env` must outlive the machine. A scenario
  /// controller is built through `controllers` (nullptr: controllers::builtin_controllers()).
  [[nodiscard]] static std::expected<Machine, ConfigError> build(
      const Scenario& scenario, const TransportRegistry& registry, RunEnvironment& env,
      const controllers::ControllerRegistry* controllers = nullptr);

  /// One cycle: begin_cycle (all factories), update (all axes), end_cycle (all factories).
  void cycle(const CycleTime& cycle) noexcept;
  /// After the last cycle: every factory's finish() report.
  [[nodiscard]] std::vector<NamedReport> finish(const CycleTime& cycle);

  [[nodiscard]] std::vector<MachineAxis>& axes() noexcept { return axes_; }
  [[nodiscard]] const std::vector<MachineAxis>& axes() const noexcept { return axes_; }
  [[nodiscard]] MachineAxis* find(const std::string& name) noexcept;
  /// Transport names in the order their first axis appears.
  [[nodiscard]] std::vector<std::string> transports() const;
  /// Couplings and virtual masters (scenario machine.couplings / masters / cams).
  [[nodiscard]] MachineCouplings& couplings() noexcept { return couplings_; }
  [[nodiscard]] const MachineCouplings& couplings() const noexcept { return couplings_; }

  /// The scenario's controller, nullptr when it has none.
  [[nodiscard]] controllers::Controller* controller() noexcept { return controller_.get(); }
  [[nodiscard]] const controllers::Controller* controller() const noexcept { return controller_.get(); }
  /// I/O signals the run reports (trace columns, plot strips, JSON): the controller's named
  /// signals, then every address the scenario's io:/expect: entries name. Empty without controller.
  [[nodiscard]] const std::vector<std::pair<std::string, controllers::BitAddress>>& io_signals() const noexcept {
    return io_signals_;
  }
  /// The scenario's Modbus I/O links (their faults become run fault events, source "io_link").
  [[nodiscard]] const std::vector<ModbusLinkEntry>& modbus_links() const noexcept { return modbus_links_; }
  /// The scenario's `io_links: - gpio:` entries (a failed line is a fault of its link).
  [[nodiscard]] const std::vector<GpioLinkEntry>& gpio_links() const noexcept { return gpio_links_; }
  /// What a run prints before its first cycle about its I/O links ("io_links[0]: simulated Modbus
  /// I/O terminal listening on 127.0.0.1:40123 (unit 1)").
  [[nodiscard]] const std::vector<std::string>& io_link_notes() const noexcept { return io_link_notes_; }
  /// True when the last cycle ran the controller's step (always true without a controller): a
  /// run ends only then, so a fault of the last cycles has reached the device's error handling.
  [[nodiscard]] bool controller_cycle_complete() const noexcept {
    return !controller_ || cycle_count_ == 0 || (cycle_count_ - 1) % controller_every_ == 0;
  }
  /// When the last timed input stimulus of the scenario (io: set/pulse at a time) has ended,
  /// from the run's start; zero without any. A run lasts at least this long.
  [[nodiscard]] Duration last_stimulus_time() const noexcept { return last_stimulus_; }

 private:
  struct Factory {
    std::string name;
    std::unique_ptr<TransportFactory> factory;
  };
  [[nodiscard]] std::optional<ConfigError> build_controller(const Scenario& scenario,
                                                            const controllers::ControllerRegistry* registry);
  [[nodiscard]] std::optional<ConfigError> attach_io(const Scenario& scenario, const Clock& clock);
  /// The scenario's analog inputs (`io: - {analog: ...}`): one AnalogSchedule per input.
  [[nodiscard]] std::optional<ConfigError> attach_analog(const Scenario& scenario);
  /// One `io_links:` entry: resolves its signals (inputs: input/data bits; outputs: output/marker
  /// bits), opens the device and attaches its source and sink to the controller's image.
  [[nodiscard]] std::optional<ConfigError> attach_io_link(const Scenario& scenario, const IoLink& link,
                                                          const Clock& clock);
  using ResolveLinkBit = std::function<std::expected<controllers::BitAddress, ConfigError>(const IoLinkBit&, bool)>;
  /// The `modbus:` kind (machine_io_modbus.cpp): the simulated terminal or a tcp:// one.
  [[nodiscard]] std::optional<ConfigError> make_modbus_link(const Scenario& scenario, const IoLink& link,
                                                            const ModbusLinkDevice& device,
                                                            const ResolveLinkBit& resolve);
  /// `- drive: AXIS`: DriveInputs / DriveOutputs on the axis, after checking the axis exists and its
  /// drive has the digital inputs / output bits the link uses.
  /// `- gpio:`: the chip's (or mock) lines through a controllers::GpioLink.
  [[nodiscard]] std::optional<ConfigError> make_gpio_link(const Scenario& scenario, const IoLink& link,
                                                          const GpioLinkDevice& device, const Clock& clock,
                                                          const ResolveLinkBit& resolve);
  /// A signal name or device address as a bit of the controller's image; errors name `src`.
  [[nodiscard]] std::expected<controllers::BitAddress, ConfigError> resolve_signal(const Scenario& scenario,
                                                                                   const std::string& signal,
                                                                                   const SourceRef& src) const;
  /// Adds `name` to io_signals() (the reported signals) unless it is there already.
  void report_signal(const std::string& name, controllers::BitAddress a);
  [[nodiscard]] std::optional<ConfigError> make_drive_link(const Scenario& scenario, const IoLink& link,
                                                           const DriveLinkDevice& device,
                                                           const ResolveLinkBit& resolve);
  [[nodiscard]] std::optional<ConfigError> bind_controller(const Scenario& scenario);
  /// The controller's copy of a controller axis' spec (units, rotary, windows filled in), else `spec`.
  [[nodiscard]] const AxisSpec& controller_spec(const AxisSpec& spec) const noexcept;
  [[nodiscard]] std::expected<motion::AxisConfig, ConfigError> controller_axis_config(const AxisSpec& spec,
                                                                                      const std::string& file) const;

  std::vector<Factory> factories_;
  std::vector<std::unique_ptr<AxisSpec>> controller_specs_;  ///< specs of the controller's axes
  std::vector<MachineAxis> axes_;
  MachineCouplings couplings_;
  std::vector<std::unique_ptr<controllers::IoSource>> stimuli_;
  std::vector<GpioLinkEntry> gpio_links_;      ///< io_links: gpio
  std::vector<ModbusLinkEntry> modbus_links_;  ///< io_links: modbus
  std::vector<std::string> io_link_notes_;
  std::vector<std::unique_ptr<controllers::IoSource>> drive_inputs_;  ///< io_links: drive (after the axes)
  std::vector<std::unique_ptr<controllers::IoSink>> drive_outputs_;
  std::vector<std::pair<std::string, std::uint32_t>> drive_output_bits_;  ///< axis -> bits some link drives
  std::unique_ptr<SteadyClock> steady_clock_;            ///< tcp:// terminals age their data on real time (heap: moves)
  std::unique_ptr<controllers::Controller> controller_;  ///< declared after the axes: destroyed first
  std::vector<std::pair<std::string, controllers::BitAddress>> io_signals_;
  std::uint64_t controller_every_ = 1;  ///< run cycles per controller cycle
  std::vector<int> controller_axis_;    ///< machine axis -> the controller's axis index (-1: none)
  std::uint64_t cycle_count_ = 0;
  Duration last_stimulus_{};
};

}  // namespace hil::runtime
