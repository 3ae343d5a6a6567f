// SPDX-License-Identifier: MIT
#include "run_json.hpp"

#include <cmath>

#include <fmt/format.h>

#include "hil/runtime/latency_report.hpp"
#include "hil/runtime/run_monitor.hpp"

namespace hil::cli {
namespace {

// JSON has no inf/nan: those become null.
std::string number(double v) {
  return std::isfinite(v) ? fmt::format("{:.9g}", v) : "null";
}

template <class T, class F>
std::string array(const std::vector<T>& items, F&& item) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? "," : "") + item(items[i]);
  return out + "]";
}

std::string fault_json(const runtime::FaultEvent& f) {
  return fmt::format(
      "{{\"t_s\":{},\"axis\":{},\"source\":{},\"fault\":{}}}", number(to_seconds(f.t)), json_string(f.axis),
      json_string(f.source),
      // A device error in the device's own notation (WF 725/726: hexadecimal "96").
      json_string(f.source == "device" ? runtime::fault_code_text(f) + " " + f.fault.text : f.fault.describe()));
}

}  // namespace

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
          out += fmt::format("\\u{:04x}", static_cast<unsigned>(static_cast<unsigned char>(c)));
        else
          out += c;
    }
  }
  return out + "\"";
}

std::string realtime_json(const runtime::RealtimeReport& r) {
  return fmt::format(
      "{{\"priority\":{},\"policy\":{},\"cpu\":{},\"io_cpus\":{},\"memory_locked\":{},\"dma_latency_held\":{},"
      "\"absolute_sleeps\":{},\"fallbacks\":{}}}",
      r.priority, json_string(r.priority > 0 ? "SCHED_FIFO" : "SCHED_OTHER"),
      r.cpu ? fmt::format("{}", *r.cpu) : "null", array(r.io_cpus, [](int c) { return fmt::format("{}", c); }),
      r.memory_locked, r.dma_latency_held, r.absolute_sleeps, array(r.fallbacks, [](const runtime::RealtimeProblem& p) {
        return fmt::format("{{\"setting\":{},\"errno\":{},\"message\":{}}}", json_string(runtime::to_string(p.setting)),
                           p.error, json_string(p.message));
      }));
}

std::string run_json(const runtime::RunResult& r) {
  const auto& s = r.scheduler;
  const std::string scheduler = fmt::format(
      "{{\"virtual_time\":{},\"period_us\":{},\"cycles\":{},\"overruns\":{},\"skipped_cycles\":{},"
      "\"simulated_s\":{},\"wall_s\":{},\"max_cycle_work_us\":{},\"wake_latency\":{}}}",
      s.virtual_time, number(to_microseconds(s.period)), s.cycles, s.overruns, s.skipped_cycles,
      number(to_seconds(s.simulated)), number(to_seconds(s.wall)), number(to_microseconds(s.max_cycle_work)),
      s.virtual_time ? std::string("null") : runtime::latency_json(s.wake_latency));
  const std::string axes = array(r.axes, [](const runtime::AxisSummary& a) {
    return fmt::format(
        "{{\"name\":{},\"units\":{},\"final_position\":{},\"final_velocity\":{},\"final_state\":{},"
        "\"max_following_error\":{},\"max_following_error_t_s\":{},\"faults\":{}}}",
        json_string(a.name), json_string(a.units), number(a.final_position), number(a.final_velocity),
        json_string(a.final_state), number(a.max_following_error), number(to_seconds(a.max_following_error_t)),
        array(a.faults, fault_json));
  });
  const std::string expectations = array(r.expectations, [](const runtime::ExpectationResult& e) {
    return fmt::format("{{\"axis\":{},\"description\":{},\"passed\":{},\"detail\":{},\"line\":{},\"path\":{}}}",
                       json_string(e.axis), json_string(e.description), e.passed, json_string(e.detail), e.line,
                       json_string(e.path));
  });
  const std::string reports = array(r.reports, [](const runtime::NamedReport& n) {
    return fmt::format("{{\"transport\":{},\"ok\":{},\"lines\":{}}}", json_string(n.transport), n.report.ok,
                       array(n.report.lines, [](const std::string& l) { return json_string(l); }));
  });
  const auto optional_s = [](const std::optional<Duration>& d) {
    return d ? number(to_seconds(*d)) : std::string("null");
  };
  const std::string controller =
      r.controller.empty()
          ? std::string("null")
          : fmt::format("{{\"device\":{},\"device_errors\":{},\"io\":{}}}", json_string(r.controller),
                        array(r.device_errors,
                              [](const runtime::DeviceErrorEvent& e) {
                                return fmt::format(
                                    "{{\"t_s\":{},\"axis\":{},\"category\":{},\"code\":{},\"text\":{},\"reaction\":{},"
                                    "\"acknowledge\":{}}}",
                                    number(to_seconds(e.t)), json_string(e.axis), json_string(e.category),
                                    json_string(e.code), json_string(e.text), json_string(e.reaction),
                                    json_string(e.acknowledge));
                              }),
                        array(r.io, [&](const runtime::IoSummary& io) {
                          return fmt::format(
                              "{{\"name\":{},\"address\":{},\"final\":{},\"rising\":{},\"falling\":{},"
                              "\"first_rising_s\":{},\"first_falling_s\":{}}}",
                              json_string(io.name), json_string(io.address), io.final_state, io.rising, io.falling,
                              optional_s(io.first_rising), optional_s(io.first_falling));
                        }));
  return fmt::format(
      "{{\"scenario\":{},\"file\":{},\"ok\":{},\"interrupted\":{},\"simulated_s\":{},\"cut_off\":{},"
      "\"failures\":{},\"warnings\":{},\"axes\":{},\"faults\":{},\"expectations\":{},\"controller\":{},"
      "\"scheduler\":{},\"realtime\":{},\"transports\":{}}}\n",
      json_string(r.scenario), json_string(r.file), r.ok, r.interrupted, number(to_seconds(r.simulated)),
      r.cut_off ? fmt::format("{{\"reason\":{},\"expected\":{}}}", json_string(*r.cut_off), r.cut_off_expected)
                : std::string("null"),
      array(r.failures, [](const std::string& f) { return json_string(f); }),
      array(r.warnings, [](const std::string& w) { return json_string(w); }), axes, array(r.faults, fault_json),
      expectations, controller, scheduler, r.realtime ? realtime_json(*r.realtime) : std::string("null"), reports);
}

}  // namespace hil::cli
