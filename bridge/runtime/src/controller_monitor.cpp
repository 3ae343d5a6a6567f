// SPDX-License-Identifier: MIT
#include "hil/runtime/controller_monitor.hpp"

#include <cmath>

#include <fmt/format.h>

#include "hil/runtime/run_monitor.hpp"

namespace hil::runtime {
namespace {

std::string number(double v) {
  if (std::isnan(v)) return "not available";
  return fmt::format("{}", v);
}

}  // namespace

std::string describe(const ControllerExpectation& e) {
  if (e.kind == ControllerExpectation::Kind::device_error)
    return fmt::format("device error {}{}", e.code, e.by ? fmt::format(" by t={:.3f} s", to_seconds(*e.by)) : "");
  const std::string tol = e.tolerance > 0.0 ? fmt::format(" +/- {}", e.tolerance) : std::string();
  const std::string when = e.at   ? fmt::format(" at t={:.3f} s", to_seconds(*e.at))
                           : e.by ? fmt::format(" by t={:.3f} s", to_seconds(*e.by))
                                  : std::string(" at the end of the run");
  return fmt::format("{} = {}{}{}", e.name, e.value_text.empty() ? number(e.value) : e.value_text, tol, when);
}

ControllerMonitor::ControllerMonitor(const Scenario& scenario, const Machine& machine) : machine_(machine) {
  const auto* c = machine.controller();
  for (const auto& e : scenario.controller_expectations) {
    State s;
    s.e = &e;
    if (e.kind == ControllerExpectation::Kind::value) {
      if (c == nullptr) {
        s.resolve_error = "the scenario has no controller";
      } else if (auto h = c->resolve_value(e.name)) {
        s.handle = *h;
      } else {
        s.resolve_error = h.error();
      }
    }
    if (e.at) latest_ = std::max(latest_, *e.at);
    if (e.by) latest_ = std::max(latest_, *e.by);
    states_.push_back(std::move(s));
  }
}

bool ControllerMonitor::holds(const State& s, double v) const noexcept {
  return !std::isnan(v) && std::abs(v - s.e->value) <= s.e->tolerance;
}

void ControllerMonitor::observe(Duration t) noexcept {
  const auto* c = machine_.controller();
  if (c == nullptr) return;
  for (auto& s : states_) {
    if (!s.handle) continue;
    const double v = c->value(*s.handle);
    if (!s.seen) {
      s.seen = true;
      s.first = v;
      s.held_at_start = holds(s, v);
      s.closest = v;
      s.closest_t = t;
    } else if (!(v == s.first || (std::isnan(v) && std::isnan(s.first)))) {
      s.changed = true;
    }
    if (s.decided) continue;
    const ControllerExpectation& e = *s.e;
    if (e.at && t >= *e.at) {
      s.decided = true;
      s.passed = holds(s, v);
      if (!s.passed) s.detail = fmt::format("was {} at t={:.3f} s", number(v), to_seconds(t));
    } else if (e.by) {
      if (!std::isnan(v) && (std::isnan(s.closest) || std::abs(v - e.value) < std::abs(s.closest - e.value))) {
        s.closest = v;
        s.closest_t = t;
      }
      if (holds(s, v)) {
        s.decided = true;
        s.passed = true;
      } else if (t >= *e.by) {
        s.decided = true;
        s.detail = fmt::format("was {} at t={:.3f} s; closest {} at t={:.3f} s", number(v), to_seconds(t),
                               number(s.closest), to_seconds(s.closest_t));
      }
    }
  }
}

void ControllerMonitor::finish(Duration t_end, RunResult& r) const {
  const auto* c = machine_.controller();
  for (const auto& s0 : states_) {
    State s = s0;
    const ControllerExpectation& e = *s.e;
    if (e.kind == ControllerExpectation::Kind::device_error) {
      s.decided = true;
      std::string seen;
      for (const auto& ev : r.faults) {
        if (ev.source != "device") continue;
        if (fault_matches(ev, e.code) && (!e.by || ev.t <= *e.by)) {
          s.passed = true;
          break;
        }
        seen += fmt::format("{}{} at t={:.3f} s", seen.empty() ? "" : "; ", fault_code_text(ev), to_seconds(ev.t));
      }
      if (!s.passed) s.detail = seen.empty() ? "the controller raised no device error" : "saw " + seen;
    } else if (!s.handle) {
      s.decided = true;
      s.detail = s.resolve_error;
    } else if (!s.decided) {
      if (e.at || e.by) {
        s.decided = true;
        s.detail = fmt::format("the run ended at t={:.3f} s, before that time", to_seconds(t_end));
      } else {
        const double v = c != nullptr ? c->value(*s.handle) : std::nan("");
        s.passed = holds(s, v);
        if (!s.passed) s.detail = fmt::format("was {} at the end of the run", number(v));
      }
    }
    ExpectationResult er{"controller", describe(e), s.passed, s.detail, e.source.line, e.source.path};
    er.controller = true;
    // Met at the first cycle and never changed (or a `by:` met at the first cycle): it checks nothing.
    if (er.passed && e.kind == ControllerExpectation::Kind::value && s.held_at_start && (!s.changed || e.by))
      r.warnings.push_back(fmt::format(
          "{}:{} {}: controller: expected {} already holds at the start of the run{}: it checks nothing", r.file,
          er.line, er.path, er.description, e.by ? " (`by:` accepts the first cycle)" : " and never changed"));
    if (!er.passed) {
      r.ok = false;
      r.failures.push_back(fmt::format("controller: expected {}, {}", er.description, er.detail));
    }
    r.expectations.push_back(std::move(er));
  }
}

}  // namespace hil::runtime
