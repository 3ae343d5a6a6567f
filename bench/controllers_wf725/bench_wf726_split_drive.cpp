// SPDX-License-Identifier: MIT
// bench_wf726_split_drive: a WF 726 split drive (gantry A+B, MD 27 = 3, MD 29 monitored) running a
// program in automatic cycle on two simulated drives: one module cycle (6 ms) of the pair, i.e.
// per 1 ms run period A's axis update, B's split-drive set-point (Axis::follow) and axis update,
// and the two controller steps (A's program, B's MD 29 comparison); against the same two axes
// uncoupled (B standing). The difference is the coupling's cost.
// Run: bench_wf726_split_drive --benchmark_format=json
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace s5 = hil::controllers::s5;
namespace db = s5::wf_db;
namespace fs = std::filesystem;
using std::chrono::milliseconds;

namespace {

// examples/controllers/wf725-axis-a.txt with MD 27 = @27@, MD 29 = 100 µm.
std::string md_text(int md27) {
  return "MD 49 = 1\nMD 4 = 1\nMD 1 = 500\nMD 2 = 500\nMD 3 = 6000\nMD 6 = 0\nMD 7 = 1\nMD 8 = 10\nMD 9 = 1\n"
         "MD 10 = 21\nMD 11 = -24537\nMD 12 = -42728\nMD 13 = 96417\nMD 14 = 137428\nMD 15 = 47\nMD 16 = 0\n"
         "MD 17 = 0\nMD 18 = 0\nMD 19 = 1\nMD 20 = 0\nMD 21 = 4\nMD 22 = 1.00\nMD 23 = 8000\nMD 24 = 12000\n"
         "MD 25 = 40\nMD 26 = 1200\nMD 27 = " +
         std::to_string(md27) +
         "\nMD 28 = 0\nMD 29 = 100\nMD 30 = 150\nMD 31 = 0\nMD 32 = 30\nMD 33 = 11\n"
         "MD 34 = 10000\nMD 35 = 0\nMD 36 = 0\nMD 38 = 0\nMD 39 = 0\nMD 40 = 0\nMD 41 = 0\nMD 42 = 0\nMD 46 = 500\n"
         "MD 47 = 500\nMD 50 = 0\n";
}

const char* const program_text =
    "%1\nN1 G90 X 20 000 F 300 000\nN2 G90 X 40 000 F 600 000\nN3 G90 X 5 000 F 300 000\nN4 G90 X 0 F 300 000\n";

struct Side {
  std::unique_ptr<s5::Wf725Controller> ctl;
  std::unique_ptr<hil::motion::Axis> axis;
};

struct Gantry {
  fs::path dir = fs::temp_directory_path() / "bench_wf726_split";
  Side a, b;
  hil::TimePoint now{};
  long tick = 0;

  explicit Gantry(bool coupled) {
    fs::create_directories(dir);
    make(a, 'A', coupled ? 3 : 0);
    make(b, 'B', 0);
    if (coupled) {
      s5::Wf725Controller* axes[] = {a.ctl.get(), b.ctl.get()};
      if (auto r = s5::wf725_couple_split_drive(axes); !r) throw std::runtime_error(r.error());
    }
    for (Side* s : {&a, &b}) {
      s->ctl->write_db_word(db::dw_mode, 0x0100 | static_cast<unsigned>(db::Submode::set_actual));
      s->ctl->write_db_word(db::dw_enable, 1 | (1U << db::bit_split_monitoring));
    }
    periods(60, false);
    for (Side* s : {&a, &b}) s->ctl->write_db_word(db::dw_control, 1);
    periods(12, false);
    for (Side* s : {&a, &b}) s->ctl->write_db_word(db::dw_control, 0);
    periods(12, false);
    b.ctl->write_db_word(db::dw_mode, 0x0100);  // submode "0"
    a.ctl->write_db_word(db::dw_mode, 0x0100 | static_cast<unsigned>(db::Submode::automatic));
    a.ctl->write_db_word(db::dw_program, 1);
    periods(12, false);
  }
  ~Gantry() { fs::remove_all(dir); }

