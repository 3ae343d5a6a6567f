// SPDX-License-Identifier: MIT
// The IP247 retrofit chain of `emulate ip247 --machine` on virtual time: the module's axis (its own
// step planner) pulses, an Ip247Follower hands its pulse count to a machine axis on the step/dir
// transport (mock lines, verified edges) as a cyclic set-point, in the emulator's order (module
// cycle, follower, machine cycle), BB = the machine axis takes set-points. The machine axis must
// stand where the module's pulses put it: after an out-and-back move and after a limit-switch stop,
// also when the PLC's first job arrives while the drive is still in its reset pulse (BB low).
#include <gtest/gtest.h>

#include <functional>

#include "hil/controllers/s5/ip247_axis.hpp"
#include "hil/controllers/s5/ip247_follower.hpp"
#include "hil/core/clock.hpp"
#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/runtime/machine.hpp"
#include "hil/runtime/scenario_loader.hpp"

using namespace hil::controllers::s5;
using C = Ip247Command;

namespace {

constexpr hil::Duration cycle = std::chrono::milliseconds(1);

// The machine file of tests/controllers_s5/ip247-machine-stepdir.yaml (reset pulse 100 ms default).
constexpr const char* machine_file = R"(name: ip247 retrofit machine, step/dir
period: 1ms
machine:
  axes:
    - name: "1"
      units: pulses
      inc_per_unit: 1
      limits: {velocity: 20000, acceleration: 10000000}
      supervision: {following_error: 200, in_position: 1, standstill: 2}
      drive: {transport: stepdir, profile: motion, fmax_hz: 20000, fss_hz: 500, accel_hz_per_s: 200000, pulse_us: 10}
)";

bool takes_setpoints(const hil::motion::Axis& a) {
  const auto st = a.status().state;
  return st == hil::motion::AxisState::standstill || st == hil::motion::AxisState::moving ||
         st == hil::motion::AxisState::stopping;
}

struct Retrofit {
  hil::VirtualClock clock;
  hil::runtime::Scenario scenario;
  hil::TransportRegistry registry;
  std::unique_ptr<hil::RunEnvironment> env;
  std::optional<hil::runtime::Machine> machine;
  Ip247ProgramStore store;
  Ip247Axis module{store, 1};
  Ip247Follower follower;
  Ip247Inputs in;
  std::optional<std::int64_t> limit_end_at;  ///< module motor pulses from which E END is actuated
  bool enabled = false;

  Retrofit() {
    auto sc = hil::runtime::parse_scenario(machine_file, "ip247-machine-stepdir.yaml");
    EXPECT_TRUE(sc) << sc.error().describe();
    scenario = std::move(*sc);
    registry.add("stepdir", [] { return std::make_unique<hil::drives::stepdir::StepDirTransportFactory>(); });
    env = std::make_unique<hil::RunEnvironment>(
        hil::RunEnvironment{clock, true, nullptr, scenario.file, scenario.period, true, {}});
    auto m = hil::runtime::Machine::build(scenario, registry, *env);
    EXPECT_TRUE(m) << m.error().describe();
    machine.emplace(std::move(*m));
    Ip247MachineData md;
    md.limits_normally_closed = false;
    md.sw_start = -4'000'000;
    md.sw_end = 4'000'000;
    EXPECT_EQ(module.load_machine_data(md, 0), hil::stepdir::Ip247MdError::none);
  }
  hil::motion::Axis& axis() { return *machine->axes().front().axis; }
  std::int64_t pulses() const { return module.planner()->motor_position(); }
  /// One module cycle as the emulator runs it.
  void step() {
    if (!enabled) {
      (void)axis().enable();  // the power section comes up with the module's first cycle
      enabled = true;
    }
    clock.advance(cycle);
    const auto now = clock.now();
    in.ready = takes_setpoints(axis());
    in.limit_end = limit_end_at && pulses() >= *limit_end_at;
    module.step(now.time_since_epoch().count(), cycle.count(), in, nullptr);
    if (takes_setpoints(axis())) follower.step(axis(), module, cycle.count());
    machine->cycle(hil::CycleTime{now, cycle});
  }
  bool run_until(const std::function<bool()>& done, int max_cycles = 60'000) {
    for (int i = 0; i < max_cycles; ++i) {
      step();
      if (done()) return true;
    }
    return false;
  }
  /// Module finished and the machine axis at rest.
  bool settle() {
    if (!run_until([&] { return !module.running(); })) return false;
    return run_until([&] { return axis().status().state == hil::motion::AxisState::standstill; }) &&
           run_until([&] { return axis().status().in_position; });
  }
  void cmd(int ba, C c, std::int64_t value = 0, int byte = 0) {
    module.command({.ba = ba, .command = c, .byte_param = byte, .speed = 3000, .value = value});
  }
};

}  // namespace

TEST(Ip247Retrofit, JobDuringTheResetPulseOutputsNoPulsesTheMachineMisses) {
  Retrofit r;
  for (int i = 0; i < 5; ++i) r.step();
  ASSERT_EQ(r.axis().status().state, hil::motion::AxisState::enabling);  // step/dir: 100 ms reset pulse
  r.cmd(7, C::forward, 50'000);                                          // 5000 pulses
  EXPECT_EQ(r.module.error(), 53);                                       // BB low: refused, no pulses
  ASSERT_TRUE(r.run_until([&] { return takes_setpoints(r.axis()); }));
  r.step();  // the module reads BB high
  EXPECT_EQ(r.pulses(), 0);
  r.cmd(7, C::forward, 50'000);
  EXPECT_EQ(r.module.error(), 0);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.pulses(), 5'000);
  EXPECT_EQ(r.axis().status().position_inc, r.pulses());
}

TEST(Ip247Retrofit, OutAndBackAndLimitStopEndWhereTheModulesPulsesAre) {
  Retrofit r;
  ASSERT_TRUE(r.run_until([&] { return takes_setpoints(r.axis()); }));
  r.step();  // the module reads BB high
  for (int k = 0; k < 3; ++k) {
    r.cmd(7, C::forward, 50'000);
    ASSERT_TRUE(r.settle());
    EXPECT_EQ(r.axis().status().position_inc, r.pulses());
    r.cmd(7, C::backward, 50'000);
    ASSERT_TRUE(r.settle());
    EXPECT_EQ(r.pulses(), 0);
    EXPECT_EQ(r.axis().status().position_inc, 0);
  }
  // E END from 3000 pulses: the module aborts the job and brakes; the machine axis follows it.
  r.limit_end_at = 3'000;
  r.cmd(7, C::forward, 100'000);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.module.error(), 26);
  EXPECT_GE(r.pulses(), 3'000);
  EXPECT_LT(r.pulses(), 10'000);
  EXPECT_EQ(r.axis().status().position_inc, r.pulses());
  EXPECT_FALSE(r.axis().status().fault);
  r.cmd(7, C::backward, 20'000);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.module.error(), 0);
  EXPECT_EQ(r.axis().status().position_inc, r.pulses());
  const auto reports = r.machine->finish(hil::CycleTime{r.clock.now(), cycle});
  bool verified = false;
  for (const auto& rep : reports)
    for (const auto& l : rep.report.lines) {
      EXPECT_EQ(l.find("VIOLATION"), std::string::npos) << l;
      verified = verified || l.find("timing rules held") != std::string::npos;
    }
  EXPECT_TRUE(verified);
}
