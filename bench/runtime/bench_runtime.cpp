// SPDX-License-Identifier: MIT
// Runtime benchmarks: the full cycle (scheduler + factories + axes + monitor + program) of 64
// simulated axes at 1 kHz for 1 s of virtual time. Reported: CPU time per simulated second.
//   bench_runtime --benchmark_format=json
#include <benchmark/benchmark.h>

#include <fmt/format.h>

#include "hil/mocks/sim_transport.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"

namespace {

std::string scenario_text(int axes, bool moving) {
  std::string s = "duration: 1s\nmachine:\n  axes:\n";
  for (int i = 0; i < axes; ++i)
    s += fmt::format(
        "    - {{name: a{}, inc_per_unit: 1000, limits: {{velocity: 100, acceleration: 1000, jerk: 10000}}, "
        "supervision: {{following_error: 1.0}}, drive: {{transport: sim, kv: 80, feedforward: 1.0}}}}\n",
        i);
  s += "program:\n  - enable: all\n";
  if (moving) {
    s += "  - parallel:\n";
    for (int i = 0; i < axes; ++i) s += fmt::format("      - move_absolute: {{axis: a{}, position: {}}}\n", i, 20 + i);
  }
  return s;
}

void run_axes(benchmark::State& state, bool moving) {
  const int axes = static_cast<int>(state.range(0));
  auto scenario = hil::runtime::parse_scenario(scenario_text(axes, moving), "bench.yaml");
  if (!scenario) {
    state.SkipWithError(scenario.error().describe().c_str());
    return;
  }
  hil::TransportRegistry registry;
  registry.add("sim", [] { return hil::mocks::make_sim_transport(); });
  std::uint64_t cycles = 0;
  for (auto _ : state) {
    auto r = hil::runtime::run_scenario(*scenario, registry, hil::runtime::RunOptions{});
    if (!r || !r->ok) {
      state.SkipWithError("run failed");
      return;
    }
    cycles += r->scheduler.cycles;
  }
  state.counters["axes"] = axes;
  state.counters["cycles_per_s"] = benchmark::Counter(static_cast<double>(cycles), benchmark::Counter::kIsRate);
  state.counters["axis_updates_per_s"] =
      benchmark::Counter(static_cast<double>(cycles) * axes, benchmark::Counter::kIsRate);
  state.SetLabel("one iteration = 1 s of virtual time at 1 kHz (time per iteration = CPU per simulated second)");
}

void BM_RunVirtualSecondMoving(benchmark::State& state) {
  run_axes(state, true);
}
void BM_RunVirtualSecondHolding(benchmark::State& state) {
  run_axes(state, false);
}

}  // namespace

BENCHMARK(BM_RunVirtualSecondMoving)->Arg(1)->Arg(8)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RunVirtualSecondHolding)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
