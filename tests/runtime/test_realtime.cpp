// SPDX-License-Identifier: MIT
// Real-time mode: the scheduler's sleeper path (a recording sleeper that never sleeps), the
// latency presentation maths, CPU lists, the scenario key, and the Linux session: applied and
// restored as root (skipped when SCHED_FIFO is refused), refused with what to do as an
// unprivileged user (a forked child that drops to nobody).
#include <sched.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <vector>

#include <gtest/gtest.h>
#include <asio/io_context.hpp>
#include <asio/post.hpp>

#include "hil/runtime/latency_report.hpp"
#include "hil/runtime/linux/realtime_session.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "hil/runtime/scheduler.hpp"

using namespace std::chrono_literals;
using hil::CycleTime;
using hil::Duration;
using hil::TimePoint;
using hil::runtime::CycleControl;
using hil::runtime::LatencyHistogram;

namespace {

// Returns at once and remembers the deadlines it was asked to wait for.
class RecordingSleeper final : public hil::runtime::DeadlineSleeper {
 public:
  void sleep_until(TimePoint deadline) noexcept override { deadlines.push_back(deadline); }
  std::vector<TimePoint> deadlines;
};

}  // namespace

TEST(RealtimeScheduler, SleeperWaitsForEveryDeadlineOnTheAbsoluteGrid) {
  asio::io_context io;
  hil::SteadyClock clock;
  RecordingSleeper sleeper;
  hil::runtime::AsioScheduler s(io, clock, 1ms, &sleeper);
  std::vector<TimePoint> cycles;
  int io_handlers = 0;
  const auto stats = s.run(
      [&](const CycleTime& c) {
        cycles.push_back(c.now);
        // I/O completions posted during a cycle run before the next sleep.
        asio::post(io, [&] { ++io_handlers; });
        return CycleControl::proceed;
      },
      50);
  ASSERT_EQ(stats.cycles, 50u);
  ASSERT_EQ(sleeper.deadlines.size(), 50u);
  // Every cycle sleeps to its own deadline on the 1 ms grid; a busy machine may make a cycle
  // overrun, and then the scheduler skips the deadlines it missed (counted), never drifts.
  std::uint64_t gaps = 0;
  for (std::size_t i = 0; i < cycles.size(); ++i) {
    EXPECT_EQ(sleeper.deadlines[i], cycles[i]);
    if (i > 0) {
      const auto step = cycles[i] - cycles[i - 1];
      EXPECT_GE(step, 1ms);
      EXPECT_EQ(step % 1ms, Duration::zero()) << "off the grid at cycle " << i;
      gaps += static_cast<std::uint64_t>(step / 1ms) - 1;
    }
  }
  EXPECT_EQ(gaps, stats.skipped_cycles);
  // The last cycle's handler is left for the caller's final poll (the runner flushes it).
  EXPECT_EQ(io_handlers, 49);
  io.restart();
  io.poll();
  EXPECT_EQ(io_handlers, 50);
  EXPECT_EQ(stats.wake_latency.count(), 50u);
  EXPECT_FALSE(stats.virtual_time);
}

TEST(RealtimeScheduler, StopFromAnIoHandlerEndsBeforeTheNextSleep) {
  asio::io_context io;
  hil::SteadyClock clock;
  RecordingSleeper sleeper;
  hil::runtime::AsioScheduler s(io, clock, 1ms, &sleeper);
  int n = 0;
  const auto stats = s.run([&](const CycleTime&) {
    if (++n == 3) asio::post(io, [&] { s.stop(); });
    return CycleControl::proceed;
  });
  EXPECT_EQ(stats.cycles, 3u);
  EXPECT_EQ(sleeper.deadlines.size(), 3u);
}

TEST(LatencyReport, BinsHoldEverySampleOnce) {
  LatencyHistogram h;
  for (auto d : {0us, 5us, 10us, 19us, 20us, 99us, 100us, 999us, 1000us, 4999us, 19999us, 20000us, 50000us}) h.add(d);
  const auto bins = hil::runtime::latency_bins(h);
  std::uint64_t total = 0;
  for (const auto& b : bins) total += b.count;
  EXPECT_EQ(total, h.count());
  EXPECT_EQ(bins.front().from, 0us);
  EXPECT_EQ(bins[0].count, 2u);              // 0, 5
  EXPECT_EQ(bins[1].count, 2u);              // 10, 19
  EXPECT_EQ(bins[2].count, 1u);              // 20
  EXPECT_EQ(bins[3].count, 1u);              // 99
  EXPECT_FALSE(bins.back().to);              // open bin
  EXPECT_EQ(bins.back().count, 2u);          // 20 ms, 50 ms
  EXPECT_EQ(h.count_between(1ms, 5ms), 2u);  // 1000 us, 4999 us
}

