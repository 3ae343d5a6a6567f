// SPDX-License-Identifier: MIT
#pragma once
// The machine of a run: one hil::motion::Axis per scenario axis, each on the hil::Drive its
// transport factory built from the axis' `drive:` block, and one factory instance per transport
// used (so a factory can share a bus between its axes).
//
// One cycle (docs/runtime.md): every factory's begin_cycle, the virtual masters, each axis' update
// (a coupled slave first takes its coupling's set-point; drive read -> trajectory + supervision ->
// drive write) in scenario order, every factory's end_cycle.
// Thread: the cycle thread only; cycle() never throws.

#include <expected>
#include <memory>
#include <string>
#include <vector>

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

struct NamedReport {
  std::string transport;
  TransportReport report;
};

class Machine {
 public:
  /// Build every axis' drive through `registry` (unknown transports and factory errors are
  /// ConfigErrors naming the axis' `drive:` line). `env` must outlive the machine.
  [[nodiscard]] static std::expected<Machine, ConfigError> build(const Scenario& scenario,
                                                                 const TransportRegistry& registry,
                                                                 RunEnvironment& env);

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

 private:
  struct Factory {
    std::string name;
    std::unique_ptr<TransportFactory> factory;
  };
  std::vector<Factory> factories_;
  std::vector<MachineAxis> axes_;
  MachineCouplings couplings_;
};

}  // namespace hil::runtime
