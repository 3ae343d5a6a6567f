// SPDX-License-Identifier: MIT
#pragma once
// A scenario given as YAML text, run on the sim transports (the controller_scenario tests):
// `run_text` parses it as if it were examples/controllers/test.yaml (relative parameter and
// program paths resolve against examples/controllers) and runs it; `wf_head` is a WF 725/726
// axis A on the simulated drive, to which a test appends its `program:` / `io:` / `expect:`.
#include <expected>
#include <string>
#include <vector>

#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "sim_registry.hpp"

namespace hil::runtime::scenario_text {

inline std::expected<RunResult, ConfigError> run_text(const std::string& text,
                                                      std::vector<RunObserver*> observers = {}) {
  auto s = parse_scenario(text, "examples/controllers/test.yaml");
  if (!s) return std::unexpected(s.error());
  static Scenario keep;  // the result refers to the scenario: it lives until the next run
  keep = std::move(*s);
  RunOptions o;
  o.observers = std::move(observers);
  return run_scenario(keep, hil::testing::sim_registry(), o);
}

inline const std::string wf_head = R"(
period: 1ms
controller: {device: wf725-726, parameters: wf725-axis-a.txt}
machine:
  axes:
    - name: A
      drive: {transport: sim, kv: 100, feedforward: 1.0}
)";

}  // namespace hil::runtime::scenario_text