  void make(Side& s, char letter, int md27) {
    const auto md = dir / (std::string("md-") + letter + ".txt");
    std::ofstream(md) << md_text(md27);
    std::ofstream(dir / "p.wf") << program_text;
    hil::controllers::ControllerSpec spec;
    spec.device = "wf725-726";
    spec.parameters = md;
    if (letter == 'A') spec.programs = {dir / "p.wf"};
    spec.options["axis"] = std::string(1, letter);
    spec.options["db"] = std::to_string(10 + (letter - 'A'));
    spec.file = (dir / "bench.yaml").string();
    hil::controllers::ControllerRegistry r;
    s5::register_wf725(r);
    auto c = r.create(spec);
    if (!c) throw std::runtime_error(c.error().describe());
    s.ctl.reset(static_cast<s5::Wf725Controller*>(c->release()));
    hil::mocks::SimDriveConfig d;
    d.name = std::string("sim:") + letter;
    d.plant.kv_per_s = 200.0;
    d.plant.velocity_lag_s = 0.0;
    d.plant.velocity_feedforward = 1.0;
    s.axis =
        std::make_unique<hil::motion::Axis>(s.ctl->axis_specs()[0].config, std::make_unique<hil::mocks::SimDrive>(d));
    hil::motion::Axis* p = s.axis.get();
    if (!s.ctl->bind_axes(std::span<hil::motion::Axis* const>(&p, 1))) throw std::runtime_error("bind");
  }

  /// `n` run periods of 1 ms in the order of `hilbridge emulate wf725`; `restart`: a program that
  /// ended is started again.
  void periods(int n, bool restart = true) {
    for (int i = 0; i < n; ++i) {
      now += milliseconds(1);
      ++tick;
      const hil::CycleTime c{now, milliseconds(1)};
      for (Side* s : {&a, &b}) {
        s->ctl->split_drive_period(c);
        s->axis->update(c);
        if (tick % 6 == 0) (void)s->ctl->step(hil::CycleTime{now, s->ctl->cycle_period()});
      }
    }
    // Program end: start it again (the start bit's edge over two cycles).
    if (restart && (a.ctl->read_db_word(db::dw_flags) & 2) == 0) {
      const auto w = a.ctl->read_db_word(db::dw_control);
      a.ctl->write_db_word(db::dw_control, static_cast<std::uint16_t>(w ^ 1U));
    }
  }
};

void run(benchmark::State& state, bool coupled) {
  Gantry g(coupled);
  double travel = 0.0;
  double last = g.b.axis->status().position;
  for (auto _ : state) {
    g.periods(6);  // one module cycle
    travel += std::abs(g.b.axis->status().position - last);
    last = g.b.axis->status().position;
  }
  if ((g.a.ctl->read_db_word(db::dw_status) & (1U << db::bit_error)) != 0 ||
      (g.b.ctl->read_db_word(db::dw_status) & (1U << db::bit_error)) != 0)
    state.SkipWithError(("an error stopped the gantry: A " +
                         std::to_string(g.a.ctl->read_db_word(db::dw_error) & 0xFF) + ", B " +
                         std::to_string(g.b.ctl->read_db_word(db::dw_error) & 0xFF))
                            .c_str());
  // The first, one-iteration estimate of the framework runs 6 ms only: judge longer runs.
  if (coupled && state.iterations() > 2000 && travel < 1.0) state.SkipWithError("axis B did not follow");
  if (coupled) state.counters["max_difference_um"] = g.a.ctl->split_drive()->max_difference_um;
  state.counters["b_travel_mm_per_sim_s"] =
      benchmark::Counter(travel / (static_cast<double>(state.iterations()) * 6e-3));
  state.SetItemsProcessed(state.iterations());
}

void BM_Wf726SplitDriveModuleCycle(benchmark::State& state) {
  run(state, true);
}
BENCHMARK(BM_Wf726SplitDriveModuleCycle);

void BM_Wf726TwoAxesUncoupledModuleCycle(benchmark::State& state) {
  run(state, false);
}
BENCHMARK(BM_Wf726TwoAxesUncoupledModuleCycle);

}  // namespace
