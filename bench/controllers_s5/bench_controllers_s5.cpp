// SPDX-License-Identifier: MIT
// bench_controllers_s5: IP247 program interpretation per block (syntax check and interpreter),
// one module cycle of an axis running a program, and 64 IP247 axes running programs at the
// module cycle (1 ms) on virtual time: CPU per simulated second.
// Run: bench_controllers_s5 --benchmark_format=json
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "hil/controllers/s5/ip247_axis.hpp"
#include "hil/controllers/s5/ip247_interpreter.hpp"

using namespace hil::controllers::s5;

namespace {

const char* const program_text =
    "%1 BENCH\nN10 G90\nN20 G24 F0\nN30 X100 F3000 M10\nN40 G54\nN50 X0 F3000 M11\nN60 G53\nN70 G04 F1\nN80 G20\n"
    "N90 M02\n";

Ip247MachineData bench_md() {
  Ip247MachineData md;
  md.limits_normally_closed = false;
  md.sw_start = -1'000'000;
  md.sw_end = 1'000'000;
  return md;
}

void BM_ParseBlock(benchmark::State& state) {
  std::string text = "%1\n";
  for (int i = 0; i < 40; ++i) text += "N" + std::to_string(i) + " G10 X-12345.678 F2500 M10\n";
  text += "N99 M02\n";
  for (auto _ : state) {
    auto p = parse_ip247_program(text);
    benchmark::DoNotOptimize(p);
  }
  state.SetItemsProcessed(state.iterations() * 41);  // blocks
}
BENCHMARK(BM_ParseBlock);

void BM_InterpretBlock(benchmark::State& state) {
  auto prog = *parse_ip247_program(program_text);
  const Ip247MachineData md = bench_md();
  Ip247Interpreter in([&](int n) { return n == 1 ? &prog : nullptr; });
  Ip247Offsets off;
  (void)in.start(1, md, 0, false);
  std::int64_t blocks = 0;
  for (auto _ : state) {
    auto a = in.next(off);
    benchmark::DoNotOptimize(a);
    ++blocks;
  }
  // Each next() interprets the switching blocks up to one motion/dwell: 7 blocks per 3 actions.
  state.counters["actions"] = static_cast<double>(blocks);
  state.SetItemsProcessed(blocks);
}
BENCHMARK(BM_InterpretBlock);

struct Module {
  Ip247ProgramStore store;
  std::vector<std::unique_ptr<Ip247Axis>> axes;
  explicit Module(int n) {
    (void)store.write(1, program_text);
    const Ip247MachineData md = bench_md();
    for (int i = 0; i < n; ++i) {
      axes.push_back(std::make_unique<Ip247Axis>(store, 1));
      (void)axes.back()->load_machine_data(md, 0);
      axes.back()->command({.ba = 5, .command = Ip247Command::start, .byte_param = 1});
      axes.back()->command({.ba = 8, .command = Ip247Command::start, .byte_param = 1});
    }
  }
};

void BM_AxisCycle(benchmark::State& state) {
  Module m(1);
  std::vector<hil::gpio::Edge> edges;
  edges.reserve(64);
  std::int64_t now = 0;
  for (auto _ : state) {
    edges.clear();
    m.axes[0]->step(now, 1'000'000, {}, &edges);
    now += 1'000'000;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_AxisCycle);

/// 64 axes, each running the endless program, 1000 cycles of 1 ms = 1 s of module time.
void BM_64AxesSimulatedSecond(benchmark::State& state) {
  Module m(64);
  std::vector<hil::gpio::Edge> edges;
  edges.reserve(4096);
  std::int64_t now = 0;
  for (auto _ : state) {
    for (int c = 0; c < 1000; ++c) {
      for (auto& a : m.axes) {
        edges.clear();
        a->step(now, 1'000'000, {}, &edges);
      }
      now += 1'000'000;
    }
  }
  state.counters["sim_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_64AxesSimulatedSecond)->Unit(benchmark::kMillisecond);

}  // namespace
