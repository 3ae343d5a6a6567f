// SPDX-License-Identifier: MIT
// bench_stepdir: planned steps per second (target > 10 M steps/s of schedule on one core),
// verifier throughput, and the real-line writer's timing error (against mock lines on the
// steady clock here; on gpio-sim when HIL_GPIOCHIP is set, e.g. in tests/vm/run-in-kernel.sh).
// Run: bench_stepdir --benchmark_format=json
#include <cstdlib>
#include <memory>

#include <benchmark/benchmark.h>

#include "hil/gpio/io/edge_writer.hpp"
#include "hil/gpio/linux/gpiod_lines.hpp"
#include "hil/mocks/gpio/mock_lines.hpp"
#include "hil/stepdir/step_planner.hpp"
#include "hil/stepdir/verifier.hpp"

using namespace hil::stepdir;

namespace {

std::pair<StepTiming, std::shared_ptr<const Ip247Ramp>> setup() {
  auto t = make_ip247_timing(2, PulseRounding::up, 100'000, Polarity::positive_edge, 1'000, 1'000);
  auto r = Ip247Ramp::make({100'000, 2'000, 2'000'000}, t->min_period_ns());
  return {*t, std::make_shared<const Ip247Ramp>(std::move(*r))};
}

void BM_PlanIp247Move(benchmark::State& state) {
  auto [t, r] = setup();
  const std::int64_t n = state.range(0);
  std::vector<hil::gpio::Edge> edges;
  edges.reserve(static_cast<std::size_t>(2 * n + 8));
  std::int64_t target = 0;
  for (auto _ : state) {
    StepPlanner p(t, r);
    edges.clear();
    target = target == 0 ? n : 0;
    p.set_position(target == n ? 0 : n, 0);
    p.move_to(target, 100'000);
    p.plan(0, plan_forever_ns, edges);
    benchmark::DoNotOptimize(edges.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * n), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PlanIp247Move)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

void BM_PlanFollowCycles(benchmark::State& state) {
  auto [t, r] = setup();
  StepPlanner p(t, r);
  p.set_mode(PlannerMode::follow);
  std::vector<hil::gpio::Edge> edges;
  edges.reserve(4096);
  std::int64_t now = 0, cmd = 0;
  const std::int64_t per_cycle = state.range(0);
  for (auto _ : state) {
    edges.clear();
    cmd += per_cycle;
    p.follow(cmd);
    p.plan(now, now + 1'000'000, edges);
    now += 1'000'000;
    benchmark::DoNotOptimize(edges.data());
  }
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * per_cycle), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PlanFollowCycles)->Arg(10)->Arg(100);

void BM_Verify(benchmark::State& state) {
  auto [t, r] = setup();
  StepPlanner p(t, r);
  std::vector<hil::gpio::Edge> edges;
  p.move_to(1'000'000, 100'000);
  p.plan(0, plan_forever_ns, edges);
  for (auto _ : state) {
    StepVerifier v(t);
    v.feed(edges);
    benchmark::DoNotOptimize(v.stats());
  }
  state.counters["edges_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * edges.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Verify)->Unit(benchmark::kMillisecond);

/// Writer timing against `lines`: 2000 edges (1000 pulses of 20 us at `hz`) per iteration.
void run_writer(benchmark::State& state, hil::gpio::LineBank& lines, const hil::SteadyClock& clock) {
  hil::gpio::EdgeWriter w(lines, clock);
  const double hz = static_cast<double>(state.range(0));
  const auto period = static_cast<std::int64_t>(1e9 / hz);
  std::vector<hil::gpio::Edge> edges;
  for (auto _ : state) {
    edges.clear();
    const std::int64_t t0 = clock.now().time_since_epoch().count() + 500'000;
    for (int i = 0; i < 1000; ++i) {
      edges.push_back({t0 + i * period, 0, true});
      edges.push_back({t0 + i * period + 20'000, 0, false});
    }
    w.write(edges);
  }
  const auto& s = w.stats();
  state.counters["edges"] = static_cast<double>(s.edges);
  state.counters["late"] = static_cast<double>(s.late);
  state.counters["err_mean_us"] = s.mean_error_ns() / 1000.0;
  state.counters["err_p99_us_le"] = static_cast<double>(s.quantile_bound_ns(0.99)) / 1000.0;
  state.counters["err_max_us"] = static_cast<double>(s.max_error_ns) / 1000.0;
  state.counters["max_slip_us"] = static_cast<double>(s.max_slip_ns) / 1000.0;
}

void BM_WriterMockLinesRealClock(benchmark::State& state) {
  hil::SteadyClock clock;
  hil::gpio::LineSpec step{"step", 0U, "", hil::gpio::LineDirection::output, false, hil::gpio::Bias::as_is, false};
  hil::gpio::mock::MockLines lines({step}, clock);
  lines.set_record_limit(0);
  run_writer(state, lines, clock);
}
BENCHMARK(BM_WriterMockLinesRealClock)->Arg(1'000)->Arg(10'000)->Iterations(5)->Unit(benchmark::kMillisecond);

void BM_WriterGpioSim(benchmark::State& state) {
  const char* chip = std::getenv("HIL_GPIOCHIP");
  if (!chip || !*chip) {
    state.SkipWithError("HIL_GPIOCHIP unset: run under tests/vm/run-in-kernel.sh for the gpio-sim figure");
    return;
  }
  hil::gpio::LineSpec step{"step", 0U, "", hil::gpio::LineDirection::output, false, hil::gpio::Bias::as_is, false};
  auto lines = hil::gpio::linux_gpiod::GpiodLines::open(chip, {step});
  if (!lines) {
    state.SkipWithError(lines.error().message.c_str());
    return;
  }
  hil::SteadyClock clock;
  run_writer(state, **lines, clock);
}
BENCHMARK(BM_WriterGpioSim)->Arg(1'000)->Arg(10'000)->Iterations(5)->Unit(benchmark::kMillisecond);

}  // namespace
