// SPDX-License-Identifier: MIT
#include "report.hpp"

#include <fmt/format.h>

#include "hil/runtime/latency_report.hpp"
#include "hil/runtime/run_monitor.hpp"

namespace hil::cli {

std::string describe_scheduler(const runtime::SchedulerStats& s) {
  const auto us = [](Duration d) { return std::chrono::duration<double, std::micro>(d).count(); };
  std::string out =
      fmt::format("{} cycles at {:.3f} ms, {:.3f} s {} in {:.3f} s wall", s.cycles, to_seconds(s.period) * 1e3,
                  to_seconds(s.simulated), s.virtual_time ? "virtual time" : "real time", to_seconds(s.wall));
  if (s.virtual_time) {
    if (s.wall > Duration::zero())
      out += fmt::format(" ({:.0f}x real time)", to_seconds(s.simulated) / to_seconds(s.wall));
    return out;
  }
  out += fmt::format(
      "; wake-up latency min/mean/p99/max {:.0f}/{:.0f}/{:.0f}/{:.0f} us; longest cycle {:.0f} us; "
      "{} overruns, {} skipped cycles",
      us(s.wake_latency.min()), us(s.wake_latency.mean()), us(s.wake_latency.percentile(0.99)),
      us(s.wake_latency.max()), us(s.max_cycle_work), s.overruns, s.skipped_cycles);
  return out;
}

void print_summary(std::FILE* out, const runtime::RunResult& r) {
  fmt::print(out, "\nsummary of {} ({}):\n", r.scenario, r.file);
  fmt::print(out, "  {:<8} {:>16} {:>14} {:>24}  {}\n", "axis", "final position", "final state", "max following error",
             "faults");
  for (const auto& a : r.axes) {
    std::string faults = a.faults.empty() ? "none" : "";
    for (const auto& f : a.faults)
      faults +=
          fmt::format("{}t={:.3f} s {} {}", faults.empty() ? "" : "; ", to_seconds(f.t), f.source,
                      f.source == "device" ? runtime::fault_code_text(f) + " " + f.fault.text : f.fault.describe());
    fmt::print(out, "  {:<8} {:>12.4f} {:<3} {:>14} {:>10.4f} {:<3} at {:>7.3f} s  {}\n", a.name, a.final_position,
               a.units, a.final_state, a.max_following_error, a.units, to_seconds(a.max_following_error_t), faults);
  }
  if (!r.controller.empty()) {
    fmt::print(out, "controller {}:\n", r.controller);
    for (const auto& d : r.device_errors)
      fmt::print(out, "  device error t={:.3f} s axis {}: {} (reaction {})\n", to_seconds(d.t), d.axis, d.describe(),
                 d.reaction);
    for (const auto& io : r.io)
      fmt::print(out, "  io {:<16} {:<14} final {}  rising {}  falling {}\n", io.name, io.address,
                 io.final_state ? 1 : 0, io.rising, io.falling);
  }
  if (!r.expectations.empty()) {
    fmt::print(out, "expectations:\n");
    for (const auto& e : r.expectations)
      fmt::print(out, "  {} {}: {}{}\n", e.passed ? "pass" : "FAIL", e.subject(), e.description,
                 e.passed ? "" : ": " + e.detail);
  }
  for (const auto& w : r.warnings) fmt::print(out, "warning: {}\n", w);
  if (r.cut_off && r.cut_off_expected) fmt::print(out, "note: {} (expected)\n", *r.cut_off);
  fmt::print(out, "scheduler: {}\n", describe_scheduler(r.scheduler));
  if (r.realtime) fmt::print(out, "real time: {}\n", r.realtime->describe());
  if (!r.scheduler.virtual_time && r.scheduler.wake_latency.count() > 0)
    fmt::print(out, "wake-up latency histogram:\n{}",
               runtime::format_latency_histogram(r.scheduler.wake_latency, "  "));
  for (const auto& rep : r.reports) {
    fmt::print(out, "transport {}: {}\n", rep.transport, rep.report.ok ? "ok" : "FAILED");
    for (const auto& l : rep.report.lines) fmt::print(out, "  {}\n", l);
  }
  if (r.ok) {
    fmt::print(out, "result: OK\n");
  } else {
    fmt::print(out, "result: FAILED\n");
    for (const auto& f : r.failures) fmt::print(out, "  {}\n", f);
  }
  std::fflush(out);
}

}  // namespace hil::cli
