// SPDX-License-Identifier: MIT
// Motion core speed goals (run: bench_motion --benchmark_format=json):
//   plan one jerk-limited rest-to-rest move    < 150 ns median (Ruckig: ~110 ns)
//   one Axis::update with a trivial drive      < 50 ns (trajectory sample + supervision)
//   1 kHz loop, 64 axes on SimDrive            < 5 % of one core (counter cpu_percent)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <random>
#include <vector>

#include "hil/mocks/sim_drive.hpp"
#include "hil/motion/axis.hpp"
#include "hil/motion/plan.hpp"

namespace {

using namespace hil::motion;
using std::chrono::milliseconds;

struct Move {
  double from, to;
  Limits limits;
};

std::vector<Move> random_moves(std::size_t n) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> pos(-1000.0, 1000.0), lv(10.0, 500.0), la(100.0, 5000.0), lj(1e3, 1e5);
  std::vector<Move> out(n);
  for (auto& m : out) m = Move{pos(rng), pos(rng), Limits{lv(rng), la(rng), lj(rng)}};
  return out;
}

void BM_PlanRestToRest(benchmark::State& state) {
  const auto moves = random_moves(1024);
  Profile p;
  std::size_t i = 0;
  for (auto _ : state) {
    const Move& m = moves[i++ & 1023];
    plan_rest_to_rest(m.from, m.to, m.limits, p);
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_PlanRestToRest);

void BM_PlanFromMotion(benchmark::State& state) {
  const auto moves = random_moves(1024);
  std::vector<State> states(1024);
  Profile p;
  for (std::size_t k = 0; k < 1024; ++k) {
    plan_rest_to_rest(moves[k].from, moves[k].to, moves[k].limits, p);
    states[k] = p.sample(0.37 * p.duration());
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 1023;
    plan_position(states[k], moves[(k + 1) & 1023].to, moves[k].limits, p);
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_PlanFromMotion);

// The re-planning cases of issue 18 and docs/performance anchors (the same as the Ruckig
// comparison): start and target in [-10, 10], V in [0.5, 5], A in [0.5, 10], J in [1, 100];
// "from motion" = start velocity uniform in +/- V/2, acceleration 0, target at rest.
struct ReplanCase {
  State from;
  double target;
  Limits limits;
};

std::vector<ReplanCase> replan_cases(std::size_t n, bool moving) {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> pos(-10.0, 10.0), lv(0.5, 5.0), la(0.5, 10.0), lj(1.0, 100.0), u(-0.5, 0.5);
  std::vector<ReplanCase> out(n);
  for (auto& c : out) {
    c.limits = {lv(rng), la(rng), lj(rng)};
    c.from = {pos(rng), moving ? u(rng) * c.limits.velocity : 0.0, 0.0, 0.0};
    c.target = pos(rng);
  }
  return out;
}

constexpr std::size_t replan_count = 100'000;

void BM_ReplanRestToRest(benchmark::State& state) {
  const auto cases = replan_cases(replan_count, false);
  Profile p;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& c = cases[i];
    i = i + 1 == replan_count ? 0 : i + 1;
    plan_rest_to_rest(c.from.p, c.target, c.limits, p);
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_ReplanRestToRest);

void BM_ReplanFromMotion(benchmark::State& state) {
  const auto cases = replan_cases(replan_count, true);
  Profile p;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& c = cases[i];
    i = i + 1 == replan_count ? 0 : i + 1;
    plan_position(c.from, c.target, c.limits, p);
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_ReplanFromMotion);

// A target moving at a velocity uniform in +/- V/2 (synchronising to a master), same cases.
void BM_PlanMovingTarget(benchmark::State& state) {
  const auto cases = replan_cases(replan_count, true);
  std::vector<double> vt(replan_count);
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (std::size_t k = 0; k < replan_count; ++k) vt[k] = u(rng) * cases[k].limits.velocity;
  Profile p;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& c = cases[i];
    plan_moving_target(c.from, c.target, vt[i], c.limits, p);
    i = i + 1 == replan_count ? 0 : i + 1;
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_PlanMovingTarget);

// Per-call distribution: every call timed with steady_clock (about 20 ns of timer overhead
// included, as in the anchors' per-call columns); counters mean_ns, p50_ns, p99_ns, max_ns.
void BM_ReplanFromMotionPerCall(benchmark::State& state) {
  const auto cases = replan_cases(replan_count, true);
  std::vector<double> ns(replan_count);
  Profile p;
  for (auto _ : state) {
    for (std::size_t i = 0; i < replan_count; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      plan_position(cases[i].from, cases[i].target, cases[i].limits, p);
      benchmark::DoNotOptimize(p);
      const auto t1 = std::chrono::steady_clock::now();
      ns[i] = std::chrono::duration<double, std::nano>(t1 - t0).count();
    }
  }
  double sum = 0.0;
  for (double v : ns) sum += v;
  std::sort(ns.begin(), ns.end());
  state.counters["mean_ns"] = sum / static_cast<double>(replan_count);
  state.counters["p50_ns"] = ns[replan_count / 2];
  state.counters["p99_ns"] = ns[replan_count * 99 / 100];
  state.counters["max_ns"] = ns.back();
}
BENCHMARK(BM_ReplanFromMotionPerCall)->Iterations(3)->Unit(benchmark::kMillisecond);

// The drive does nothing but report the command back (ideal, instant).
class EchoDrive final : public hil::Drive {
 public:
  std::string_view name() const noexcept override { return "echo"; }
  hil::DriveCapabilities capabilities() const noexcept override { return {}; }
  void read(const hil::CycleTime&) override {}
  void write(const hil::CycleTime&, const hil::DriveCommand& c) override {
    fb_.position_inc = c.position_inc;
    fb_.velocity_inc_per_s = c.velocity_inc_per_s;
  }
  const hil::DriveFeedback& feedback() const noexcept override { return fb_; }
  bool request(hil::DriveRequest r) override {
    if (r == hil::DriveRequest::enable) fb_.state = hil::DriveState::operation_enabled;
    return true;
  }

 private:
  hil::DriveFeedback fb_;
};

AxisConfig bench_config() {
  AxisConfig c;
  c.name = "bench";
  c.inc_per_unit = {4096, 5};
  c.limits = {200.0, 2000.0, 40000.0};
  c.quick_stop_deceleration = 10000.0;
  c.jog_velocity = 50.0;
  c.following_error.dynamic = true;
  c.following_error.kv_per_s = 50.0;
  c.following_error.min_window = 0.2;
  c.following_error.max_window = 8.0;
  c.standstill_window = 0.1;
  c.in_position_window = 0.01;
  c.in_position_timeout = milliseconds(300);
  return c;
}

void BM_AxisUpdate(benchmark::State& state) {
  Axis axis(bench_config(), std::make_unique<EchoDrive>());
  hil::TimePoint now{};
  const hil::Duration period = milliseconds(1);
  axis.update({now, period});
  axis.enable();
  for (int i = 0; i < 3; ++i) axis.update({now += period, period});
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> pos(-1000.0, 1000.0);
  for (auto _ : state) {
    if (!axis.status().busy) axis.move_absolute(pos(rng));  // keeps it moving through all phases
    benchmark::DoNotOptimize(axis.update({now += period, period}));
  }
}
BENCHMARK(BM_AxisUpdate);

void BM_Loop64AxesSimDrive1s(benchmark::State& state) {
  std::vector<std::unique_ptr<Axis>> axes;
  for (int k = 0; k < 64; ++k) {
    hil::mocks::SimDriveConfig d;
    d.plant.kv_per_s = 50.0;
    auto c = bench_config();
    c.name = "a" + std::to_string(k);
    axes.push_back(std::make_unique<Axis>(c, std::make_unique<hil::mocks::SimDrive>(d)));
  }
  hil::TimePoint now{};
  const hil::Duration period = milliseconds(1);
  for (auto& a : axes) {
    a->update({now, period});
    a->enable();
  }
  for (int i = 0; i < 50; ++i) {
    now += period;
    for (auto& a : axes) a->update({now, period});
  }
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> pos(-300.0, 300.0);
  for (auto _ : state) {
    for (int cycle = 0; cycle < 1000; ++cycle) {  // 1 s of simulated time at 1 kHz
      now += period;
      for (auto& a : axes) {
        if (!a->status().busy && a->status().in_position) a->move_absolute(pos(rng));
        benchmark::DoNotOptimize(a->update({now, period}));
      }
    }
  }
  // CPU time per simulated second, as % of one core: 100 * (seconds per iteration) / 1 s.
  state.counters["cpu_percent"] =
      benchmark::Counter(0.01, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_Loop64AxesSimDrive1s)->Unit(benchmark::kMillisecond);

}  // namespace
