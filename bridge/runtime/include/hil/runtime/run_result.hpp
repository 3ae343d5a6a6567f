// SPDX-License-Identifier: MIT
#pragma once
// What a run produced: per-axis summary, fault events, expectation verdicts, scheduler
// statistics and the transports' reports. Printed by `hilbridge run`, turned into JUnit XML by
// `hilbridge test`.

#include <string>
#include <vector>

#include "hil/core/fault.hpp"
#include "hil/runtime/machine.hpp"
#include "hil/runtime/scheduler.hpp"

namespace hil::runtime {

struct FaultEvent {
  Duration t{};  ///< scenario time it was first seen
  std::string axis;
  std::string source;  ///< "axis" (motion supervision) or "drive" (the drive's own fault)
  Fault fault;
};

struct AxisSummary {
  std::string name;
  std::string units;
  double final_position = 0.0;
  double final_velocity = 0.0;
  std::string final_state;
  double max_following_error = 0.0;  ///< |following error|, units
  Duration max_following_error_t{};
  std::vector<FaultEvent> faults;
};

struct ExpectationResult {
  std::string axis;
  std::string description;  ///< "position 100.000 +/- 0.010 mm at t=2.000 s"
  bool passed = false;
  std::string detail;  ///< why it failed, with values ("was 99.412 mm (off by 0.588 mm)")
  int line = 0;
  std::string path;  ///< "expect[3]"
};

struct RunResult {
  std::string scenario;  ///< name or file
  std::string file;
  bool ok = true;
  std::vector<std::string> failures;  ///< program failure, timeout, unexpected faults, failed reports
  /// Expectations that check nothing: met at the first cycle and never changed (the run still passes).
  std::vector<std::string> warnings;
  std::vector<AxisSummary> axes;
  std::vector<FaultEvent> faults;
  std::vector<ExpectationResult> expectations;
  std::vector<NamedReport> reports;
  SchedulerStats scheduler;
  Duration simulated{};  ///< scenario time at the last cycle
  bool interrupted = false;
};

}  // namespace hil::runtime
