// SPDX-License-Identifier: MIT
#pragma once
// Outputs a schedule of timestamped edges on real lines with the best timing user space allows:
// sleep until shortly before an edge, then spin on the steady clock, then one set_value ioctl.
//
// Never drops an edge. An edge that cannot be output on time is output as soon as possible and
// counted as late; the rest of the schedule then slips by the same amount (so pulse widths,
// spaces and direction setup/hold only ever stretch, never shrink). The slip is absorbed only in
// gaps longer than `resync_gap` (standstill), which no step timing rule can notice.

#include <array>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <span>
#include <system_error>
#include <thread>
#include <vector>

#include "hil/core/clock.hpp"
#include "hil/gpio/edge.hpp"
#include "hil/gpio/edge_sink.hpp"
#include "hil/gpio/line_bank.hpp"

namespace hil::gpio {

struct EdgeWriterOptions {
  Duration spin_window{std::chrono::microseconds(200)};    ///< spin (not sleep) this close to an edge
  Duration late_threshold{std::chrono::microseconds(50)};  ///< error above this counts as late
  Duration resync_gap{std::chrono::milliseconds(1)};       ///< gaps at least this long absorb slip
  int realtime_priority = 0;  ///< AsyncEdgeWriter: SCHED_FIFO priority for its thread (0 = normal scheduling)
};

/// Timing error = (time set_value returned) - (edge time + current slip), per edge.
struct EdgeWriterStats {
  static constexpr std::size_t buckets = 16;  ///< bucket i: error < 2^i µs (last: everything above)
  std::uint64_t edges = 0;
  std::uint64_t late = 0;       ///< edges whose lateness vs. the schedule exceeded late_threshold
  std::uint64_t io_errors = 0;  ///< set_value failures (edge still counted, level unknown)
  std::int64_t max_error_ns = 0;
  std::int64_t sum_error_ns = 0;
  std::int64_t max_slip_ns = 0;  ///< largest shift of the schedule caused by late edges
  std::int64_t slip_ns = 0;      ///< current shift
  std::array<std::uint64_t, buckets> histogram{};

  [[nodiscard]] double mean_error_ns() const noexcept {
    return edges ? static_cast<double>(sum_error_ns) / static_cast<double>(edges) : 0.0;
  }
  /// Upper bound (ns) of the bucket that holds the p-quantile (0 < p <= 1).
  [[nodiscard]] std::int64_t quantile_bound_ns(double p) const noexcept;
  void merge(const EdgeWriterStats& o) noexcept;
};

/// Synchronous writer. `write` blocks until the last edge of the batch is out.
/// Thread: one thread at a time; uses real time only (SteadyClock), never a VirtualClock.
class EdgeWriter {
 public:
  EdgeWriter(LineBank& lines, const SteadyClock& clock, EdgeWriterOptions options = {}) noexcept
      : lines_(lines), clock_(clock), options_(options) {}

  /// Output `edges` (sorted by time). Returns the first I/O error (all edges are still attempted).
  std::error_code write(std::span<const Edge> edges) noexcept;
  [[nodiscard]] const EdgeWriterStats& stats() const noexcept { return stats_; }
  void reset_stats() noexcept { stats_ = {}; }

 private:
  LineBank& lines_;
  const SteadyClock& clock_;
  EdgeWriterOptions options_;
  EdgeWriterStats stats_;
  std::int64_t last_edge_ns_ = INT64_MIN;
};

/// The writer on its own thread, so the motion cycle only enqueues (non-blocking) batches.
/// Call drain() before destruction: the destructor stops after the batch in progress.
/// Thread: submit/stats/drain from any thread; the lines are touched only by the writer thread.
class AsyncEdgeWriter final : public EdgeSink {
 public:
  AsyncEdgeWriter(LineBank& lines, const SteadyClock& clock, EdgeWriterOptions options = {});
  ~AsyncEdgeWriter() override;
  AsyncEdgeWriter(const AsyncEdgeWriter&) = delete;
  AsyncEdgeWriter& operator=(const AsyncEdgeWriter&) = delete;

  /// Queue a batch (copied). Never blocks on the lines.
  void submit(std::span<const Edge> edges);
  /// EdgeSink: submit with every time shifted by `offset_ns` (virtual-to-steady timeline).
  void output(std::span<const Edge> edges) noexcept override;
  void set_time_offset(std::int64_t offset_ns) noexcept { offset_ns_ = offset_ns; }
  /// Wait until every queued edge is out, at most `timeout`. Returns false on timeout.
  bool drain(Duration timeout);
  [[nodiscard]] EdgeWriterStats stats() const;
  [[nodiscard]] std::error_code last_error() const;
  /// Result of the SCHED_FIFO request (empty when not asked or granted; EPERM without CAP_SYS_NICE).
  [[nodiscard]] std::error_code realtime_error() const;

 private:
  void run();
  EdgeWriter writer_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::condition_variable idle_cv_;
  std::deque<std::vector<Edge>> queue_;
  bool busy_ = false;
  bool stop_ = false;
  EdgeWriterStats stats_;
  std::error_code last_error_;
  std::int64_t offset_ns_ = 0;
  int rt_priority_ = 0;
  std::error_code rt_error_;
  std::thread thread_;
};

}  // namespace hil::gpio
