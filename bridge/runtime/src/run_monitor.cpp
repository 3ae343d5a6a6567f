// SPDX-License-Identifier: MIT
#include "hil/runtime/run_monitor.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "hil/runtime/scenario_loader.hpp"
#include "overloaded.hpp"

namespace hil::runtime {
namespace {

using detail::Overloaded;

int decimals(double tolerance) {
  if (tolerance <= 0.0) return 3;
  return std::clamp(static_cast<int>(std::ceil(-std::log10(tolerance))) + 1, 3, 9);
}

std::string fault_text(const Fault& f) {
  return fmt::format("{}:{}{}", f.code.category().name(), f.code.value(),
                     f.text.empty() ? " " + f.code.message() : " " + f.text);
}

/// A device error's number as its manual writes it: the catalogue category's message starts with it.
std::string device_code(const Fault& f) {
  const std::string m = f.code.message();
  return m.substr(0, m.find(' '));
}

std::string fault_text(const FaultEvent& e) {
  if (e.source != "device") return fault_text(e.fault);
  return fmt::format("{} {}", fault_code_text(e), e.fault.text);
}

bool same_text(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::toupper(static_cast<unsigned char>(x)) == std::toupper(static_cast<unsigned char>(y));
         });
}

bool code_matches(const FaultEvent& e, const std::string& code) {
  if (code.empty()) return true;
  const auto c = parse_fault_code(code);
  if (!c || c->category != e.fault.code.category().name()) return false;
  if (c->value < 0) return e.source == "device" && same_text(c->text, device_code(e.fault));
  return e.fault.code.value() == c->value;
}

}  // namespace

bool fault_matches(const FaultEvent& e, const std::string& code) {
  return code_matches(e, code);
}

std::string fault_code_text(const FaultEvent& e) {
  if (e.source != "device") return fmt::format("{}:{}", e.fault.code.category().name(), e.fault.code.value());
  return fmt::format("{}:{}", e.fault.code.category().name(), device_code(e.fault));
}

std::string describe(const Expectation& e, const AxisSpec& axis) {
  return std::visit(
      Overloaded{
          [&](const PositionExpectation& p) {
            const int d = decimals(p.tolerance);
            std::string when = p.at   ? fmt::format(" at t={:.3f} s", to_seconds(*p.at))
                               : p.by ? fmt::format(" by t={:.3f} s", to_seconds(*p.by))
                                      : std::string(" at the end of the run");
            return fmt::format("position {:.{}f} +/- {:.{}f} {}{}", p.value, d, p.tolerance, d, axis.units, when);
          },
          [&](const FaultExpectation& f) {
            return fmt::format("fault {}{}", f.code.empty() ? "(any)" : f.code,
                               f.by ? fmt::format(" by t={:.3f} s", to_seconds(*f.by)) : std::string());
          },
          [&](const StateExpectation& s) {
            return fmt::format("state {}{}", s.state,
                               s.at ? fmt::format(" at t={:.3f} s", to_seconds(*s.at)) : " at the end of the run");
          },
          [&](const NoFaultExpectation&) { return std::string("no fault"); },
          [&](const MaxFollowingErrorExpectation& m) {
            return fmt::format("following error at most {:.{}f} {}", m.value, decimals(m.value), axis.units);
          },
          [&](const MovesExpectation& m) {
            return fmt::format("{} move{} over the run", m.count, m.count == 1 ? "" : "s");
          },
      },
      e.kind);
}

RunMonitor::RunMonitor(const Scenario& scenario, const Machine& machine)
    : scenario_(scenario), machine_(machine), io_(scenario, machine), ctl_(scenario, machine) {
  link_outages_seen_.assign(machine.modbus_links().size(), 0);
  gpio_outages_seen_.assign(machine.gpio_links().size(), 0);
  for (const auto& a : machine.axes()) tracks_.push_back(AxisTrack{&a, 0.0, {}, {}, {}});
  for (const auto& e : scenario.expectations) {
    ExpectationState s;
    s.e = &e;
    for (std::size_t i = 0; i < machine.axes().size(); ++i)
      if (machine.axes()[i].spec->name == e.axis) s.axis = i;
    std::visit(Overloaded{
                   [&](const PositionExpectation& p) {
                     if (p.at) latest_ = std::max(latest_, *p.at);
                     if (p.by) latest_ = std::max(latest_, *p.by);
                   },
                   [&](const FaultExpectation& f) {
                     if (f.by) latest_ = std::max(latest_, *f.by);
                   },
                   [&](const StateExpectation& st) {
                     if (st.at) latest_ = std::max(latest_, *st.at);
                   },
                   [](const auto&) {},
               },
               e.kind);
    states_.push_back(std::move(s));
  }
}

