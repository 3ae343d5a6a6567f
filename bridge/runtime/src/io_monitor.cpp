// SPDX-License-Identifier: MIT
#include "hil/runtime/io_monitor.hpp"

#include <fmt/format.h>

namespace hil::runtime {
namespace {

std::string_view edge_name(IoExpectation::Edge e) noexcept {
  switch (e) {
    case IoExpectation::Edge::rising:
      return "rising";
    case IoExpectation::Edge::falling:
      return "falling";
    case IoExpectation::Edge::any:
      return "any";
  }
  return "?";
}

std::string when(std::optional<Duration> t, const char* word) {
  return t ? fmt::format(" {} t={:.3f} s", word, to_seconds(*t)) : std::string();
}

}  // namespace

std::string describe(const IoExpectation& e) {
  switch (e.kind) {
    case IoExpectation::Kind::state:
      return fmt::format("{} = {}{}", e.signal, e.state ? 1 : 0,
                         e.at ? when(e.at, "at") : std::string(" at the end of the run"));
    case IoExpectation::Kind::edges:
      return fmt::format("{} has {} {} edge{}", e.signal, e.count, edge_name(e.edge), e.count == 1 ? "" : "s");
    case IoExpectation::Kind::first_edge:
      return fmt::format("{} first {} edge{}{}", e.signal, edge_name(e.edge), when(e.after, "after"), when(e.by, "by"));
  }
  return e.signal;
}

IoMonitor::IoMonitor(const Scenario& scenario, const Machine& machine) : machine_(machine) {
  if (machine.controller() == nullptr) return;
  for (const auto& [name, address] : machine.io_signals())
    tracks_.push_back(Track{name, address, false, false, 0, 0, std::nullopt, std::nullopt});
  for (const auto& e : scenario.io_expectations) {
    ExpectationState s;
    s.e = &e;
    auto a = machine.controller()->resolve_bit(e.signal);
    s.track = a ? track_of(*a) : tracks_.size();
    if (e.at) latest_ = std::max(latest_, *e.at);
    if (e.by) latest_ = std::max(latest_, *e.by);
    states_.push_back(std::move(s));
  }
}

std::size_t IoMonitor::track_of(controllers::BitAddress a) const noexcept {
  for (std::size_t i = 0; i < tracks_.size(); ++i)
    if (tracks_[i].address == a) return i;
  return tracks_.size();
}

void IoMonitor::observe(Duration t) noexcept {
  const auto* c = machine_.controller();
  if (c == nullptr) return;
  for (auto& tr : tracks_) {
    const bool v = c->io().get(tr.address);
    if (tr.seen && v != tr.state) {
      if (v) {
        ++tr.rising;
        if (!tr.first_rising) tr.first_rising = t;
      } else {
        ++tr.falling;
        if (!tr.first_falling) tr.first_falling = t;
      }
    }
    tr.state = v;
    tr.seen = true;
  }
  for (auto& s : states_) {
    if (s.decided || s.track >= tracks_.size()) continue;
    if (s.e->kind == IoExpectation::Kind::state && s.e->at && t >= *s.e->at) {
      s.decided = true;
      s.passed = tracks_[s.track].state == s.e->state;
      if (!s.passed) s.detail = fmt::format("was {} at t={:.3f} s", tracks_[s.track].state ? 1 : 0, to_seconds(t));
    }
  }
}

void IoMonitor::finish(Duration t_end, RunResult& r) const {
  for (const auto& tr : tracks_) {
    r.io.push_back(IoSummary{tr.name, controllers::format_address(tr.address), tr.state, tr.rising, tr.falling,
                             tr.first_rising, tr.first_falling});
  }
  for (const auto& s0 : states_) {
    ExpectationState s = s0;
    if (s.track >= tracks_.size()) {
      s.decided = true;
      s.detail = "the signal is not in the controller's image";
    }
    const Track* tr = s.track < tracks_.size() ? &tracks_[s.track] : nullptr;
    if (!s.decided && tr != nullptr) {
      const IoExpectation& e = *s.e;
      switch (e.kind) {
        case IoExpectation::Kind::state:
          if (e.at) {
            s.detail = fmt::format("the run ended at t={:.3f} s, before that time", to_seconds(t_end));
          } else {
            s.passed = tr->state == e.state;
            if (!s.passed) s.detail = fmt::format("was {} at the end of the run", tr->state ? 1 : 0);
          }
          break;
        case IoExpectation::Kind::edges: {
          const std::uint64_t n = e.edge == IoExpectation::Edge::rising    ? tr->rising
                                  : e.edge == IoExpectation::Edge::falling ? tr->falling
                                                                           : tr->rising + tr->falling;
          s.passed = n == e.count;
          if (!s.passed) s.detail = fmt::format("saw {} ({} rising, {} falling)", n, tr->rising, tr->falling);
          break;
        }
        case IoExpectation::Kind::first_edge: {
          std::optional<Duration> first = e.edge == IoExpectation::Edge::rising    ? tr->first_rising
                                          : e.edge == IoExpectation::Edge::falling ? tr->first_falling
                                          : !tr->first_rising                      ? tr->first_falling
                                          : !tr->first_falling                     ? tr->first_rising
                                                               : std::min(*tr->first_rising, *tr->first_falling);
          if (!first) {
            s.detail = "no such edge occurred";
          } else {
            s.passed = (!e.after || *first >= *e.after) && (!e.by || *first <= *e.by);
            if (!s.passed) s.detail = fmt::format("the first edge came at t={:.3f} s", to_seconds(*first));
          }
          break;
        }
      }
    }
    ExpectationResult er{"io", describe(*s.e), s.passed, s.detail, s.e->source.line, s.e->source.path, true};
    if (!er.passed) {
      r.ok = false;
      r.failures.push_back(fmt::format("I/O: expected {}, {}", er.description, er.detail));
    }
    r.expectations.push_back(std::move(er));
  }
}

}  // namespace hil::runtime
