// SPDX-License-Identifier: MIT
// bench_controllers_s5: the IP247 (docs/ip247.md, "Benchmarks").
//   * program interpretation: the syntax check per block; the interpreter per block (items =
//     blocks interpreted, counted by the interpreter itself) and per action (one next() call);
//   * one module cycle of one axis running a program;
//   * 64 IP247 axes (22 modules of Ip247Module, 3 axes each, the last with 1) running programs at
//     the module cycle (1 ms) on virtual time: one iteration = 1 simulated second, so the time per
//     iteration is the CPU per simulated second;
//   * the same 64 axes on the controller runtime: 22 `ip247` controllers (module cycle 2 ms), each
//     axis following its module's pulses on a motion::Axis with a simulated drive (run period 1 ms),
//     the programs started through the interface DB as a PLC does.
// Run: bench_controllers_s5 --benchmark_format=json
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include <unistd.h>

#include "hil/controllers/s5/ip247_controller.hpp"
#include "hil/controllers/s5/ip247_interpreter.hpp"
#include "hil/controllers/s5/ip247_module.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "hil/serial/s5/db_listing.hpp"

using namespace hil::controllers::s5;

namespace {

constexpr int bench_axes = 64;
/// An endless loop of two moves, two zero-offset switchings and a dwell (6 blocks, 3 actions a pass).
const char* const program_text =
    "%1 BENCH\nN10 G90\nN20 G24 F0\nN30 X100 F3000 M10\nN40 G54\nN50 X0 F3000 M11\nN60 G53\nN70 G04 F1\nN80 G20\n"
    "N90 M02\n";

Ip247MachineData bench_md(int axis = 1) {
  Ip247MachineData md;  // the manual's example set: 10 um/pulse, fmax 5 kHz (3000 mm/min)
  md.axis = axis;
  md.db = static_cast<std::uint8_t>(19 + axis);
  md.limits_normally_closed = false;
  md.sw_start = -1'000'000;
  md.sw_end = 1'000'000;
  return md;
}

void BM_Ip247ParseBlock(benchmark::State& state) {
  // 30 blocks of 28..29 chars: within the 1023 chars of a program (a longer text stops at error 1).
  std::string text = "%1\n";
  for (int i = 0; i < 30; ++i) text += "N" + std::to_string(i) + " G10 X-12345.678 F2500 M10\n";
  text += "N99 M02\n";
  if (auto p = parse_ip247_program(text); !p || p->blocks.size() != 31) {
    state.SkipWithError("the benchmark program does not pass the syntax check");
    return;
  }
  for (auto _ : state) {
    auto p = parse_ip247_program(text);
    benchmark::DoNotOptimize(p);
  }
  state.SetItemsProcessed(state.iterations() * 31);  // blocks
  state.counters["chars"] = static_cast<double>(text.size());
}
BENCHMARK(BM_Ip247ParseBlock);

/// The interpreter alone: each next() interprets the blocks up to the next motion or dwell.
void BM_Ip247InterpretBlock(benchmark::State& state) {
  auto prog = *parse_ip247_program(program_text);
  const Ip247MachineData md = bench_md();
  Ip247Interpreter in([&](int n) { return n == 1 ? &prog : nullptr; });
  Ip247Offsets off;
  (void)in.start(1, md, 0, false);
  const std::uint64_t blocks0 = in.blocks_interpreted();
  std::int64_t actions = 0;
  for (auto _ : state) {
    auto a = in.next(off);
    benchmark::DoNotOptimize(a);
    ++actions;
  }
  const auto blocks = static_cast<std::int64_t>(in.blocks_interpreted() - blocks0);
  state.SetItemsProcessed(blocks);
  state.counters["blocks_per_action"] =
      static_cast<double>(blocks) / static_cast<double>(std::max<std::int64_t>(1, actions));
  state.counters["ns_per_block"] =
      benchmark::Counter(static_cast<double>(blocks), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_Ip247InterpretBlock);

/// Modules of three axes, `axes` axes in all, every axis referenced and running program 1.
struct Modules {
  std::vector<std::unique_ptr<Ip247Module>> modules;
  std::vector<Ip247Axis*> axes;
  explicit Modules(int n) {
    const auto image = make_ip247_vp_db(Ip247VpImage{1, program_text, 0, 0});
    for (int i = 0; i < n; ++i) {
      if (i % ip247_axes == 0) {
        modules.push_back(std::make_unique<Ip247Module>());
        (void)modules.back()->write_vp(1, *image);
      }
      Ip247Module& m = *modules.back();
      const int k = i % ip247_axes + 1;
      const auto md = bench_md(k);
      (void)m.write_md(k, md.db, make_ip247_md_db(md));
      m.command(k, {.ba = 5, .command = Ip247Command::start, .byte_param = 1});
      m.command(k, {.ba = 8, .command = Ip247Command::start, .byte_param = 1});
      axes.push_back(&m.axis(k));
    }
  }
  [[nodiscard]] std::uint64_t blocks() const {
    std::uint64_t b = 0;
    for (const auto* a : axes) b += a->interpreter().blocks_interpreted();
    return b;
  }
};

/// One module cycle (1 ms) of one axis running the program.
void BM_Ip247AxisCycle(benchmark::State& state) {
  Modules m(1);
  std::vector<hil::gpio::Edge> edges;
  edges.reserve(64);
  std::int64_t now = 0;
  const std::uint64_t b0 = m.blocks();
  for (auto _ : state) {
    edges.clear();
    m.axes[0]->step(now, 1'000'000, {}, &edges);
    now += 1'000'000;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["blocks_per_s_sim"] =
      static_cast<double>(m.blocks() - b0) / (static_cast<double>(state.iterations()) * 1e-3);
}
BENCHMARK(BM_Ip247AxisCycle);

/// 64 axes running the endless program; one iteration = 1000 module cycles of 1 ms = 1 s of module
/// time, so the time per iteration is the CPU per simulated second. The step/dir edges of every
/// axis are generated (as for a GPIO output) and counted.
void BM_Ip247_64Axes_SimulatedSecond(benchmark::State& state) {
  Modules m(bench_axes);
  std::vector<hil::gpio::Edge> edges;
  edges.reserve(4096);
  std::int64_t now = 0;
  std::uint64_t edge_count = 0;
  const std::uint64_t b0 = m.blocks();
  for (auto _ : state) {
    for (int c = 0; c < 1000; ++c) {
      for (auto* a : m.axes) {
        edges.clear();
        a->step(now, 1'000'000, {}, &edges);
        edge_count += edges.size();
      }
      now += 1'000'000;
    }
  }
  const double sim_s = static_cast<double>(state.iterations());
  state.counters["axes"] = bench_axes;
  state.counters["edges_per_sim_s"] = static_cast<double>(edge_count) / sim_s;
  state.counters["blocks_per_sim_s"] = static_cast<double>(m.blocks() - b0) / sim_s;
  int running = 0;
  for (const auto* a : m.axes) running += a->running() ? 1 : 0;
  state.counters["running_axes"] = running;
}
BENCHMARK(BM_Ip247_64Axes_SimulatedSecond)->Unit(benchmark::kMillisecond);

/// The 64 axes on the controller runtime: 22 `ip247` controllers and 64 motion axes on simulated
/// drives, run period 1 ms, module cycle 2 ms; one iteration = 1 simulated second.
void BM_Ip247Controller_64Axes_SimulatedSecond(benchmark::State& state) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("hil_bench_ip247_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::vector<hil::serial::s5::DbImage> dbs;
  for (int k = 1; k <= ip247_axes; ++k) {
    const auto md = bench_md(k);
    dbs.push_back({md.db, make_ip247_md_db(md)});
  }
  std::ofstream(dir / "md3.s5db") << hil::serial::s5::make_db_listing(dbs, "bench: MD of axes 1..3");
  dbs.resize(1);
  std::ofstream(dir / "md1.s5db") << hil::serial::s5::make_db_listing(dbs, "bench: MD of axis 1");
  std::ofstream(dir / "prog1.txt") << program_text;

  std::vector<std::unique_ptr<hil::controllers::Controller>> controllers;
  std::vector<std::unique_ptr<hil::motion::Axis>> axes;
  std::vector<int> per_controller;
  for (int left = bench_axes; left > 0; left -= ip247_axes) {
    hil::controllers::ControllerSpec spec;
    spec.device = "ip247";
    spec.parameters = dir / (left >= ip247_axes ? "md3.s5db" : "md1.s5db");
    spec.programs = {dir / "prog1.txt"};
    spec.options = {{"interface_db", "10"}};
    auto c = Ip247Controller::create(spec);
    if (!c) {
      state.SkipWithError(c.error().describe().c_str());
      return;
    }
    std::vector<hil::motion::Axis*> raw;
    for (const auto& s : (*c)->axis_specs()) {
      axes.push_back(std::make_unique<hil::motion::Axis>(
          s.config, std::make_unique<hil::mocks::SimDrive>(hil::mocks::SimDriveConfig{})));
      raw.push_back(axes.back().get());
    }
    if (auto b = (*c)->bind_axes(raw); !b) {
      state.SkipWithError(b.error().c_str());
      return;
    }
    per_controller.push_back(static_cast<int>(raw.size()));
    controllers.push_back(std::move(*c));
  }
  const auto period = std::chrono::milliseconds(1);
  hil::TimePoint now{};
  std::int64_t cycle = 0;
  const auto run_cycle = [&] {
    now += period;
    const hil::CycleTime t{now, period};
    for (auto& a : axes) (void)a->update(t);
    if (cycle++ % 2 == 0)
      for (auto& c : controllers) (void)c->step(hil::CycleTime{now, std::chrono::milliseconds(2)});
  };
  // The PLC: BA5 set reference point, then BA8 program 1, on every axis (DW 20(k-1)).
  const auto command = [&](std::uint16_t ba_word) {
    for (std::size_t i = 0; i < controllers.size(); ++i)
      for (int k = 0; k < per_controller[i]; ++k) {
        (void)controllers[i]->write_data_word(10, 20 * k, ba_word);
        (void)controllers[i]->write_data_word(10, 20 * k + 4, 1);
      }
    for (int n = 0; n < 200; ++n) run_cycle();
  };
  command(0x0501);
  command(0x0801);
  int running = 0;
  for (std::size_t i = 0; i < controllers.size(); ++i)
    for (int k = 0; k < per_controller[i]; ++k)
      running += (controllers[i]->read_data_word(10, 20 * k + 12).value_or(0x8000) & 0x8000) == 0 ? 1 : 0;
  if (running != bench_axes) {
    state.SkipWithError("not every axis runs its program");
    return;
  }
  for (auto _ : state) {
    for (int c = 0; c < 1000; ++c) run_cycle();
  }
  int faulted = 0;
  for (const auto& a : axes) faulted += a->status().state == hil::motion::AxisState::error ? 1 : 0;
  state.counters["axes"] = bench_axes;
  state.counters["faulted_axes"] = faulted;
  fs::remove_all(dir);
}
BENCHMARK(BM_Ip247Controller_64Axes_SimulatedSecond)->Unit(benchmark::kMillisecond);

}  // namespace