double RunMonitor::position_error(std::size_t axis, double position, double target) const {
  const AxisSpec& spec = *machine_.axes()[axis].spec;
  double d = position - target;
  if (spec.rotary && spec.modulo > 0.0) {
    d = std::fmod(d, spec.modulo);
    if (d > spec.modulo / 2) d -= spec.modulo;
    if (d < -spec.modulo / 2) d += spec.modulo;
  }
  return d;
}

std::string RunMonitor::fmt_pos(const ExpectationState& s, double v) const {
  const auto& p = std::get<PositionExpectation>(s.e->kind);
  return fmt::format("{:.{}f} {}", v, decimals(p.tolerance), machine_.axes()[s.axis].spec->units);
}

void RunMonitor::decide(ExpectationState& s, Duration t, const motion::AxisStatus& st) const {
  std::visit(Overloaded{
                 [&](const PositionExpectation& p) {
                   const double err = position_error(s.axis, st.position, p.value);
                   s.decided = true;
                   s.passed = std::abs(err) <= p.tolerance;
                   if (!s.passed) {
                     s.detail = fmt::format("was {} (off by {})", fmt_pos(s, st.position), fmt_pos(s, std::abs(err)));
                     if (p.by && s.best_set)
                       s.detail += fmt::format("; closest {} off at t={:.3f} s", fmt_pos(s, s.best_error),
                                               to_seconds(s.best_t));
                   }
                 },
                 [&](const StateExpectation& e) {
                   s.decided = true;
                   s.passed = e.state == motion::to_string(st.state);
                   if (!s.passed)
                     s.detail = fmt::format("was {} at t={:.3f} s{}", motion::to_string(st.state), to_seconds(t),
                                            st.fault ? " (" + fault_text(st.fault) + ")" : "");
                 },
                 [](const auto&) {},
             },
             s.e->kind);
}

void RunMonitor::track_start(ExpectationState& s, const motion::AxisStatus& st) const {
  if (const auto* p = std::get_if<PositionExpectation>(&s.e->kind)) {
    if (!s.seen) {
      s.start_position = st.position;
      s.held_at_start = std::abs(position_error(s.axis, st.position, p->value)) <= p->tolerance;
    } else if (std::abs(position_error(s.axis, st.position, s.start_position)) > p->tolerance) {
      s.changed = true;
    }
  } else if (const auto* e = std::get_if<StateExpectation>(&s.e->kind)) {
    if (!s.seen) {
      s.start_state = st.state;
      s.held_at_start = e->state == motion::to_string(st.state);
    } else if (st.state != s.start_state) {
      s.changed = true;
    }
  }
  s.seen = true;
}

