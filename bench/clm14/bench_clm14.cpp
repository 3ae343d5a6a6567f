// SPDX-License-Identifier: MIT
// One NC cycle of a CLM1.4 running 5 tasks and a 1000-line logic task on 4 axes (issue 15:
// target < 2 µs, i.e. a CLM runs 1000x faster than real time on virtual time).
//   ClmCycle/controller        : Controller::cycle() alone (axes attached, feedback read)
//   ClmCycle/with_axes         : plus the 4 hil::motion::Axis updates over simulated drives
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hil/controllers/clm14/controller.hpp"
#include "hil/controllers/clm14/logic_task.hpp"
#include "hil/controllers/clm14/motion_axis_port.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace {

using namespace hil::controllers::clm14;

std::map<std::string, std::string> parameters() {
  std::map<std::string, std::string> p{{"B000", "1 1 1"},          {"B010", "0.0"},
                                       {"B011", "0200 0300 0"},    {"B012", "0400 0500"},
                                       {"B014", "00.00.0 0 0000"}, {"B015", "00.00.0 0 0 0000"},
                                       {"B016", "0000"},           {"B018", "0 0000000"}};
  for (int ax = 1; ax <= 4; ++ax) {
    const auto n = [ax](int k) { return "A" + std::to_string(ax) + (k < 10 ? "0" : "") + std::to_string(k); };
    p[n(0)] = "1 0 0 0 0";
    p[n(1)] = "0010.00000";
    p[n(3)] = "-111111.111";
    p[n(4)] = "+100000.000";
    p[n(5)] = "000000.000 0";
    p[n(6)] = "000100.000";
    p[n(7)] = "000050.000";
    p[n(8)] = "001000";
    p[n(9)] = "000 000";
    p[n(10)] = "0.000";
    p[n(15)] = "00.00.0 00.00.0";
    p[n(19)] = "01024 1024";
    p[n(20)] = "0 0 00 1";
    p[n(23)] = "00.00.0 00.00.0";
    p[n(24)] = "00.00.0 +100 0";
    p[n(25)] = "+00000.000";
    p[n(27)] = "M2.0" + std::to_string(ax - 1) + ".0 0000.010";
    p[n(29)] = "00.00.0 0.0 0000";
    p[n(32)] = "00.00.0 00.00.0";
  }
  return p;
}

