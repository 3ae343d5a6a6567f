// SPDX-License-Identifier: MIT
#pragma once
// Mock GPIO lines: a LineBank that records every output edge with its timestamp and drives its
// inputs from sources (a fixed level, a timed script, or a function of the steps output so far,
// which closes the loop in simulation). Used by tests and by `hilbridge run` without a chip.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "hil/core/clock.hpp"
#include "hil/gpio/edge.hpp"
#include "hil/gpio/edge_sink.hpp"
#include "hil/gpio/line_bank.hpp"
#include "hil/gpio/line_config.hpp"

namespace hil::gpio::mock {

/// Logical level of an input at time t_ns.
using InputSource = std::function<bool(std::int64_t t_ns)>;

/// Level changes at given times; the level before the first entry is `initial`.
struct InputScript {
  bool initial = false;
  std::vector<std::pair<std::int64_t, bool>> changes;  ///< (t_ns, level), sorted by time
  [[nodiscard]] bool level_at(std::int64_t t_ns) const noexcept;
};

class MockLines final : public LineBank, public EdgeSink {
 public:
  /// Thread: single-threaded unless used as the target of an EdgeWriter (then one writer thread).
  MockLines(std::vector<LineSpec> specs, const Clock& clock);

  [[nodiscard]] std::size_t size() const noexcept override { return specs_.size(); }
  /// Records an edge at clock.now() when the level changes (outputs only).
  std::error_code set_value(std::size_t index, bool level) noexcept override;
  [[nodiscard]] std::expected<bool, std::error_code> get_value(std::size_t index) noexcept override;
  /// EdgeSink: record a planned batch at its own timestamps (virtual time).
  void output(std::span<const Edge> edges) noexcept override;

  void set_input(std::size_t index, bool level);
  void set_input_source(std::size_t index, InputSource source);
  /// Force an input (fault injection: a broken wire reads as 0). std::nullopt releases it.
  void force_input(std::size_t index, std::optional<bool> level);
  /// Make every get_value/set_value of line `index` fail with `error` (a chip that went away:
  /// ENODEV); an empty code heals it.
  void fail_line(std::size_t index, std::error_code error);

  [[nodiscard]] const std::vector<Edge>& recorded() const noexcept { return recorded_; }
  void clear_recorded() noexcept { recorded_.clear(); }
  /// Keep at most this many recorded edges (0 = no recording, only observers and counters).
  void set_record_limit(std::size_t n) noexcept { record_limit_ = n; }
  [[nodiscard]] std::uint64_t edges_seen() const noexcept { return edges_seen_; }
  /// Protocol errors seen by the mock: edges on inputs, out-of-order edges, redundant edges.
  [[nodiscard]] const std::vector<std::string>& errors() const noexcept { return errors_; }
  /// Called for every recorded output edge, in time order.
  void add_observer(std::function<void(const Edge&)> f) { observers_.push_back(std::move(f)); }
  [[nodiscard]] bool output_level(std::size_t index) const noexcept { return index < levels_.size() && levels_[index]; }
  [[nodiscard]] const LineSpec& spec(std::size_t index) const { return specs_.at(index); }

 private:
  void record(const Edge& e) noexcept;
  std::vector<LineSpec> specs_;
  const Clock& clock_;
  std::vector<bool> levels_;
  std::vector<InputSource> sources_;
  std::vector<std::optional<bool>> forced_;
  std::vector<std::error_code> failing_;
  std::vector<Edge> recorded_;
  std::size_t record_limit_ = SIZE_MAX;
  std::uint64_t edges_seen_ = 0;
  std::int64_t last_t_ = INT64_MIN;
  std::vector<std::string> errors_;
  std::vector<std::function<void(const Edge&)>> observers_;
};

/// Follows the step/dir output edges of a MockLines and knows the motor position (steps) at any
/// time: the plant side of the closed loop. Edges are applied lazily up to the asked time,
/// because a drive records a whole window of edges ahead of the clock.
class StepDirDecoder {
 public:
  StepDirDecoder(MockLines& outputs, std::uint16_t step_line, std::uint16_t dir_line, bool active_level,
                 bool dir_forward_level, std::int64_t initial_position = 0);
  [[nodiscard]] std::int64_t position_at(std::int64_t t_ns);
  [[nodiscard]] std::int64_t position() const noexcept { return position_; }

 private:
  void on_edge(const Edge& e);
  std::uint16_t step_line_, dir_line_;
  bool active_level_, dir_forward_level_;
  bool dir_level_;
  std::int64_t position_;
  std::vector<Edge> queue_;
  std::size_t head_ = 0;
};

}  // namespace hil::gpio::mock