void RunMonitor::observe(Duration t) noexcept {
  for (auto& tr : tracks_) {
    const auto& st = tr.axis->axis->status();
    const double fe = std::abs(st.following_error);
    if (fe > tr.max_fe) {
      tr.max_fe = fe;
      tr.max_fe_t = t;
    }
    // A move starts when the axis enters `moving` from rest; a new command while it still brakes
    // (stopping -> moving) continues the motion.
    if (st.state == motion::AxisState::moving && (!tr.state_seen || (tr.last_state != motion::AxisState::moving &&
                                                                     tr.last_state != motion::AxisState::stopping)))
      ++tr.moves;
    tr.state_seen = true;
    tr.last_state = st.state;
    if (st.fault.code != tr.last_axis_fault) {
      tr.last_axis_fault = st.fault.code;
      if (st.fault) faults_.push_back(FaultEvent{t, tr.axis->spec->name, "axis", st.fault});
    }
    const Fault& df = tr.axis->axis->drive().feedback().fault;
    if (df.code != tr.last_drive_fault) {
      tr.last_drive_fault = df.code;
      if (df) faults_.push_back(FaultEvent{t, tr.axis->spec->name, "drive", df});
    }
  }
  if (const auto* c = machine_.controller()) {
    const auto history = c->errors().history();
    for (; device_errors_seen_ < history.size(); ++device_errors_seen_) {
      const auto& e = history[device_errors_seen_];
      const bool on_axis = e.axis >= 0 && static_cast<std::size_t>(e.axis) < c->axis_specs().size();
      faults_.push_back(FaultEvent{t, on_axis ? c->axis_specs()[static_cast<std::size_t>(e.axis)].name : "controller",
                                   "device", e.fault});
      device_events_.push_back(DeviceErrorEvent{t, faults_.back().axis, e.fault.code.category().name(), e.code_text(),
                                                e.fault.text, std::string(profiles::to_string(e.reaction)),
                                                std::string(controllers::to_string(e.ack))});
    }
  }
  // An I/O link outage (the terminal stopped answering, refused a request, or its data went
  // stale) is a fault event of the link, once per outage.
  const auto outages = [&](const auto& links, std::vector<std::uint64_t>& seen) {
    for (std::size_t i = 0; i < links.size() && i < seen.size(); ++i) {
      const auto& l = *links[i].link;
      if (l.fault_count() == seen[i]) continue;
      seen[i] = l.fault_count();
      faults_.push_back(FaultEvent{t, links[i].name, "io_link", l.fault()});
    }
  };
  outages(machine_.modbus_links(), link_outages_seen_);
  outages(machine_.gpio_links(), gpio_outages_seen_);
  io_.observe(t);
  ctl_.observe(t);
  for (auto& s : states_) {
    const auto& st = machine_.axes()[s.axis].axis->status();
    track_start(s, st);
    if (s.decided) continue;
    if (const auto* p = std::get_if<PositionExpectation>(&s.e->kind)) {
      if (p->at && t >= *p->at) decide(s, t, st);
      if (p->by && !s.decided) {
        const double err = std::abs(position_error(s.axis, st.position, p->value));
        if (!s.best_set || err < s.best_error) {
          s.best_error = err;
          s.best_t = t;
          s.best_set = true;
        }
        if (err <= p->tolerance) {
          s.decided = true;
          s.passed = true;
        } else if (t >= *p->by) {
          decide(s, t, st);
        }
      }
    } else if (const auto* e = std::get_if<StateExpectation>(&s.e->kind)) {
      if (e->at && t >= *e->at) decide(s, t, st);
    }
  }
}