struct Bench {
  explicit Bench() : clm(options()) {
    clm.set_parameters([this](std::string_view n) {
      const auto it = params.find(std::string(n));
      return it == params.end() ? std::string{} : it->second;
    });
    auto s = make_settings([this](std::string_view n) {
      const auto it = params.find(std::string(n));
      return it == params.end() ? std::string{} : it->second;
    });
    for (int ax = 1; ax <= 4; ++ax) {
      hil::mocks::SimDriveConfig dc;
      dc.plant.kv_per_s = 200.0;
      dc.plant.velocity_feedforward = 1.0;
      dc.plant.max_velocity_inc_per_s = 1e9;
      axes.push_back(
          std::make_unique<hil::motion::Axis>(make_axis_config(s->axes[static_cast<std::size_t>(ax - 1)], "a"),
                                              std::make_unique<hil::mocks::SimDrive>(dc)));
      ports.push_back(std::make_unique<MotionAxisPort>(*axes.back()));
      clm.attach_axis(ax, ports.back().get());
    }
    std::vector<std::pair<int, std::string>> prog{// task 1: feeds on all four axes, counters, arithmetic
                                                  {0, "POI 1 +000001.000 999"},
                                                  {1, "POI 2 +000001.000 999"},
                                                  {2, "POI 3 +000001.000 999"},
                                                  {3, "POI 4 +000001.000 999"},
                                                  {4, "COU +00000 Q1.00.4 001000"},
                                                  {5, "MAT V600 = V600 + +1.5"},
                                                  {6, "JMP 0000"},
                                                  // tasks 2..5: bit, byte and variable work that never waits
                                                  {200, "BIC 0210 1 M2.10.0 2 0"},
                                                  {210, "AEA Q1.01.0 1"},
                                                  {211, "APE Q1.02 21021021"},
                                                  {212, "JMP 0200"},
                                                  {300, "CPJ V600 > +5.0 0.0 0302"},
                                                  {301, "JMP 0300"},
                                                  {302, "CPS V600 < +1000000.0 0.0 M2.11.0"},
                                                  {303, "JMP 0300"},
                                                  {400, "CIO I1.00.0 M2.12.0 16"},
                                                  {401, "BPA 0400 M2.12 22222222"},
                                                  {500, "SET V700 = V600"},
                                                  {501, "CVT V700 M2.13 0 0"},
                                                  {502, "JMP 0500"}};
    if (!clm.load_program(prog)) std::abort();
    for (int i = 0; i < 999; ++i) {
      const int b = i % 8;
      const std::string m = "M6.2" + std::to_string(i % 10) + "." + std::to_string(b);
      switch (i % 4) {
        case 0:
          clm.store_logic_line(i, "LD I1.00." + std::to_string(b));
          break;
        case 1:
          clm.store_logic_line(i, "AND " + m);
          break;
        case 2:
          clm.store_logic_line(i, "OR M4.00." + std::to_string(b));
          break;
        default:
          clm.store_logic_line(i, "ST " + m);
      }
    }
    clm.store_logic_line(999, "END");
    auto& im = clm.image();
    im.set_bit(sys::emergency_stop_ok, true);
    im.set_bit(sys::immediate_stop_ok, true);
    for (const auto& e : sys::enable) im.set_bit(e, true);
    step(false);
    im.set_bit(sys::automatic, true);
    for (int i = 0; i < 200; ++i) step(true);
    im.set_bit(sys::start, true);
    step(true);
    if (clm.run_state() != RunState::running || clm.error() != 0) std::abort();
  }
  static Options options() {
    Options o;
    o.logic_period = hil::Duration::zero();  // the logic task in every cycle
    return o;
  }
  void step(bool with_axes) {
    now += period;
    clm.cycle(now);
    if (with_axes)
      for (auto& a : axes) a->update(hil::CycleTime{now, period});
  }
  std::map<std::string, std::string> params = parameters();
  Controller clm;
  std::vector<std::unique_ptr<hil::motion::Axis>> axes;
  std::vector<std::unique_ptr<MotionAxisPort>> ports;
  hil::TimePoint now{};
  hil::Duration period{std::chrono::milliseconds(4)};
};

void BM_ClmCycleController(benchmark::State& state) {
  Bench b;
  for (auto _ : state) {
    b.step(false);
    benchmark::DoNotOptimize(b.clm.variable(600));
  }
  if (b.clm.error() != 0) state.SkipWithError(b.clm.error_message().c_str());
}
BENCHMARK(BM_ClmCycleController)->Name("ClmCycle/controller");

void BM_ClmCycleWithAxes(benchmark::State& state) {
  Bench b;
  for (auto _ : state) {
    b.step(true);
    benchmark::DoNotOptimize(b.clm.variable(600));
  }
  if (b.clm.error() != 0) state.SkipWithError(b.clm.error_message().c_str());
}
BENCHMARK(BM_ClmCycleWithAxes)->Name("ClmCycle/with_axes");

/// One pass of the 1000-line logic task alone (the bulk of an NC cycle).
void BM_ClmLogicPass(benchmark::State& state) {
  std::vector<std::string> lines;
  for (int i = 0; i < 999; ++i) {
    const int b = i % 8;
    const std::string m = "M6.2" + std::to_string(i % 10) + "." + std::to_string(b);
    switch (i % 4) {
      case 0:
        lines.push_back("LD I1.00." + std::to_string(b));
        break;
      case 1:
        lines.push_back("AND " + m);
        break;
      case 2:
        lines.push_back("OR M4.00." + std::to_string(b));
        break;
      default:
        lines.push_back("ST " + m);
    }
  }
  lines.emplace_back("END");
  auto program = LogicProgram::compile(lines);
  if (!program) {
    state.SkipWithError(program.error().message.c_str());
    return;
  }
  Image image;
  image.set_byte({Area::input, 1, 0}, 0x5A);
  image.set_byte({Area::marker, 4, 0}, 0x0F);
  for (auto _ : state) {
    program->run(image);
    benchmark::DoNotOptimize(image.bytes().data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(program->size()));
}
BENCHMARK(BM_ClmLogicPass)->Name("ClmLogic/pass_1000_lines");

}  // namespace