TEST(LatencyReport, JsonHasTheStatisticsAndTheBins) {
  LatencyHistogram h;
  h.add(12us);
  h.add(30us);
  const auto j = hil::runtime::latency_json(h);
  EXPECT_NE(j.find("\"samples\":2"), std::string::npos) << j;
  EXPECT_NE(j.find("\"max_us\":30.000"), std::string::npos) << j;
  EXPECT_NE(j.find("{\"from_us\":20000,\"to_us\":null,\"count\":0}"), std::string::npos) << j;
  EXPECT_NE(hil::runtime::format_latency_histogram(h).find("10 us - 20 us"), std::string::npos);
  EXPECT_TRUE(hil::runtime::format_latency_histogram(LatencyHistogram{}).empty());
}

TEST(LatencyReport, RecommendedPeriodLeavesHalfTheCycleAfterTheWorstWakeUp) {
  LatencyHistogram h;
  EXPECT_FALSE(hil::runtime::recommended_min_period(h));
  h.add(40us);
  EXPECT_EQ(hil::runtime::recommended_min_period(h), 100us);  // 2 x 40 = 80 -> 100
  h.add(60us);
  EXPECT_EQ(hil::runtime::recommended_min_period(h), 125us);  // 120 -> 125
  EXPECT_EQ(hil::runtime::recommended_min_period(h, 40us), 200us);
  h.add(1194us);
  EXPECT_EQ(hil::runtime::recommended_min_period(h), 2500us);  // 2388 -> 2.5 ms
  h.add(3300us);
  EXPECT_EQ(hil::runtime::recommended_min_period(h), 10ms);  // 6.6 -> 10
  h.add(600ms);
  EXPECT_FALSE(hil::runtime::recommended_min_period(h));
}

TEST(RealtimeCpus, ParsesKernelCpuLists) {
  using hil::runtime::linux_rt::parse_cpu_list;
  EXPECT_EQ(parse_cpu_list("1"), (std::vector<int>{1}));
  EXPECT_EQ(parse_cpu_list("0,2-4\n"), (std::vector<int>{0, 2, 3, 4}));
  EXPECT_EQ(parse_cpu_list("3,1,1"), (std::vector<int>{1, 3}));
  EXPECT_TRUE(parse_cpu_list("").empty());
  EXPECT_TRUE(parse_cpu_list("\n").empty());
  EXPECT_TRUE(parse_cpu_list("4-2").empty());
  EXPECT_TRUE(parse_cpu_list("a").empty());
  EXPECT_TRUE(parse_cpu_list("1,").empty());
  EXPECT_FALSE(hil::runtime::linux_rt::allowed_cpus().empty());
}

TEST(RealtimeScenario, KeyAsBoolOrMap) {
  const std::string head =
      "machine:\n  axes:\n    - name: x\n      inc_per_unit: 1000\n      limits: {velocity: 10, acceleration: 100}\n"
      "      drive: {transport: sim}\n";
  auto plain = hil::runtime::parse_scenario(head, "rt.yaml");
  ASSERT_TRUE(plain) << plain.error().describe();
  EXPECT_FALSE(plain->realtime);
  auto on = hil::runtime::parse_scenario(head + "realtime: true\n", "rt.yaml");
  ASSERT_TRUE(on) << on.error().describe();
  ASSERT_TRUE(on->realtime);
  EXPECT_TRUE(on->realtime->enabled);
  EXPECT_EQ(on->realtime->priority, 80);
  auto map = hil::runtime::parse_scenario(
      head + "realtime: {priority: 90, cpu: 1, lock_memory: false, dma_latency: false, fallback: true}\n", "rt.yaml");
  ASSERT_TRUE(map) << map.error().describe();
  EXPECT_TRUE(map->realtime->enabled);
  EXPECT_EQ(map->realtime->priority, 90);
  EXPECT_EQ(map->realtime->cpu, 1);
  EXPECT_FALSE(map->realtime->lock_memory);
  EXPECT_FALSE(map->realtime->dma_latency);
  EXPECT_TRUE(map->realtime->fallback);
  auto bad = hil::runtime::parse_scenario(head + "realtime: {priority: 100}\n", "rt.yaml");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().key, "realtime.priority");
  EXPECT_NE(bad.error().message.find("1..99"), std::string::npos);
  auto unknown = hil::runtime::parse_scenario(head + "realtime: {prio: 10}\n", "rt.yaml");
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("unknown key 'prio'"), std::string::npos);
}