void RunMonitor::finish(Duration t_end, RunResult& r) const {
  r.faults = faults_;
  for (const auto& tr : tracks_) {
    const auto& st = tr.axis->axis->status();
    AxisSummary a;
    a.name = tr.axis->spec->name;
    a.units = tr.axis->spec->units;
    a.final_position = st.position;
    a.final_velocity = st.velocity;
    a.final_state = motion::to_string(st.state);
    a.max_following_error = tr.max_fe;
    a.max_following_error_t = tr.max_fe_t;
    for (const auto& f : faults_)
      if (f.axis == a.name) a.faults.push_back(f);
    r.axes.push_back(std::move(a));
  }
  for (const auto& s0 : states_) {
    ExpectationState s = s0;
    const AxisSpec& spec = *machine_.axes()[s.axis].spec;
    const auto& st = machine_.axes()[s.axis].axis->status();
    const std::string& name = spec.name;
    std::visit(Overloaded{
                   [&](const PositionExpectation& p) {
                     if (s.decided) return;
                     if (p.at || p.by) {
                       s.decided = true;
                       s.detail = fmt::format("the run ended at t={:.3f} s, before that time", to_seconds(t_end));
                       return;
                     }
                     decide(s, t_end, st);
                   },
                   [&](const StateExpectation& e) {
                     if (s.decided) return;
                     if (e.at) {
                       s.decided = true;
                       s.detail = fmt::format("the run ended at t={:.3f} s, before that time", to_seconds(t_end));
                       return;
                     }
                     decide(s, t_end, st);
                   },
                   [&](const FaultExpectation& f) {
                     s.decided = true;
                     std::string seen;
                     for (const auto& ev : faults_) {
                       if (ev.axis != name) continue;
                       if (code_matches(ev, f.code) && (!f.by || ev.t <= *f.by)) {
                         s.passed = true;
                         return;
                       }
                       seen += fmt::format("{}{} at t={:.3f} s", seen.empty() ? "" : "; ", fault_text(ev),
                                           to_seconds(ev.t));
                     }
                     s.detail = seen.empty() ? std::string("no fault occurred") : "saw " + seen;
                   },
                   [&](const NoFaultExpectation&) {
                     s.decided = true;
                     s.passed = true;
                     for (const auto& ev : faults_) {
                       if (ev.axis != name) continue;
                       s.passed = false;
                       s.detail = fmt::format("faulted at t={:.3f} s: {}", to_seconds(ev.t), fault_text(ev));
                       break;
                     }
                   },
                   [&](const MaxFollowingErrorExpectation& m) {
                     s.decided = true;
                     const AxisTrack& tr = tracks_[s.axis];
                     s.passed = tr.max_fe <= m.value;
                     if (!s.passed)
                       s.detail = fmt::format("reached {:.{}f} {} at t={:.3f} s (over by {:.{}f} {})", tr.max_fe,
                                              decimals(m.value), spec.units, to_seconds(tr.max_fe_t),
                                              tr.max_fe - m.value, decimals(m.value), spec.units);
                   },
                   [&](const MovesExpectation& m) {
                     s.decided = true;
                     const AxisTrack& tr = tracks_[s.axis];
                     s.passed = tr.moves == m.count;
                     if (!s.passed) s.detail = fmt::format("saw {} move{}", tr.moves, tr.moves == 1 ? "" : "s");
                   },
               },
               s.e->kind);
    ExpectationResult er{name, describe(*s.e, spec), s.passed, s.detail, s.e->source.line, s.e->source.path};
    // Met at the first cycle and nothing changed since (or a `by:` met at the first cycle, which
    // nothing after can undo): it passes, but it tests nothing.
    const auto* pos = std::get_if<PositionExpectation>(&s.e->kind);
    if (er.passed && s.held_at_start && (!s.changed || (pos != nullptr && pos->by)))
      r.warnings.push_back(
          fmt::format("{}:{} {}: axis {}: expected {} already holds at the start of the run{}: it checks nothing",
                      r.file, er.line, er.path, name, er.description,
                      pos != nullptr && pos->by ? " (`by:` accepts the first cycle)" : " and never changed"));
    if (!er.passed) {
      r.ok = false;
      r.failures.push_back(fmt::format("axis {}: expected {}, {}", name, er.description, er.detail));
    }
    r.expectations.push_back(std::move(er));
  }
  // A `device_error:` expectation accounts for the device errors it names (on an axis or the controller).
  const auto device_expected = [&](const FaultEvent& ev) {
    return ev.source == "device" &&
           std::ranges::any_of(scenario_.controller_expectations, [&](const ControllerExpectation& e) {
             return e.kind == ControllerExpectation::Kind::device_error && code_matches(ev, e.code);
           });
  };
  // Faults nobody expected fail the run.
  for (const auto& tr : tracks_) {
    const std::string& name = tr.axis->spec->name;
    bool expected = false;
    for (const auto& e : scenario_.expectations)
      if (e.axis == name && std::holds_alternative<FaultExpectation>(e.kind)) expected = true;
    if (expected) continue;
    // One line per axis: the device's error when the controller turned the fault into one (its
    // number is what the user looks up), else the first fault.
    const FaultEvent* first = nullptr;
    for (const auto& ev : faults_) {
      if (ev.axis != name || device_expected(ev)) continue;
      if (first == nullptr || (ev.source == "device" && first->source != "device")) first = &ev;
      if (first->source == "device") break;
    }
    if (first == nullptr) continue;
    r.ok = false;
    r.failures.push_back(fmt::format("axis {}: unexpected {} fault at t={:.3f} s: {}", name, first->source,
                                     to_seconds(first->t), fault_text(*first)));
  }
  // Device errors of the whole controller: expected when some fault expectation matches them.
  for (const auto& ev : faults_) {
    if (ev.axis != "controller") continue;
    const bool expected = device_expected(ev) || std::ranges::any_of(scenario_.expectations, [&](const Expectation& e) {
                            const auto* f = std::get_if<FaultExpectation>(&e.kind);
                            return f != nullptr && !f->code.empty() && code_matches(ev, f->code);
                          });
    if (expected) continue;
    r.ok = false;
    r.failures.push_back(
        fmt::format("controller: unexpected device error at t={:.3f} s: {}", to_seconds(ev.t), fault_text(ev)));
  }
  // An I/O link outage fails the run: the test bench lost its I/O, so what the run saw of it
  // cannot be trusted (there is no expectation for it).
  for (const auto& ev : faults_) {
    if (ev.source != "io_link") continue;
    r.ok = false;
    r.failures.push_back(
        fmt::format("{}: I/O link fault at t={:.3f} s: {}", ev.axis, to_seconds(ev.t), fault_text(ev)));
  }
  if (const auto* c = machine_.controller()) {
    r.controller = c->device();
    r.device_errors = device_events_;
  }
  io_.finish(t_end, r);
  ctl_.finish(t_end, r);
}

}  // namespace hil::runtime
