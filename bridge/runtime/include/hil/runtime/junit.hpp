// SPDX-License-Identifier: MIT
#pragma once
// JUnit XML for `hilbridge test --junit FILE` (the schema CI servers read: <testsuites> with one
// <testsuite> per scenario file, one <testcase> per expectation plus one "run" case for the
// program, faults and transport reports; a scenario that does not load is an <error>).

#include <optional>
#include <string>
#include <vector>

#include "hil/runtime/run_result.hpp"

namespace hil::runtime {

struct ScenarioOutcome {
  std::string file;
  std::optional<RunResult> result;  ///< absent when the scenario could not be loaded or built
  std::string error;                ///< the ConfigError text when `result` is absent
  double wall_s = 0.0;
  [[nodiscard]] bool passed() const noexcept { return result && result->ok; }
};

[[nodiscard]] std::string make_junit_xml(const std::vector<ScenarioOutcome>& outcomes);

}  // namespace hil::runtime
