// SPDX-License-Identifier: MIT
#pragma once
// Hooks for what watches a run (live status line, trace CSV, SVG plot). Called on the cycle
// thread after each cycle; an observer must be quick and must not throw.

#include "hil/runtime/machine.hpp"
#include "hil/runtime/run_result.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime {

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  /// Before the first cycle, once the machine is built.
  virtual void on_start(const Scenario&, const Machine&) {}
  /// After every cycle; `t` = scenario time of the cycle (0 for the first).
  virtual void on_cycle(Duration t, const Machine& machine) noexcept = 0;
  /// After the last cycle, with the complete result.
  virtual void on_finish(const RunResult&) {}
};

}  // namespace hil::runtime
