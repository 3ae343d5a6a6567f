// SPDX-License-Identifier: MIT
#pragma once
// Watches a run cycle by cycle: fault events (axis supervision and drive faults), maximum
// following error, and the scenario's expectations, evaluated online so nothing per cycle is
// stored. Thread: the cycle thread.

#include <algorithm>
#include <optional>
#include <vector>

#include "hil/runtime/controller_monitor.hpp"
#include "hil/runtime/io_monitor.hpp"
#include "hil/runtime/machine.hpp"
#include "hil/runtime/run_result.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime {

class RunMonitor {
 public:
  RunMonitor(const Scenario& scenario, const Machine& machine);

  /// After each cycle, at scenario time `t`. Never throws.
  void observe(Duration t) noexcept;
  /// The latest `at:`/`by:` time of any expectation (a run lasts at least this long).
  [[nodiscard]] Duration latest_expectation_time() const noexcept {
    return std::max({latest_, io_.latest_expectation_time(), ctl_.latest_expectation_time()});
  }
  /// Fill axes, faults and expectations of `result`; adds failures for failed expectations and
  /// for faults no `fault:` expectation of their axis accounts for.
  void finish(Duration t_end, RunResult& result) const;

  [[nodiscard]] const std::vector<FaultEvent>& faults() const noexcept { return faults_; }

 private:
  struct AxisTrack {
    const MachineAxis* axis = nullptr;
    double max_fe = 0.0;
    Duration max_fe_t{};
    std::error_code last_axis_fault;
    std::error_code last_drive_fault;
    std::uint64_t moves = 0;  ///< entries into state `moving`
    bool state_seen = false;
    motion::AxisState last_state{};
  };
  struct ExpectationState {
    const Expectation* e = nullptr;
    std::size_t axis = 0;
    bool decided = false;
    bool passed = false;
    std::string detail;
    double best_error = 0.0;  ///< position: closest approach so far
    Duration best_t{};
    bool best_set = false;
    // An expectation that holds at the first cycle and whose axis never changes checks nothing.
    bool seen = false;           ///< the first cycle was observed
    bool held_at_start = false;  ///< the condition held at the first cycle
    bool changed = false;        ///< position left its start tolerance band / state changed since
    double start_position = 0.0;
    motion::AxisState start_state{};
  };
  void track_start(ExpectationState& s, const motion::AxisStatus& st) const;
  void decide(ExpectationState& s, Duration t, const motion::AxisStatus& st) const;
  [[nodiscard]] double position_error(std::size_t axis, double position, double target) const;
  [[nodiscard]] std::string fmt_pos(const ExpectationState& s, double v) const;

  const Scenario& scenario_;
  const Machine& machine_;
  std::vector<AxisTrack> tracks_;
  std::vector<ExpectationState> states_;
  std::vector<FaultEvent> faults_;
  Duration latest_{};
  IoMonitor io_;
  ControllerMonitor ctl_;
  std::size_t device_errors_seen_ = 0;
  std::vector<std::uint64_t> link_outages_seen_;  ///< per Machine::modbus_links() entry
  std::vector<std::uint64_t> gpio_outages_seen_;  ///< per Machine::gpio_links() entry
  std::vector<DeviceErrorEvent> device_events_;   ///< controller error history entries turned into events
};

/// "wf725-726.traversing:96" for a device error event, "motion:5" otherwise.
[[nodiscard]] std::string fault_code_text(const FaultEvent& e);
/// Whether `e` is a fault with this code as scenarios write it ("motion:1", a device error
/// "clm14.diagnostic:0E" by the manual's text; "" matches any).
[[nodiscard]] bool fault_matches(const FaultEvent& e, const std::string& code);

/// "position 100.000 +/- 0.010 mm at t=2.000 s" (what was expected, for reports).
[[nodiscard]] std::string describe(const Expectation& e, const AxisSpec& axis);

}  // namespace hil::runtime