TEST(RealtimeSession, AppliesAndRestoresTheSettingsAsRoot) {
  hil::runtime::RealtimeOptions o;
  o.enabled = true;
  o.priority = 10;
  const auto before = hil::runtime::linux_rt::allowed_cpus();
  {
    auto rt = hil::runtime::linux_rt::RealtimeSession::begin(o);
    if (!rt && rt.error().setting == hil::runtime::RealtimeSetting::scheduling)
      GTEST_SKIP() << "SCHED_FIFO refused here: " << rt.error().message;
    if (!rt && rt.error().setting == hil::runtime::RealtimeSetting::dma_latency)
      GTEST_SKIP() << "no /dev/cpu_dma_latency here: " << rt.error().message;
    ASSERT_TRUE(rt) << rt.error().message;
    const auto& r = (*rt)->report();
    EXPECT_EQ(r.priority, 10);
#if defined(__SANITIZE_ADDRESS__)
    EXPECT_FALSE(r.memory_locked) << "ASan's mlockall is a no-op: an instrumented build must not claim a lock";
#else
    EXPECT_TRUE(r.memory_locked);
#endif
    EXPECT_TRUE(r.dma_latency_held);
    EXPECT_TRUE(r.fallbacks.empty());
    EXPECT_EQ(sched_getscheduler(0) & ~SCHED_RESET_ON_FORK, SCHED_FIFO);
    ASSERT_TRUE(r.cpu);
    if (before.size() > 1) {
      EXPECT_EQ(hil::runtime::linux_rt::allowed_cpus(), r.io_cpus);
    }
    (*rt)->enter_cycle_cpu();
    EXPECT_EQ(hil::runtime::linux_rt::allowed_cpus(), std::vector<int>{*r.cpu});
    EXPECT_NE(r.describe().find("SCHED_FIFO 10"), std::string::npos) << r.describe();
  }
  EXPECT_EQ(sched_getscheduler(0), SCHED_OTHER);
  EXPECT_EQ(hil::runtime::linux_rt::allowed_cpus(), before);
}

TEST(RealtimeSession, ACpuOutsideTheAllowedSetIsRefusedOrSkipped) {
  hil::runtime::RealtimeOptions o;
  o.enabled = true;
  o.cpu = 1023;
  o.lock_memory = false;
  o.dma_latency = false;
  o.priority = 10;
  auto rt = hil::runtime::linux_rt::RealtimeSession::begin(o);
  ASSERT_FALSE(rt);
  EXPECT_EQ(rt.error().setting, hil::runtime::RealtimeSetting::cpu_affinity);
  EXPECT_NE(rt.error().message.find("CPU 1023 is not available"), std::string::npos);
  o.fallback = true;
  auto fb = hil::runtime::linux_rt::RealtimeSession::begin(o);
  ASSERT_TRUE(fb);
  ASSERT_FALSE((*fb)->report().fallbacks.empty());
  EXPECT_EQ((*fb)->report().fallbacks.front().setting, hil::runtime::RealtimeSetting::cpu_affinity);
  EXPECT_FALSE((*fb)->report().cpu);
}

TEST(RealtimeSession, UnprivilegedUserIsToldWhatToDo) {
  if (geteuid() != 0) {
    // Already unprivileged: unless this user was granted rtprio, the refusal is the test.
    hil::runtime::RealtimeOptions o;
    o.enabled = true;
    o.lock_memory = o.dma_latency = false;
    auto rt = hil::runtime::linux_rt::RealtimeSession::begin(o);
    if (rt) GTEST_SKIP() << "this user may use SCHED_FIFO";
    EXPECT_NE(rt.error().message.find("limits.conf"), std::string::npos) << rt.error().message;
    return;
  }
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // nobody: no capabilities, RLIMIT_RTPRIO 0.
    if (setgid(65534) != 0 || setuid(65534) != 0) _exit(10);
    hil::runtime::RealtimeOptions o;
    o.enabled = true;
    o.dma_latency = false;
    o.lock_memory = false;
    auto rt = hil::runtime::linux_rt::RealtimeSession::begin(o);
    if (rt) _exit(11);
    if (rt.error().setting != hil::runtime::RealtimeSetting::scheduling || rt.error().error != EPERM) _exit(12);
    const auto& m = rt.error().message;
    if (m.find("CAP_SYS_NICE") == std::string::npos || m.find("setcap") == std::string::npos ||
        m.find("limits.conf") == std::string::npos)
      _exit(13);
    o.dma_latency = true;
    auto dma = hil::runtime::linux_rt::RealtimeSession::begin(o);
    if (dma) _exit(14);
    if (dma.error().setting != hil::runtime::RealtimeSetting::dma_latency) _exit(15);
    o.fallback = true;
    auto fb = hil::runtime::linux_rt::RealtimeSession::begin(o);
    if (!fb || (*fb)->report().priority != 0 || (*fb)->report().fallbacks.size() != 2) _exit(16);
    _exit(0);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "child failed at check " << WEXITSTATUS(status);
}
