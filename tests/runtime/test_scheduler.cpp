// SPDX-License-Identifier: MIT
// Cycle scheduler: virtual time runs exact cycles; the Asio scheduler keeps an absolute grid on
// real time and reports latency (bounded ~50 ms smoke run, no timing assertions).
// A standard header before Asio: asio/detail/config.hpp picks its aligned allocator from
// libstdc++'s macros, and every translation unit must see the same choice (otherwise ASan reports
// an alloc-dealloc mismatch between TUs).
#include <vector>

#include <gtest/gtest.h>
#include <asio/io_context.hpp>

#include "hil/runtime/latency_histogram.hpp"
#include "hil/runtime/scheduler.hpp"

using namespace std::chrono_literals;
using hil::CycleTime;
using hil::Duration;
using hil::runtime::CycleControl;

TEST(VirtualScheduler, RunsCyclesOnAnExactGrid) {
  hil::VirtualClock clock;
  hil::runtime::VirtualScheduler s(clock, 1ms);
  std::vector<Duration> times;
  const auto stats = s.run([&](const CycleTime& c) {
    EXPECT_EQ(c.period, 1ms);
    times.push_back(c.now.time_since_epoch());
    return times.size() == 1000 ? CycleControl::stop : CycleControl::proceed;
  });
  ASSERT_EQ(times.size(), 1000u);
  EXPECT_EQ(stats.cycles, 1000u);
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_EQ(times[i], std::chrono::milliseconds(i));
  EXPECT_EQ(stats.simulated, 1000ms);
  EXPECT_TRUE(stats.virtual_time);
  EXPECT_EQ(stats.overruns, 0u);
}

TEST(VirtualScheduler, StopsAtMaxCycles) {
  hil::VirtualClock clock(hil::TimePoint{5s});
  hil::runtime::VirtualScheduler s(clock, 250us);
  int n = 0;
  const auto stats = s.run(
      [&](const CycleTime&) {
        ++n;
        return CycleControl::proceed;
      },
      40);
  EXPECT_EQ(n, 40);
  EXPECT_EQ(stats.cycles, 40u);
  EXPECT_EQ(stats.simulated, 10ms);
  EXPECT_GE(clock.now(), hil::TimePoint{5s + 9750us});
}

TEST(LatencyHistogram, Statistics) {
  hil::runtime::LatencyHistogram h;
  EXPECT_EQ(h.percentile(0.99), Duration{});
  for (int i = 1; i <= 100; ++i) h.add(std::chrono::microseconds(i));
  h.add(-5us);  // counts as 0
  EXPECT_EQ(h.count(), 101u);
  EXPECT_EQ(h.min(), 0us);
  EXPECT_EQ(h.max(), 100us);
  EXPECT_EQ(h.mean(), Duration{5050us} / 101);
  EXPECT_EQ(h.percentile(0.5), 51us);  // bucket upper edges, 1 µs resolution
  EXPECT_EQ(h.percentile(0.99), 100us);
  EXPECT_EQ(h.percentile(1.0), 100us);
  h.add(50ms);  // overflow bucket keeps the exact max
  EXPECT_EQ(h.max(), 50ms);
  EXPECT_EQ(h.percentile(1.0), 50ms);
}

TEST(AsioScheduler, RealTimeSmokeRun) {
  // ~50 ms of real time at 1 ms: checks the grid and the bookkeeping, not the machine's latency.
  asio::io_context io;
  hil::SteadyClock clock;
  hil::runtime::AsioScheduler s(io, clock, 1ms);
  std::vector<hil::TimePoint> deadlines;
  std::vector<hil::TimePoint> woke;
  const auto stats = s.run(
      [&](const CycleTime& c) {
        deadlines.push_back(c.now);
        woke.push_back(clock.now());
        return CycleControl::proceed;
      },
      50);
  ASSERT_EQ(stats.cycles, 50u);
  ASSERT_EQ(deadlines.size(), 50u);
  EXPECT_FALSE(stats.virtual_time);
  for (std::size_t i = 0; i < woke.size(); ++i) EXPECT_GE(woke[i], deadlines[i]) << "woke before its deadline";
  // Absolute grid: every deadline is start + k * period (skips after overruns keep the grid).
  for (std::size_t i = 1; i < deadlines.size(); ++i) {
    const auto step = deadlines[i] - deadlines[i - 1];
    EXPECT_EQ(step % 1ms, Duration::zero());
    EXPECT_GE(step, 1ms);
  }
  EXPECT_EQ(stats.wake_latency.count(), 50u);
  EXPECT_LE(stats.wake_latency.min(), stats.wake_latency.mean());
  EXPECT_LE(stats.wake_latency.mean(), stats.wake_latency.max());
  EXPECT_LE(stats.wake_latency.percentile(0.99), stats.wake_latency.max());
  EXPECT_EQ(stats.simulated, 1ms * static_cast<long>(50 + stats.skipped_cycles));
}

TEST(AsioScheduler, CycleFunctionStopsTheRunAndStopCancels) {
  asio::io_context io;
  hil::SteadyClock clock;
  hil::runtime::AsioScheduler s(io, clock, 1ms);
  int n = 0;
  auto stats = s.run([&](const CycleTime&) { return ++n == 3 ? CycleControl::stop : CycleControl::proceed; });
  EXPECT_EQ(stats.cycles, 3u);

  bool done = false;
  s.async_run([&](const CycleTime&) { return CycleControl::proceed; },
              [&](const hil::runtime::SchedulerStats& st) {
                done = true;
                EXPECT_EQ(st.cycles, 0u);
              });
  s.stop();
  io.restart();
  io.run_for(1s);  // returns as soon as the cancelled timer completed
  EXPECT_TRUE(done);
}

TEST(AsioScheduler, OverrunKeepsTheGridAndSkipsMissedDeadlines) {
  // Cycle 3 works for 3.5 periods (busy, measured on the clock, no sleep): it must be counted as
  // an overrun, the deadlines it missed skipped, and the grid kept.
  asio::io_context io;
  hil::SteadyClock clock;
  hil::runtime::AsioScheduler s(io, clock, 2ms);
  std::vector<hil::TimePoint> deadlines;
  const auto stats = s.run(
      [&](const CycleTime& c) {
        deadlines.push_back(c.now);
        if (deadlines.size() == 3) {
          const auto until = clock.now() + 7ms;
          while (clock.now() < until) {
          }
        }
        return CycleControl::proceed;
      },
      6);
  ASSERT_EQ(deadlines.size(), 6u);
  EXPECT_GE(stats.overruns, 1u);
  EXPECT_GE(stats.skipped_cycles, 3u);
  EXPECT_GE(stats.max_cycle_work, 7ms);
  EXPECT_GE(deadlines[3] - deadlines[2], 8ms);  // 3.5 periods of work: the next free slot is 4 periods on
  for (std::size_t i = 1; i < deadlines.size(); ++i) EXPECT_EQ((deadlines[i] - deadlines[0]) % 2ms, Duration::zero());
}
