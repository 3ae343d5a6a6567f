// SPDX-License-Identifier: MIT
// AsyncEdgeWriter on mock lines (real time, no chip): batches handed over by a "motion" thread
// while another thread reads the statistics go out on the writer's thread, every edge once and in
// order; drain() waits for them; a line error is reported; destruction with a backlog stops after
// the batch in progress. Also the ThreadSanitizer cover of the edge writer (scripts/tsan.sh).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <thread>
#include <vector>

#include "hil/core/clock.hpp"
#include "hil/gpio/io/edge_writer.hpp"
#include "hil/mocks/gpio/mock_lines.hpp"

using namespace hil::gpio;
using namespace std::chrono_literals;

namespace {
std::vector<LineSpec> step_and_dir() {
  return {LineSpec{"step", 0U, "", LineDirection::output, false, Bias::as_is, false},
          LineSpec{"dir", 1U, "", LineDirection::output, false, Bias::as_is, false}};
}
std::int64_t now_ns(const hil::SteadyClock& c) {
  return c.now().time_since_epoch().count();
}
/// `n` step pulses (high, then low 20 us later) every 50 us from `t0`.
std::vector<Edge> pulses(std::int64_t t0, int n) {
  std::vector<Edge> e;
  for (int i = 0; i < n; ++i) {
    e.push_back({t0 + i * 50'000LL, 0, true});
    e.push_back({t0 + i * 50'000LL + 20'000, 0, false});
  }
  return e;
}
/// The recorded edges alternate on the step line, start high, and never go back in time.
void expect_pulse_train(const mock::MockLines& lines) {
  const auto& rec = lines.recorded();
  for (std::size_t i = 0; i < rec.size(); ++i) {
    EXPECT_EQ(rec[i].line, 0) << "edge " << i;
    EXPECT_EQ(rec[i].level, i % 2 == 0) << "edge " << i;
    if (i > 0) {
      EXPECT_GE(rec[i].t_ns, rec[i - 1].t_ns) << "edge " << i;
    }
  }
  EXPECT_EQ(lines.errors(), std::vector<std::string>{});
}
}  // namespace

TEST(AsyncEdgeWriter, BatchesFromAnotherThreadGoOutOnceAndInOrder) {
  hil::SteadyClock clock;
  mock::MockLines lines(step_and_dir(), clock);
  AsyncEdgeWriter writer(lines, clock);
  writer.set_time_offset(0);
  constexpr int batches = 100, per_batch = 2;
  std::atomic<bool> done{false};
  std::uint64_t max_seen = 0;
  std::thread observer([&] {  // a report reads the statistics while edges go out
    while (!done) {
      max_seen = std::max(max_seen, writer.stats().edges);
      EXPECT_FALSE(writer.last_error());
      std::this_thread::sleep_for(200us);
    }
  });
  std::thread motion([&] {  // the motion cycle hands over one batch per cycle, never blocking
    const std::int64_t t0 = now_ns(clock) + 2'000'000;
    for (int b = 0; b < batches; ++b) {
      const auto batch = pulses(t0 + b * per_batch * 50'000LL, per_batch);
      if (b % 2 == 0)
        writer.output(batch);
      else
        writer.submit(batch);
    }
  });
  motion.join();
  ASSERT_TRUE(writer.drain(10s)) << "every queued edge out";
  done = true;
  observer.join();
  EXPECT_EQ(lines.recorded().size(), std::size_t{batches * per_batch * 2});
  expect_pulse_train(lines);
  const auto s = writer.stats();
  EXPECT_EQ(s.edges, std::uint64_t{batches * per_batch * 2});
  EXPECT_EQ(s.io_errors, 0u);
  EXPECT_LE(max_seen, s.edges);
  EXPECT_FALSE(lines.output_level(0)) << "the last pulse ended low";
}

TEST(AsyncEdgeWriter, ALineErrorIsCountedAndReportedAndTheRestStillGoesOut) {
  hil::SteadyClock clock;
  mock::MockLines lines(step_and_dir(), clock);
  AsyncEdgeWriter writer(lines, clock);
  auto batch = pulses(now_ns(clock), 2);
  batch.insert(batch.begin() + 1, Edge{batch[0].t_ns + 1'000, 7, true});  // no line 7
  std::thread motion([&] { writer.submit(batch); });
  motion.join();
  ASSERT_TRUE(writer.drain(10s));
  EXPECT_EQ(writer.last_error(), std::make_error_code(std::errc::invalid_argument));
  EXPECT_EQ(writer.stats().io_errors, 1u);
  EXPECT_EQ(writer.stats().edges, 5u) << "the failed edge is counted, the others are out";
  EXPECT_EQ(lines.recorded().size(), 4u);
  expect_pulse_train(lines);
}

TEST(AsyncEdgeWriter, DestructionWithABacklogStopsAfterTheBatchInProgress) {
  hil::SteadyClock clock;
  mock::MockLines lines(step_and_dir(), clock);
  const auto start = std::chrono::steady_clock::now();
  {
    AsyncEdgeWriter writer(lines, clock);
    const std::int64_t t0 = now_ns(clock) + 1'000'000;
    std::thread motion([&] {
      for (int b = 0; b < 200; ++b) writer.submit(pulses(t0 + b * 5'000'000LL, 1));  // 1 s of pulses
    });
    motion.join();
  }  // the writer thread is joined here, without waiting for the 1 s backlog
  EXPECT_LT(std::chrono::steady_clock::now() - start, 500ms);
  EXPECT_LT(lines.recorded().size(), 400u) << "the backlog was dropped";
  EXPECT_EQ(lines.recorded().size() % 2, 0u) << "whole batches only";
  expect_pulse_train(lines);
}
