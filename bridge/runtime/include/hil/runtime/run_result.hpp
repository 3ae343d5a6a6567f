// SPDX-License-Identifier: MIT
#pragma once
// What a run produced: per-axis summary, fault events, expectation verdicts, scheduler
// statistics and the transports' reports. Printed by `hilbridge run`, turned into JUnit XML by
// `hilbridge test`.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hil/core/fault.hpp"
#include "hil/runtime/machine.hpp"
#include "hil/runtime/realtime.hpp"
#include "hil/runtime/scheduler.hpp"

namespace hil::runtime {

struct FaultEvent {
  Duration t{};        ///< scenario time it was first seen
  std::string axis;    ///< axis name; "controller" for a device error of the whole device
  std::string source;  ///< "axis" (motion supervision), "drive" (the drive's own fault) or "device"
  Fault fault;
};

/// A device error the controller raised (also a FaultEvent with source "device").
struct DeviceErrorEvent {
  Duration t{};
  std::string axis;         ///< axis name, or "controller"
  std::string category;     ///< "wf725-726.traversing"
  std::string code;         ///< as the manual writes it: "96", "4C", "28"
  std::string text;         ///< the catalogue's text, cause and context
  std::string reaction;     ///< message / stop / drive_off / needs_reset
  std::string acknowledge;  ///< self_clearing / acknowledge / reset / power_cycle
  /// "wf725-726.traversing:96 Pre-limit switch positive (MD 13): ..."
  [[nodiscard]] std::string describe() const { return category + ":" + code + " " + text; }
};

/// One I/O signal of the controller over the run (summary, JSON).
struct IoSummary {
  std::string name;     ///< as the device or the scenario names it
  std::string address;  ///< the image address ("output 64.3")
  bool final_state = false;
  std::uint64_t rising = 0, falling = 0;
  std::optional<Duration> first_rising, first_falling;
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
  std::string axis;         ///< the axis expected on; "io" for an I/O expectation (`io` set)
  std::string description;  ///< "position 100.000 +/- 0.010 mm at t=2.000 s"
  bool passed = false;
  std::string detail;  ///< why it failed, with values ("was 99.412 mm (off by 0.588 mm)")
  int line = 0;
  std::string path;  ///< "expect[3]"
  bool io = false;   ///< an I/O expectation (`{io: SIGNAL, ...}`), not an axis'
  /// A controller expectation (`{controller: NAME, value: V}`, `{device_error: CODE}`); axis "controller".
  bool controller = false;
  /// "axis x", "I/O" or "controller", as reports name what was expected on.
  [[nodiscard]] std::string subject() const {
    return io ? std::string("I/O") : controller ? std::string("controller") : "axis " + axis;
  }
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
  std::string controller;                       ///< device name of the scenario's controller ("" without)
  std::vector<DeviceErrorEvent> device_errors;  ///< every device error the controller raised, in order
  std::vector<IoSummary> io;                    ///< the controller's reported I/O signals
  std::vector<NamedReport> reports;
  SchedulerStats scheduler;
  std::optional<RealtimeReport> realtime;  ///< set when the run asked for real-time operation
  Duration simulated{};                    ///< scenario time at the last cycle
  bool interrupted = false;
  /// What a fixed `duration:` cut off ("cut off by duration at t=2.000 s: step 3 of 5 (...) not
  /// completed; axis x still moving"); unset when the program had ended and every axis was at rest.
  /// A failure unless `cut_off_expected` (the scenario's `cut_off: expected`).
  std::optional<std::string> cut_off;
  bool cut_off_expected = false;
};

}  // namespace hil::runtime
