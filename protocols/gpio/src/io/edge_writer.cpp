// SPDX-License-Identifier: MIT
#include "hil/gpio/io/edge_writer.hpp"

#include <algorithm>
#include <bit>

#include <pthread.h>
#include <sched.h>

namespace hil::gpio {

std::int64_t EdgeWriterStats::quantile_bound_ns(double p) const noexcept {
  if (edges == 0) return 0;
  const auto want = static_cast<std::uint64_t>(p * static_cast<double>(edges) + 0.999999);
  std::uint64_t acc = 0;
  for (std::size_t i = 0; i < buckets; ++i) {
    acc += histogram[i];
    if (acc >= want) return i + 1 == buckets ? max_error_ns : (std::int64_t{1000} << i);
  }
  return max_error_ns;
}

void EdgeWriterStats::merge(const EdgeWriterStats& o) noexcept {
  edges += o.edges;
  late += o.late;
  io_errors += o.io_errors;
  max_error_ns = std::max(max_error_ns, o.max_error_ns);
  sum_error_ns += o.sum_error_ns;
  max_slip_ns = std::max(max_slip_ns, o.max_slip_ns);
  slip_ns = o.slip_ns;
  for (std::size_t i = 0; i < buckets; ++i) histogram[i] += o.histogram[i];
}

std::error_code EdgeWriter::write(std::span<const Edge> edges) noexcept {
  std::error_code first;
  for (const Edge& e : edges) {
    // Absorb slip in long gaps only, never below the resync gap.
    if (stats_.slip_ns > 0 && last_edge_ns_ != INT64_MIN) {
      const std::int64_t gap = e.t_ns - last_edge_ns_;
      const std::int64_t spare = gap - options_.resync_gap.count();
      if (spare > 0) stats_.slip_ns = std::max<std::int64_t>(0, stats_.slip_ns - spare);
    }
    last_edge_ns_ = e.t_ns;
    const std::int64_t due = e.t_ns + stats_.slip_ns;
    for (;;) {
      const std::int64_t now = clock_.now().time_since_epoch().count();
      const std::int64_t left = due - now;
      if (left <= 0) break;
      if (left > options_.spin_window.count()) {
        std::this_thread::sleep_for(Duration(left - options_.spin_window.count()));
      }
      // else spin: the steady clock read is the tightest wait user space has.
    }
    if (auto ec = lines_.set_value(e.line, e.level)) {
      ++stats_.io_errors;
      if (!first) first = ec;
    }
    const std::int64_t done = clock_.now().time_since_epoch().count();
    const std::int64_t err = std::max<std::int64_t>(0, done - due);
    ++stats_.edges;
    stats_.sum_error_ns += err;
    stats_.max_error_ns = std::max(stats_.max_error_ns, err);
    const auto us = static_cast<std::uint64_t>(err / 1000);
    const std::size_t bucket = std::min<std::size_t>(EdgeWriterStats::buckets - 1, us == 0 ? 0 : std::bit_width(us));
    ++stats_.histogram[bucket];
    if (err > options_.late_threshold.count()) {
      ++stats_.late;
      // Keep the schedule's intervals: everything after this edge shifts by the lateness.
      stats_.slip_ns += err;
      stats_.max_slip_ns = std::max(stats_.max_slip_ns, stats_.slip_ns);
    }
  }
  return first;
}

AsyncEdgeWriter::AsyncEdgeWriter(LineBank& lines, const SteadyClock& clock, EdgeWriterOptions options)
    : writer_(lines, clock, options), rt_priority_(options.realtime_priority), thread_([this] { run(); }) {}

AsyncEdgeWriter::~AsyncEdgeWriter() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void AsyncEdgeWriter::submit(std::span<const Edge> edges) {
  if (edges.empty()) return;
  {
    std::lock_guard lock(mutex_);
    queue_.emplace_back(edges.begin(), edges.end());
  }
  cv_.notify_one();
}

void AsyncEdgeWriter::output(std::span<const Edge> edges) noexcept {
  if (edges.empty()) return;
  try {
    std::vector<Edge> batch(edges.begin(), edges.end());
    for (auto& e : batch) e.t_ns += offset_ns_;
    {
      std::lock_guard lock(mutex_);
      queue_.push_back(std::move(batch));
    }
    cv_.notify_one();
  } catch (...) {
    std::lock_guard lock(mutex_);
    last_error_ = std::make_error_code(std::errc::not_enough_memory);
  }
}

bool AsyncEdgeWriter::drain(Duration timeout) {
  std::unique_lock lock(mutex_);
  return idle_cv_.wait_for(lock, timeout, [this] { return queue_.empty() && !busy_; });
}

EdgeWriterStats AsyncEdgeWriter::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::error_code AsyncEdgeWriter::realtime_error() const {
  std::lock_guard lock(mutex_);
  return rt_error_;
}

std::error_code AsyncEdgeWriter::last_error() const {
  std::lock_guard lock(mutex_);
  return last_error_;
}

void AsyncEdgeWriter::run() {
  if (rt_priority_ > 0) {
    sched_param sp{};
    sp.sched_priority =
        std::clamp(rt_priority_, sched_get_priority_min(SCHED_FIFO), sched_get_priority_max(SCHED_FIFO));
    if (int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp); rc != 0) {
      std::lock_guard lock(mutex_);
      rt_error_ = std::error_code(rc, std::generic_category());
    }
  }
  for (;;) {
    std::vector<Edge> batch;
    {
      std::unique_lock lock(mutex_);
      cv_.wait(lock, [this] { return stop_ || !queue_.empty(); });
      // Destruction does not wait for a backlog (finish()/drain() reports one before that).
      if (stop_) return;
      batch = std::move(queue_.front());
      queue_.pop_front();
      busy_ = true;
    }
    auto ec = writer_.write(batch);
    {
      std::lock_guard lock(mutex_);
      stats_ = writer_.stats();
      if (ec) last_error_ = ec;
      busy_ = false;
    }
    idle_cv_.notify_all();
  }
}

}  // namespace hil::gpio
