// SPDX-License-Identifier: MIT
#pragma once
// The couplings of a machine (scenario machine.masters / cams / couplings, docs/coupling.md):
// virtual masters, the cam tables scaled to each coupling's increments, and one
// hil::motion::Coupling per slave axis. Stepped by Machine::cycle on the cycle thread, just
// before the slave's Axis::update; `couple:` program steps command it.

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/core/config_error.hpp"
#include "hil/core/drive.hpp"
#include "hil/motion/coupling.hpp"
#include "hil/motion/master.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime {

struct MachineAxis;

struct MachineMaster {
  const VirtualMasterSpec* spec = nullptr;
  motion::VirtualMaster master;
  double inc_per_unit = 1.0;
  double target_velocity_inc = 0.0;
};

struct MachineCoupling {
  const CouplingSpec* spec = nullptr;
  std::size_t slave = 0;                   ///< index in Machine::axes()
  std::optional<std::size_t> master_axis;  ///< index in Machine::axes()
  std::optional<std::size_t> master_virtual;
  std::int64_t master_num = 1, master_den = 1;  ///< master increments per master unit
  std::int64_t slave_num = 1, slave_den = 1;    ///< slave increments per slave unit
  motion::TimeMaster time{std::chrono::microseconds(1)};
  motion::Coupling coupling;
  std::vector<std::optional<motion::CamTable>> cams;  ///< per scenario cam, scaled; nullopt when unusable
  std::vector<std::string> cam_errors;                ///< why a cam cannot be used by this coupling
  bool active = false;
  std::int64_t master_inc = 0;  ///< last master position
  // For the plot: last master position (units), slave command (units), cam table position (master units).
  double plot_master = 0.0, plot_slave = 0.0, plot_cam = NAN;

  [[nodiscard]] double master_units(std::int64_t inc) const noexcept {
    return static_cast<double>(inc) * static_cast<double>(master_den) / static_cast<double>(master_num);
  }
  [[nodiscard]] std::int64_t master_to_inc(double units) const noexcept;
};

class MachineCouplings {
 public:
  /// Resolve names and scale the cams; errors name the coupling's line.
  [[nodiscard]] std::optional<ConfigError> build(const Scenario& scenario, const std::vector<MachineAxis>& axes);
  /// Before the axes' updates: advance the virtual masters.
  void begin_cycle(const hil::CycleTime& cycle) noexcept;
  /// Just before axis `index` updates: run its coupling, hand the set-point to the axis.
  void before_axis(std::size_t index, std::vector<MachineAxis>& axes, const hil::CycleTime& cycle) noexcept;

  /// A `couple:` step: "" when accepted, else why not.
  [[nodiscard]] std::string command(const CoupleStep& step, std::vector<MachineAxis>& axes);
  /// Whether a `couple:` step has completed.
  [[nodiscard]] bool done(const CoupleStep& step, std::vector<MachineAxis>& axes);

  [[nodiscard]] const std::vector<std::unique_ptr<MachineCoupling>>& couplings() const noexcept { return couplings_; }
  [[nodiscard]] bool empty() const noexcept { return couplings_.empty() && masters_.empty(); }

 private:
  MachineCoupling* find(const std::string& slave) noexcept;
  MachineMaster* find_master(const std::string& name) noexcept;
  std::int64_t master_position(MachineCoupling& c, const std::vector<MachineAxis>& axes) noexcept;

  const Scenario* scenario_ = nullptr;
  std::vector<MachineMaster> masters_;
  std::vector<std::unique_ptr<MachineCoupling>> couplings_;
  std::vector<MachineCoupling*> by_axis_;  ///< per axis index: its coupling or nullptr
};

}  // namespace hil::runtime
