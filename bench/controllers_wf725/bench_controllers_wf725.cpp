// SPDX-License-Identifier: MIT
// bench_controllers_wf725: WF 725/726 program interpretation per block (the text parser that
// checks a program on input), and per controller cycle of an axis running a program in automatic
// cycle on the simulated drive (the controller's step alone, and the module cycle with its axis
// updates at 1 ms), with the blocks executed per simulated second; a WF 726 with two axes running a
// combined program (blocks of the slave, G17 pairs by linear interpolation).
// Run: bench_controllers_wf725 --benchmark_format=json
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/controllers/s5/wf726_module.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace s5 = hil::controllers::s5;
namespace db = s5::wf_db;
namespace fs = std::filesystem;
using std::chrono::milliseconds;

namespace {

// examples/controllers/wf725-axis-a.txt, with timed M output (MD 8 = 10 ms): no PLC handshake.
const char* const md_text =
    "MD 49 = 1\nMD 4 = 1\nMD 1 = 500\nMD 2 = 500\nMD 3 = 6000\nMD 6 = 0\nMD 7 = 1\nMD 8 = 10\nMD 9 = 1\n"
    "MD 10 = 21\nMD 11 = -24537\nMD 12 = -42728\nMD 13 = 96417\nMD 14 = 137428\nMD 15 = 47\nMD 16 = 0\n"
    "MD 17 = 0\nMD 18 = 0\nMD 19 = 1\nMD 20 = 0\nMD 21 = 4\nMD 22 = 1.00\nMD 23 = 8000\nMD 24 = 12000\n"
    "MD 25 = 40\nMD 26 = 1200\nMD 27 = 0\nMD 28 = 0\nMD 29 = 0\nMD 30 = 150\nMD 31 = 0\nMD 32 = 30\nMD 33 = 11\n"
    "MD 34 = 10000\nMD 35 = 0\nMD 36 = 0\nMD 38 = 0\nMD 39 = 0\nMD 40 = 0\nMD 41 = 0\nMD 42 = 0\nMD 46 = 500\n"
    "MD 47 = 500\nMD 50 = 0\n";

// Short moves with flying changes, an M output, a dwell and a subprogram call (2 passes).
const char* const program_text =
    "%1\nN1 G90 X 2 000 F 300 000\nN2 G91 X 1 000 F 200 000 M21\nN3 G04 F 5\nN4 L2 P2\nN5 G90 X 0 F 300 000\n"
    "%2\nN1 G91 X 500 F 100 000\nN2 G91 X -500 F 100 000 T3\n";

// examples/controllers/wf725-axis-ak.txt: open loop (MD 4 = 3), levels 87/52/5 at 50/25/5 mm, 0 at 60 um.
const char* const ak_md_text =
    "MD 49 = 1\nMD 4 = 3\nMD 1 = 0\nMD 2 = 0\nMD 6 = 0\nMD 7 = 1\nMD 8 = 10\nMD 9 = 1\nMD 10 = 4000\n"
    "MD 11 = -24537\nMD 12 = -42728\nMD 13 = 150000\nMD 14 = 200000\nMD 15 = 1\nMD 16 = 0\nMD 17 = 0\n"
    "MD 18 = 0\nMD 19 = 1\nMD 20 = 0\nMD 21 = 4\nMD 27 = 0\nMD 28 = 0\nMD 30 = 150\nMD 31 = 0\nMD 32 = 30\n"
    "MD 33 = 30\nMD 34 = 10000\nMD 40 = 0\nMD 41 = 0\nMD 42 = 87\nMD 43 = 52\nMD 44 = 5\nMD 45 = 50000\n"
    "MD 46 = 25000\nMD 47 = 5000\nMD 48 = 60\nMD 50 = 0\n";

// Open loop: staged positionings back and forth (F = speed level).
const char* const ak_program_text =
    "%1\nN1 G90 X 60 000 F 87\nN2 G90 X 10 000 F 60\nN3 G91 X 5 000 F 20\nN4 G90 X 0 F 87\n";

/// A WF axis on the simulated drive, synchronized, running program 1 in automatic cycle.
struct Axis {
  fs::path dir = fs::temp_directory_path() / "bench_wf725";
  std::unique_ptr<s5::Wf725Controller> ctl;
  std::unique_ptr<hil::motion::Axis> axis;
  hil::TimePoint now{};
  int every = 6;
  int last_block = 0;
  std::int64_t blocks = 0;

