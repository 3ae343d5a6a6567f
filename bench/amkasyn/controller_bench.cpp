// SPDX-License-Identifier: MIT
// The amkasyn-sf controller's cycle (run: bench_amkasyn_controller --benchmark_format=json): one
// controller step with two SFs (ECOPY on the flag image, VARSYNC driving AW3 from AZ message 1)
// and the image mapping (256 bytes each of E/A/M, the PLC flags, the command bits), plus the two
// axes' updates on simulated drives, as one run cycle does them.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>

#include "hil/controllers/amkasyn/amkasyn_controller.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace {

using namespace hil::controllers;
using namespace hil::controllers::amkasyn;
namespace fs = std::filesystem;

constexpr const char* ecopy =
    "INIT DR0 = 0\nINIT DL0 = 0\nINIT DR1 = 3\nINIT DL3 = 64\nINIT DR4 = 1\nINIT DL4 = 100\nINIT DR5 = 1\n"
    "INIT DL5 = 101\nDR0 = 0\nDL0 = 2\nDR1 = 1\nDL1 = 3\nDD2 = 10000\nDD4 = 5000\n";
constexpr const char* varsync =
    "INIT DR0 = 3\nINIT DL0 = 2\nINIT DR2 = 1\nINIT DR3 = 4\nINIT DL3 = 3\nINIT DR4 = 4\nINIT DL4 = 16\n"
    "INIT DR5 = 4\nINIT DL5 = 16\nDR0 = 2\nDL0 = 1\nDR1 = 1\nDW2 = 7936\nDW4 = 10000\nDW6 = -10000\n";

void BM_ControllerCycle(benchmark::State& state) {
  const fs::path dir = fs::temp_directory_path() / "hil_amk_bench";
  fs::create_directories(dir);
  std::ofstream(dir / "ecopy.txt") << ecopy;
  std::ofstream(dir / "varsync.txt") << varsync;
  ControllerSpec spec;
  spec.device = "amkasyn-sf";
  spec.parameters = dir / "ecopy.txt";
  spec.programs = {dir / "varsync.txt"};
  spec.options = {{"aw3", "S"}, {"az1", "M"}};
  ControllerRegistry registry;
  register_amkasyn(registry);
  auto created = registry.create(spec);
  if (!created) {
    state.SkipWithError(created.error().describe().c_str());
    return;
  }
  auto& ctl = **created;
  std::vector<std::unique_ptr<hil::motion::Axis>> axes;
  std::vector<hil::motion::Axis*> ptrs;
  for (const auto& a : ctl.axis_specs()) {
    hil::mocks::SimDriveConfig d;
    d.plant.kv_per_s = 200.0;
    d.plant.velocity_feedforward = 1.0;
    axes.push_back(std::make_unique<hil::motion::Axis>(a.config, std::make_unique<hil::mocks::SimDrive>(d)));
    ptrs.push_back(axes.back().get());
  }
  (void)ctl.bind_axes(ptrs);
  hil::TimePoint now{};
  const auto dt = std::chrono::milliseconds(1);
  auto cycle = [&] {
    now += dt;
    for (auto& a : axes) a->update(hil::CycleTime{now, dt});
    ctl.step(hil::CycleTime{now, dt});
  };
  for (int i = 0; i < 100; ++i) cycle();  // enabled, SFs started
  (void)axes[1]->move_velocity(1e6);      // the master turns: VARSYNC drives S every cycle
  for (auto _ : state) cycle();
  fs::remove_all(dir);
}
BENCHMARK(BM_ControllerCycle);

}  // namespace
