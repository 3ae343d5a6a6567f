// SPDX-License-Identifier: MIT
#pragma once
// Watches the controller's values over a run for the scenario's controller expectations
// (`{controller: NAME, value: V}` at a time, by a time or at the end; `{device_error: CODE}`),
// evaluated online. Thread: the cycle thread; observe() never throws or allocates.

#include <optional>
#include <string>
#include <vector>

#include "hil/runtime/machine.hpp"
#include "hil/runtime/run_result.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime {

class ControllerMonitor {
 public:
  /// Resolves the expectations' value names on machine.controller() (none without one).
  ControllerMonitor(const Scenario& scenario, const Machine& machine);

  void observe(Duration t) noexcept;
  /// The latest `at:`/`by:` time of a controller expectation.
  [[nodiscard]] Duration latest_expectation_time() const noexcept { return latest_; }
  /// Adds the verdicts (axis "controller") to `result`, whose `faults` are already filled (the
  /// device errors the run saw); failed ones fail the run, and values that held at the first
  /// cycle and never changed are warnings (they check nothing).
  void finish(Duration t_end, RunResult& result) const;

 private:
  struct State {
    const ControllerExpectation* e = nullptr;
    std::optional<std::size_t> handle;
    std::string resolve_error;
    bool decided = false;
    bool passed = false;
    std::string detail;
    bool seen = false;
    double first = 0.0;          ///< the value at the first cycle
    bool held_at_start = false;  ///< the expectation held at the first cycle
    bool changed = false;        ///< the value changed since the first cycle
    double closest = 0.0;        ///< by: the value closest to the expected one so far
    Duration closest_t{};
  };
  [[nodiscard]] bool holds(const State& s, double v) const noexcept;

  const Machine& machine_;
  std::vector<State> states_;
  Duration latest_{};
};

/// "V600 = -87654321.654321 at the end of the run" (what was expected, for reports).
[[nodiscard]] std::string describe(const ControllerExpectation& e);

}  // namespace hil::runtime
