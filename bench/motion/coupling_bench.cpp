// SPDX-License-Identifier: MIT
// Coupling speed goals (issue 16; run: bench_coupling --benchmark_format=json):
//   one coupled-slave cycle update (gear, limits, monitor)   < 60 ns
//   one cam lookup (cubic, 64 points, monotone master)         < 30 ns
//   1000 cam-coupled axes at 1 kHz: CPU per simulated second   (counter cpu_percent_of_one_core)
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <vector>

#include "hil/motion/cam.hpp"
#include "hil/motion/coupling.hpp"
#include "hil/motion/master.hpp"

namespace {

using namespace hil::motion;
using std::chrono::milliseconds;

CamTable feed_cam(int points) {
  CamTableSpec s;
  s.interpolation = CamInterpolation::cubic_periodic;
  s.periodic = true;
  for (int i = 0; i < points; ++i) {
    const double x = 20000.0 * i / (points - 1);
    s.points.push_back(
        {x, std::round(8000.0 * x / 20000.0 + (i == 0 || i == points - 1 ? 0 : 300.0 * std::sin(x / 3000.0)))});
  }
  s.points.back().y = 8000;
  return *CamTable::make(s);
}

void BM_CoupledSlaveCycle(benchmark::State& state) {
  Coupling c("slave", SlaveLimits{1e9, 1e12, 1, 1000});
  c.use(Coupling::Law::gear);
  (void)c.gear().engage({7919, 10007});
  c.start(0, 0);
  std::int64_t m = 0;
  for (auto _ : state) {
    m += 1237;
    const auto& out = c.update(m, milliseconds(1), c.output().position_inc);
    benchmark::DoNotOptimize(out.position_inc);
  }
}
BENCHMARK(BM_CoupledSlaveCycle);

void BM_CamLookup(benchmark::State& state) {
  const CamTable t = feed_cam(64);
  std::size_t hint = 0;
  double x = 0.0;
  for (auto _ : state) {
    x += 13.7;
    if (x >= 20000.0) x -= 20000.0;
    benchmark::DoNotOptimize(t.value(x, hint));
  }
}
BENCHMARK(BM_CamLookup);

void BM_CamLookupNonEquidistant(benchmark::State& state) {
  CamTableSpec s;
  s.interpolation = CamInterpolation::cubic_natural;
  double x = 0;
  for (int i = 0; i < 64; ++i) {
    s.points.push_back({x, i * 10.0});
    x += 100.0 + (i % 5) * 37.0;
  }
  const CamTable t = *CamTable::make(s);
  std::size_t hint = 0;
  double q = 0.0;
  for (auto _ : state) {
    q += 11.3;
    if (q >= t.length()) q = 0.0;
    benchmark::DoNotOptimize(t.value(q, hint));
  }
}
BENCHMARK(BM_CamLookupNonEquidistant);

// 1000 slaves, each cam-coupled to its own virtual master, stepped at 1 kHz: one iteration is
// one simulated second (1000 cycles x 1000 couplings).
void BM_ThousandCamAxesOneSecond(benchmark::State& state) {
  const CamTable t = feed_cam(64);
  std::vector<Coupling> couplings;
  std::vector<VirtualMaster> masters(1000);
  couplings.reserve(1000);
  for (int i = 0; i < 1000; ++i) {
    couplings.emplace_back("s", SlaveLimits{1e9, 1e12, 1, 0});
    couplings.back().use(Coupling::Law::cam);
    couplings.back().cam().set_table(&t);
    couplings.back().start(0, 0);
    masters[static_cast<std::size_t>(i)].set_velocity(20000.0 + i, 1e12);
  }
  for (auto _ : state) {
    for (int k = 0; k < 1000; ++k)
      for (std::size_t i = 0; i < 1000; ++i)
        benchmark::DoNotOptimize(couplings[i].update(masters[i].update(milliseconds(1)), milliseconds(1)).position_inc);
  }
  // One iteration = one simulated second: CPU time per iteration / 1 s = share of one core.
  state.counters["cpu_percent_of_one_core"] =
      benchmark::Counter(0.01, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ThousandCamAxesOneSecond)->Unit(benchmark::kMillisecond);

}  // namespace
