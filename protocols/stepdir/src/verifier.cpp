// SPDX-License-Identifier: MIT
#include "hil/stepdir/verifier.hpp"

#include <cmath>

#include <fmt/format.h>

namespace hil::stepdir {

std::string_view to_string(Rule r) noexcept {
  switch (r) {
    case Rule::time_order:
      return "time_order";
    case Rule::redundant_edge:
      return "redundant_edge";
    case Rule::pulse_width:
      return "pulse_width";
    case Rule::step_space:
      return "step_space";
    case Rule::max_frequency:
      return "max_frequency";
    case Rule::dir_setup:
      return "dir_setup";
    case Rule::dir_hold:
      return "dir_hold";
    case Rule::dir_during_pulse:
      return "dir_during_pulse";
    case Rule::step_count:
      return "step_count";
    case Rule::unknown_line:
      return "unknown_line";
  }
  return "?";
}

std::string Violation::describe() const {
  const double ms = static_cast<double>(t_ns) * 1e-6;
  switch (rule) {
    case Rule::step_count:
      return fmt::format("after edge {}: step_count: net {} steps, expected {}", index, measured, limit);
    case Rule::time_order:
      return fmt::format("edge {} at {:.6f} ms: time_order: earlier than the previous edge ({} ns)", index, ms,
                         measured);
    case Rule::redundant_edge:
      return fmt::format("edge {} at {:.6f} ms: redundant_edge: level unchanged", index, ms);
    case Rule::unknown_line:
      return fmt::format("edge {} at {:.6f} ms: unknown_line {}", index, ms, measured);
    case Rule::dir_during_pulse:
      return fmt::format("edge {} at {:.6f} ms: dir_during_pulse: dir changed while the step line was active", index,
                         ms);
    default:
      return fmt::format("edge {} at {:.6f} ms: {} {} ns < {} ns", index, ms, to_string(rule), measured, limit);
  }
}

StepVerifier::StepVerifier(const StepTiming& rules, StepLineIndex lines, int initial_dir) noexcept
    : rules_(rules),
      lines_(lines),
      min_period_by_freq_(static_cast<std::int64_t>(std::ceil(1e9 / rules.max_freq_hz))),
      step_level_(rules.step_idle_level()),
      dir_level_(rules.dir_level(initial_dir)) {}

void StepVerifier::fail(Rule r, std::int64_t t, std::int64_t measured, std::int64_t limit) noexcept {
  if (!first_) first_ = Violation{r, stats_.edges, t, measured, limit};
}

void StepVerifier::feed(const gpio::Edge& e) noexcept {
  if (e.line != lines_.step && e.line != lines_.dir) {
    if (!ignore_other_lines) fail(Rule::unknown_line, e.t_ns, e.line, 0);
    ++stats_.edges;
    return;
  }
  if (last_t_ != INT64_MIN && e.t_ns < last_t_) fail(Rule::time_order, e.t_ns, e.t_ns - last_t_, 0);
  last_t_ = std::max(last_t_, e.t_ns);
  const bool active_level = !rules_.step_idle_level();
  if (e.line == lines_.step) {
    if (e.level == step_level_) {
      fail(Rule::redundant_edge, e.t_ns, 0, 0);
    } else if (e.level == active_level) {
      if (last_trailing_ != INT64_MIN && e.t_ns - last_trailing_ < rules_.step_space_ns) {
        fail(Rule::step_space, e.t_ns, e.t_ns - last_trailing_, rules_.step_space_ns);
      }
      if (last_active_ != INT64_MIN) {
        const std::int64_t period = e.t_ns - last_active_;
        if (period < min_period_by_freq_) fail(Rule::max_frequency, e.t_ns, period, min_period_by_freq_);
        if (stats_.min_period_ns == 0 || period < stats_.min_period_ns) stats_.min_period_ns = period;
        if (stats_.first_interval_ns == 0) stats_.first_interval_ns = period;
      }
      if (last_dir_change_ != INT64_MIN && last_dir_change_ > last_active_ &&
          e.t_ns - last_dir_change_ < rules_.dir_setup_ns) {
        fail(Rule::dir_setup, e.t_ns, e.t_ns - last_dir_change_, rules_.dir_setup_ns);
      }
      if (dir_level_ == rules_.dir_forward_level) {
        ++stats_.steps_forward;
      } else {
        ++stats_.steps_backward;
      }
      last_active_ = e.t_ns;
    } else {
      if (e.t_ns - last_active_ < rules_.step_len_ns) {
        fail(Rule::pulse_width, e.t_ns, e.t_ns - last_active_, rules_.step_len_ns);
      }
      last_trailing_ = e.t_ns;
    }
    step_level_ = e.level;
  } else {
    if (e.level == dir_level_) {
      fail(Rule::redundant_edge, e.t_ns, 0, 0);
    } else if (step_level_ == active_level) {
      fail(Rule::dir_during_pulse, e.t_ns, 0, 0);
    } else if (last_trailing_ != INT64_MIN && e.t_ns - last_trailing_ < rules_.dir_hold_ns) {
      fail(Rule::dir_hold, e.t_ns, e.t_ns - last_trailing_, rules_.dir_hold_ns);
    }
    dir_level_ = e.level;
    last_dir_change_ = e.t_ns;
  }
  ++stats_.edges;
}

void StepVerifier::expect_net_steps(std::int64_t expected) noexcept {
  if (stats_.net_steps() != expected) {
    if (!first_) first_ = Violation{Rule::step_count, stats_.edges, last_t_, stats_.net_steps(), expected};
  }
}

std::optional<Violation> verify_edges(std::span<const gpio::Edge> edges, const StepTiming& rules,
                                      std::optional<std::int64_t> expected_net_steps, StepLineIndex lines,
                                      VerifyStats* stats) {
  StepVerifier v(rules, lines);
  v.feed(edges);
  if (expected_net_steps) v.expect_net_steps(*expected_net_steps);
  if (stats) *stats = v.stats();
  return v.first_violation();
}

}  // namespace hil::stepdir
