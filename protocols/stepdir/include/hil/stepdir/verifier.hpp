// SPDX-License-Identifier: MIT
#pragma once
// Checks a recorded step/dir edge stream against the timing rules and reports the first
// violation: edge order, redundant edges, pulse width, space, period (fmax), dir setup and hold,
// dir change during a pulse, and the step count. Streaming (feed edges one at a time) so a run can
// verify on the fly without keeping the stream. Pure.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "hil/gpio/edge.hpp"
#include "hil/stepdir/step_planner.hpp"
#include "hil/stepdir/timing.hpp"

namespace hil::stepdir {

enum class Rule : std::uint8_t {
  time_order,        ///< an edge earlier than the one before it
  redundant_edge,    ///< an "edge" that does not change the line's level
  pulse_width,       ///< active edge to trailing edge shorter than step_len
  step_space,        ///< trailing edge to next active edge shorter than step_space
  max_frequency,     ///< active edge to active edge shorter than 1/fmax
  dir_setup,         ///< dir change to next active edge shorter than dir_setup
  dir_hold,          ///< trailing edge to dir change shorter than dir_hold
  dir_during_pulse,  ///< dir changed while the step line was active
  step_count,        ///< net steps differ from the expected count
  unknown_line,      ///< an edge on a line that is neither step nor dir
};
[[nodiscard]] std::string_view to_string(Rule r) noexcept;

struct Violation {
  Rule rule = Rule::time_order;
  std::size_t index = 0;  ///< index of the offending edge in the stream
  std::int64_t t_ns = 0;
  std::int64_t measured = 0;  ///< ns, or steps for step_count
  std::int64_t limit = 0;     ///< ns, or steps
  /// "edge 41 at 1.234567 ms: pulse_width 1000 ns < 2000 ns (step_len)"
  [[nodiscard]] std::string describe() const;
};

struct VerifyStats {
  std::size_t edges = 0;
  std::int64_t steps_forward = 0;
  std::int64_t steps_backward = 0;
  std::int64_t min_period_ns = 0;  ///< shortest active-to-active interval seen (0: fewer than 2 steps)
  std::int64_t first_interval_ns = 0;
  [[nodiscard]] std::int64_t net_steps() const noexcept { return steps_forward - steps_backward; }
  [[nodiscard]] double max_frequency_hz() const noexcept {
    return min_period_ns > 0 ? 1e9 / static_cast<double>(min_period_ns) : 0.0;
  }
};

class StepVerifier {
 public:
  /// Initial levels: step idle, dir = `initial_dir` (+1 forward / -1 backward).
  explicit StepVerifier(const StepTiming& rules, StepLineIndex lines = {}, int initial_dir = 1) noexcept;

  /// Feed the next edge; edges on other lines count as `unknown_line` unless `ignore_other_lines`.
  void feed(const gpio::Edge& e) noexcept;
  void feed(std::span<const gpio::Edge> edges) noexcept {
    for (const auto& e : edges) feed(e);
  }
  /// Check the net step count (call after the last edge).
  void expect_net_steps(std::int64_t expected) noexcept;

  [[nodiscard]] bool ok() const noexcept { return !first_; }
  [[nodiscard]] const std::optional<Violation>& first_violation() const noexcept { return first_; }
  [[nodiscard]] const VerifyStats& stats() const noexcept { return stats_; }
  bool ignore_other_lines = true;

 private:
  void fail(Rule r, std::int64_t t, std::int64_t measured, std::int64_t limit) noexcept;
  StepTiming rules_;
  StepLineIndex lines_;
  std::int64_t min_period_by_freq_ = 0;
  bool step_level_;
  bool dir_level_;
  std::int64_t last_t_ = INT64_MIN;
  std::int64_t last_active_ = INT64_MIN;
  std::int64_t last_trailing_ = INT64_MIN;
  std::int64_t last_dir_change_ = INT64_MIN;
  std::optional<Violation> first_;
  VerifyStats stats_;
};

/// One-shot helper: verify a whole stream (and the net count when given).
[[nodiscard]] std::optional<Violation> verify_edges(std::span<const gpio::Edge> edges, const StepTiming& rules,
                                                    std::optional<std::int64_t> expected_net_steps = std::nullopt,
                                                    StepLineIndex lines = {}, VerifyStats* stats = nullptr);

}  // namespace hil::stepdir
