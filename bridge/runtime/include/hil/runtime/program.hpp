// SPDX-License-Identifier: MIT
#pragma once
// Executes a scenario's program on the cycle thread, one call per cycle after the axes updated.
// Steps run in order; a step starts when the previous one completed (or at once after a
// `blocking: false` step) and no earlier than its `at:` time. What "completed" means per action
// is documented in docs/scenarios.md (a move: profile ended and in position; enable: the axis
// left enabling; ...). A rejected command, an axis fault during a blocking step that does not
// wait for a fault, or a step timeout fails the program with a message naming the step.

#include <optional>
#include <string>
#include <vector>

#include "hil/core/config_error.hpp"
#include "hil/runtime/machine.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime {

class Program {
 public:
  enum class Status : std::uint8_t { running, done, failed };

  Program(const Scenario& scenario, Machine& machine);

  /// Checks what can be checked before the run (fault names against the drives' injectable
  /// faults). ConfigError names the step's line.
  [[nodiscard]] std::optional<ConfigError> check() const;

  /// One cycle at scenario time `t` (time since the first cycle). Never throws.
  Status step(Duration t) noexcept;
  [[nodiscard]] Status status() const noexcept { return status_; }
  /// Why the program failed ("t=1.234 s: demo.yaml:42 program[3] move_absolute x: ...").
  [[nodiscard]] const std::string& error() const noexcept { return error_; }
  /// Index of the step running now (== program size when done).
  [[nodiscard]] std::size_t current_step() const noexcept { return next_; }

 private:
  struct Running {
    const Step* step = nullptr;
    Duration started{};
    bool launched = false;
    bool issued =
        false;  ///< its follow-up is done: jog: the stop after its duration; acknowledge: given to the controller
    std::vector<Running> children;
  };
  enum class Check : std::uint8_t { pending, done, failed };

  bool launch(Running& r, Duration t);
  Check poll(Running& r, Duration t);
  void fail(const Step& s, Duration t, const std::string& what);
  motion::Axis& axis(const std::string& name);

  const Scenario& scenario_;
  Machine& machine_;
  std::size_t next_ = 0;
  std::optional<Running> current_;
  Status status_ = Status::running;
  std::string error_;
};

}  // namespace hil::runtime