  explicit Axis(const char* md = md_text, const char* program = program_text, char letter = 'A',
                s5::Wf726Module* module = nullptr) {
    dir += std::string(1, letter);
    fs::create_directories(dir);
    std::ofstream(dir / "md.txt") << md;
    std::ofstream(dir / "p.wf") << program;
    hil::controllers::ControllerSpec spec;
    spec.device = "wf725-726";
    spec.parameters = dir / "md.txt";
    spec.programs = {dir / "p.wf"};
    spec.file = (dir / "bench.yaml").string();
    spec.options["axis"] = std::string(1, letter);
    spec.options["db"] = std::to_string(10 + (letter - 'A'));
    hil::controllers::ControllerRegistry r;
    s5::register_wf725(r);
    auto c = r.create(spec);
    if (!c) throw std::runtime_error(c.error().describe());
    ctl.reset(static_cast<s5::Wf725Controller*>(c->release()));
    hil::mocks::SimDriveConfig d;
    d.name = "sim:A";
    d.plant.kv_per_s = 200.0;
    d.plant.velocity_lag_s = 0.0;
    d.plant.velocity_feedforward = 1.0;
    axis = std::make_unique<hil::motion::Axis>(ctl->axis_specs()[0].config, std::make_unique<hil::mocks::SimDrive>(d));
    hil::motion::Axis* p = axis.get();
    if (!ctl->bind_axes(std::span<hil::motion::Axis* const>(&p, 1))) throw std::runtime_error("bind");
    every = static_cast<int>(ctl->cycle_period() / milliseconds(1));
    if (module != nullptr && !module->add(*ctl)) throw std::runtime_error("module");
    // Traversing, set actual value, drive enable, start; then automatic, program 1 (a slave: "0").
    ctl->write_db_word(db::dw_mode, 0x0100 | static_cast<unsigned>(db::Submode::set_actual));
    ctl->write_db_word(db::dw_enable, 1);
    cycles(10);
    pulse_start();
    ctl->write_db_word(db::dw_mode,
                       0x0100 | static_cast<unsigned>(letter == 'A' ? db::Submode::automatic : db::Submode::none));
    ctl->write_db_word(db::dw_program, letter == 'A' ? 1 : 0);
    cycles(3);
  }
  ~Axis() { fs::remove_all(dir); }

