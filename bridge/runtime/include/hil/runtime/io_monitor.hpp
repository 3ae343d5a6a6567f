// SPDX-License-Identifier: MIT
#pragma once
// Watches the controller's I/O over a run: per reported signal its edges and first edge times,
// and the scenario's I/O expectations (state at a time, edge count, first edge time), evaluated
// online. Thread: the cycle thread; observe() never throws or allocates.

#include <optional>
#include <vector>

#include "hil/runtime/machine.hpp"
#include "hil/runtime/run_result.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime {

class IoMonitor {
 public:
  /// Tracks machine.io_signals() (empty without a controller) and the expectations' signals.
  IoMonitor(const Scenario& scenario, const Machine& machine);

  void observe(Duration t) noexcept;
  /// The latest `at:`/`by:` time of an I/O expectation.
  [[nodiscard]] Duration latest_expectation_time() const noexcept { return latest_; }
  /// Fills result.io and the I/O expectations' verdicts (axis "io"); failed ones fail the run.
  void finish(Duration t_end, RunResult& result) const;

 private:
  struct Track {
    std::string name;
    controllers::BitAddress address;
    bool state = false;
    bool seen = false;
    std::uint64_t rising = 0, falling = 0;
    std::optional<Duration> first_rising, first_falling;
  };
  struct ExpectationState {
    const IoExpectation* e = nullptr;
    std::size_t track = 0;
    bool decided = false;
    bool passed = false;
    std::string detail;
  };
  [[nodiscard]] std::size_t track_of(controllers::BitAddress a) const noexcept;

  const Machine& machine_;
  std::vector<Track> tracks_;
  std::vector<ExpectationState> states_;
  Duration latest_{};
};

/// "I/O Q1.00.3 state 1 at t=2.000 s" (what was expected, for reports).
[[nodiscard]] std::string describe(const IoExpectation& e);

}  // namespace hil::runtime
