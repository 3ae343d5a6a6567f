// SPDX-License-Identifier: MIT
#pragma once
// Runs one scenario: builds the machine through the transport registry, then cycles
// (Machine::cycle -> RunMonitor -> observers -> Program::step) on the virtual clock as fast as
// possible or on real time with the Asio scheduler, until the program is done and the axes
// rest (or `duration:`), the timeout, a program failure or an interrupt (SIGINT/SIGTERM in real
// time: the axes quick-stop first).
//
// The run ends when: `duration` is reached; or the program is done, every axis is at rest and
// every expectation time has passed. It fails on a program failure, the timeout, a failed
// expectation, a fault no `fault:` expectation accounts for, or a transport report that is not ok.

#include <expected>
#include <vector>

#include "hil/core/config_error.hpp"
#include "hil/core/transport.hpp"
#include "hil/runtime/realtime.hpp"
#include "hil/runtime/run_observer.hpp"
#include "hil/runtime/run_result.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime {

struct RunOptions {
  bool virtual_time = true;
  bool verify_steps = false;    ///< sets RunEnvironment::verify_edge_streams
  bool handle_signals = false;  ///< real time: SIGINT/SIGTERM stop the run in a controlled way
  /// Real time only: SCHED_FIFO, memory lock, CPU affinity, cpu_dma_latency and absolute
  /// clock_nanosleep wake-ups for the cycle thread (the calling thread). A refused setting is a
  /// ConfigError (key "realtime", with what to do) unless `realtime.fallback`.
  RealtimeOptions realtime;
  std::vector<RunObserver*> observers;
  /// Device controllers for `controller:` blocks; nullptr = controllers::builtin_controllers().
  const controllers::ControllerRegistry* controllers = nullptr;
};

/// Blocking. ConfigError when the machine cannot be built (unknown transport, a factory's
/// error, an invalid axis configuration, a fault name the drive does not know) or a real-time
/// setting is refused.
[[nodiscard]] std::expected<RunResult, ConfigError> run_scenario(const Scenario& scenario,
                                                                 const TransportRegistry& registry,
                                                                 const RunOptions& options);

}  // namespace hil::runtime