  /// One module cycle: `every` axis updates at 1 ms, one controller step; returns the step's time.
  std::chrono::nanoseconds cycle() {
    for (int i = 0; i < every; ++i) {
      now += milliseconds(1);
      axis->update(hil::CycleTime{now, milliseconds(1)});
    }
    const auto t0 = std::chrono::steady_clock::now();
    (void)ctl->step(hil::CycleTime{now, ctl->cycle_period()});
    const auto dt = std::chrono::steady_clock::now() - t0;
    const int block = ctl->read_db_word(db::dw_block);
    if (block != last_block && (block & 0xFF) != 0) ++blocks;
    last_block = block;
    // Program end: start it again (the start bit's edge over two cycles).
    if ((ctl->read_db_word(db::dw_flags) & 2) == 0 && ctl->read_db_word(db::dw_program) != 0) {
      const auto w = ctl->read_db_word(db::dw_control);
      ctl->write_db_word(db::dw_control, static_cast<std::uint16_t>(w ^ 1U));
    }
    return dt;
  }
  void cycles(int n) {
    for (int i = 0; i < n; ++i) (void)cycle();
  }
  void pulse_start() {
    ctl->write_db_word(db::dw_control, 1);
    cycles(2);
    ctl->write_db_word(db::dw_control, 0);
    cycles(2);
  }
};

void BM_Wf725ParseBlock(benchmark::State& state) {
  std::string text = "%1 A RAM\n";
  for (int i = 1; i <= 200; ++i) text += "N" + std::to_string(i) + " G91 G23 X -12 345 F 250 000 M21 T3\n";
  for (auto _ : state) {
    auto p = s5::parse_wf725_programs(text);
    benchmark::DoNotOptimize(p);
  }
  state.SetItemsProcessed(state.iterations() * 200);  // blocks
}
BENCHMARK(BM_Wf725ParseBlock);

/// The controller's step alone (modes, program interpretation, M output, status words) per cycle.
void BM_Wf725ControllerCycle(benchmark::State& state) {
  Axis a;
  for (auto _ : state) state.SetIterationTime(std::chrono::duration<double>(a.cycle()).count());
  state.counters["blocks"] = static_cast<double>(a.blocks);
  state.counters["blocks_per_cycle"] = static_cast<double>(a.blocks) / static_cast<double>(state.iterations());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Wf725ControllerCycle)->UseManualTime();

/// The module cycle: the controller's step and its six 1 ms axis updates on the simulated drive.
void BM_Wf725ModuleCycle(benchmark::State& state) {
  Axis a;
  for (auto _ : state) benchmark::DoNotOptimize(a.cycle());
  state.counters["blocks_per_sim_s"] =
      benchmark::Counter(static_cast<double>(a.blocks) / (static_cast<double>(state.iterations()) * a.every * 1e-3));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Wf725ModuleCycle);

/// An open-loop axis (MD 4 = 3) running staged positionings: the speed-level selection by the
/// remaining distance, the cut-off outputs, DL 4 and the PEH/21/22 watch, with the axis updates.
void BM_Wf725OpenLoopModuleCycle(benchmark::State& state) {
  Axis a(ak_md_text, ak_program_text);
  for (auto _ : state) benchmark::DoNotOptimize(a.cycle());
  state.counters["blocks_per_sim_s"] =
      benchmark::Counter(static_cast<double>(a.blocks) / (static_cast<double>(state.iterations()) * a.every * 1e-3));
  if (a.ctl->level_changes().empty()) state.SkipWithError("no staged positioning ran");
  if ((a.ctl->read_db_word(db::dw_status) & (1U << db::bit_error)) != 0) state.SkipWithError("an error stopped it");
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Wf725OpenLoopModuleCycle);

// A combined program on A: a block of B, a G17 pair out and a G17 pair back.
const char* const combined_text =
    "%1\nN1 G90 X 2 000 F 300 000\nN2 B X 1 000\nN3 A G17 X 4 000\nN4 B X 3 000\nN5 A G17 X 0\nN6 B X 0\n";

/// A WF 726 with axes A and B (one Wf726Module) running a combined program on A: both controllers'
/// steps and both axes' 1 ms updates per module cycle; errors would stop it.
void BM_Wf726CombinedModuleCycle(benchmark::State& state) {
  s5::Wf726Module module;
  // The slave first (in submode "0" before the master's first start); the module's program memory
  // is the first axis', so B's program file holds the combined program.
  Axis b(md_text, combined_text, 'B', &module);
  Axis a(md_text, combined_text, 'A', &module);
  std::int64_t blocks = 0;
  for (auto _ : state) {
    for (int i = 0; i < b.every; ++i) {
      b.now += milliseconds(1);
      b.axis->update(hil::CycleTime{b.now, milliseconds(1)});
    }
    benchmark::DoNotOptimize(a.cycle());
    (void)b.ctl->step(hil::CycleTime{b.now, b.ctl->cycle_period()});
  }
  blocks = a.blocks;
  state.counters["blocks_per_sim_s"] =
      benchmark::Counter(static_cast<double>(blocks) / (static_cast<double>(state.iterations()) * a.every * 1e-3));
  if ((a.ctl->read_db_word(db::dw_status) & (1U << db::bit_error)) != 0 ||
      (b.ctl->read_db_word(db::dw_status) & (1U << db::bit_error)) != 0)
    state.SkipWithError(("an error stopped the combined program: A " +
                         std::to_string(a.ctl->read_db_word(db::dw_error) & 0xFF) + ", B " +
                         std::to_string(b.ctl->read_db_word(db::dw_error) & 0xFF))
                            .c_str());
  if (blocks == 0) state.SkipWithError("no block ran");
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Wf726CombinedModuleCycle);

}  // namespace
