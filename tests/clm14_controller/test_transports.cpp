// SPDX-License-Identifier: MIT
// The same CLM1.4 program gives the same trace on every transport: transport sim, the in-process
// CANopen CiA 402 node, the in-process Modbus/TCP drive server and mock step/dir lines (virtual
// time, the runtime's Machine builds the drives exactly as `hilbridge run` does).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "hil/cia402/canopen_transport.hpp"
#include "hil/drives/modbus_transport.hpp"
#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/mocks/sim_transport.hpp"
#include "hil/runtime/machine.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "rig.hpp"

namespace hil::controllers::clm14 {
namespace {

using namespace std::chrono_literals;

struct Case {
  std::string name;
  std::string drive;  // the axis' drive block (flow style)
};

std::string machine_yaml(const Case& c) {
  return fmt::format(R"(name: clm-{}
period: 2ms
machine:
  axes:
    - name: a1
      units: IU
      inc_per_unit: 100
      limits: {{velocity: 100, acceleration: 1000}}
      supervision: {{following_error: 10, in_position: 0.01, standstill: 0.05}}
      drive: {}
)",
                     c.name, c.drive);
}

struct Event {
  int line;
  int outputs;
  friend bool operator==(const Event&, const Event&) = default;
};

struct Trace {
  std::vector<Event> events;
  double final_position = 0.0;
  int error = -1;
};

Trace run_on(const Case& c) {
  // The factories `hilbridge` registers, from their drives' libraries.
  TransportRegistry registry;
  registry.add("sim", [] { return mocks::make_sim_transport(); });
  registry.add("canopen", [] { return cia402::make_canopen_transport(); });
  registry.add("modbus", [] { return drives::make_modbus_transport(); });
  registry.add("stepdir", [] { return std::make_unique<drives::stepdir::StepDirTransportFactory>(); });
  auto scenario = runtime::parse_scenario(machine_yaml(c), c.name + ".yaml");
  EXPECT_TRUE(scenario) << (scenario ? "" : scenario.error().describe());
  VirtualClock clock;
  RunEnvironment env{clock, true, nullptr, scenario->file, scenario->period, false, {}};
  auto machine = runtime::Machine::build(*scenario, registry, env);
  EXPECT_TRUE(machine) << (machine ? "" : machine.error().describe());
  MotionAxisPort port(*machine->axes()[0].axis);

  auto data = serial::clm14::load_device_data().value();
  auto params = testing::base_parameters();
  params["A127"] = "M2.00.0 0000.010";
  Controller clm;
  clm.set_parameters([&](std::string_view n) {
    const auto it = params.find(std::string(n));
    return it != params.end() ? it->second : data->parameter_default(n);
  });
  clm.attach_axis(1, &port);
  EXPECT_TRUE(clm.load_program({{0, "AEA Q1.00.0 1"},
                                {1, "PSI 1 +000020.000 999"},
                                {2, "COU +00000 Q1.00.1 000003"},
                                {3, "WAI 00.100"},
                                {4, "BCE 0006 Q1.00.1 1"},
                                {5, "JMP 0001"},
                                {6, "POI 1 -000030.000 500"},
                                {7, "AKN M2.00.0 1"},
                                {8, "AEA Q1.00.0 0"},
                                {9, "JST 0000"}}));
  auto& im = clm.image();
  im.set_bit(sys::emergency_stop_ok, true);
  im.set_bit(sys::immediate_stop_ok, true);
  im.set_bit(sys::enable[0], true);
  Trace tr;
  TimePoint now{};
  const Duration period = 2ms;
  const auto step = [&] {
    now += period;
    clock.advance_to(now);
    clm.cycle(now);
    machine->cycle(CycleTime{now, period});
    const Event e{clm.task(1).pc, im.byte({Area::output, 1, 0})};
    if (tr.events.empty() || !(tr.events.back() == e)) tr.events.push_back(e);
  };
  for (int i = 0; i < 200; ++i) step();  // enable the drive (CANopen boot-up, Modbus connect)
  im.set_bit(sys::automatic, true);
  step();
  step();
  im.set_bit(sys::start, true);
  step();
  im.set_bit(sys::start, false);
  for (int i = 0; i < 10000 && clm.run_state() == RunState::running; ++i) step();
  tr.final_position = clm.position(1);
  tr.error = clm.error();
  if (clm.error() != 0) ADD_FAILURE() << c.name << ": " << clm.error_message();
  return tr;
}

TEST(ClmTransports, SameProgramSameTraceOnEveryTransport) {
  const std::vector<Case> cases{
      {"sim", "{transport: sim, kv: 200, velocity_lag: 0.001, feedforward: 1}"},
      {"canopen", "{transport: canopen, node: 1, kv: 200, velocity_lag: 0.001}"},
      {"modbus", "{transport: modbus, profile: cia402, plant: {kv: 200, velocity_lag: 0.001}}"},
      {"stepdir",
       "{transport: stepdir, profile: motion, fmax_hz: 20000, fss_hz: 200, accel_hz_per_s: 500000, "
       "pulse_us: 10}"},
  };
  std::vector<Trace> traces;
  for (const auto& c : cases) traces.push_back(run_on(c));
  ASSERT_FALSE(traces[0].events.empty());
  // three 20 IU feeds, then 30 back: ends at +30
  for (std::size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(traces[i].error, 0) << cases[i].name;
    EXPECT_NEAR(traces[i].final_position, 30.0, 0.011) << cases[i].name;
    EXPECT_EQ(traces[i].events, traces[0].events) << cases[i].name << " differs from sim";
  }
}

}  // namespace
}  // namespace hil::controllers::clm14
