// SPDX-License-Identifier: MIT
// Retrofit mode of the emulated CLM1.4 (`emulate clm14 --machine`): a machine file's axis named
// ME1 is master encoder 1 in place of the simulated measuring wheel - here a CiA 402 node on the
// in-process CAN bus whose actual position the station reads as the wheel's counts (status 47,
// V011), while axis 1 is another node on that bus.
#include <gtest/gtest.h>

#include "hil/cia402/canopen_transport.hpp"
#include "hil/mocks/legacy/clm14_retrofit.hpp"
#include "hil/mocks/sim_transport.hpp"
#include "hil/runtime/machine.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "hil/serial/clm14/telegram.hpp"

namespace hil::mocks::legacy {
namespace {

using namespace std::chrono_literals;
namespace cc = hil::controllers::clm14;

// ME1 counts 250 increments per IU: C000 1250 pulses × 4 per C002 20 IU.
constexpr const char* machine_yaml = R"(name: clm retrofit with a CANopen measuring wheel
period: 2ms
machine:
  axes:
    - name: "1"
      units: IU
      inc_per_unit: 100
      limits: {velocity: 100, acceleration: 1000}
      supervision: {following_error: 10, in_position: 0.01, standstill: 0.05}
      drive: {transport: canopen, node: 1, kv: 200, velocity_lag: 0.001}
    - name: ME1
      units: IU
      inc_per_unit: 250
      limits: {velocity: 200, acceleration: 2000}
      supervision: {following_error: 10, in_position: 0.01, standstill: 0.05}
      drive: {transport: canopen, node: 2, kv: 200, velocity_lag: 0.001}
)";

std::string ask(Clm14Station& s, char lead, std::string_view body) {
  std::string wire = serial::clm14::make_telegram(lead, ' ', body);
  return s.on_line(std::string_view(wire).substr(0, wire.size() - 2));
}

TEST(ClmRetrofit, MachineAxisMe1IsMasterEncoder1) {
  TransportRegistry registry;
  registry.add("sim", [] { return mocks::make_sim_transport(); });
  registry.add("canopen", [] { return cia402::make_canopen_transport(); });
  auto scenario = runtime::parse_scenario(machine_yaml, "retrofit.yaml");
  ASSERT_TRUE(scenario) << scenario.error().describe();
  VirtualClock clock;
  RunEnvironment env{clock, true, nullptr, scenario->file, scenario->period, false, {}};
  auto machine = runtime::Machine::build(*scenario, registry, env);
  ASSERT_TRUE(machine) << machine.error().describe();
  std::vector<std::string> names;
  std::vector<motion::Axis*> axes;
  for (auto& a : machine->axes()) {
    names.push_back(a.spec->name);
    axes.push_back(a.axis.get());
  }
  const auto roles = clm14_machine_roles(names, "retrofit.yaml");
  ASSERT_TRUE(roles) << roles.error();
  EXPECT_EQ(roles->axes, std::vector<std::size_t>{0});
  EXPECT_EQ(roles->encoders[0], std::optional<std::size_t>{1});
  EXPECT_FALSE(roles->encoders[1]);

  auto data = serial::clm14::load_device_data();
  ASSERT_TRUE(data) << data.error();
  Clm14Station st(0, *data);
  Clm14Retrofit rf(axes, *roles);
  EXPECT_EQ(rf.axis_count(), 1U);
  rf.attach(st, [&](const CycleTime& c) {
    clock.advance_to(c.now);
    machine->cycle(c);
  });
  EXPECT_TRUE(st.external_master_encoder());
  st.set_mode(ClmMode::parameter);
  ASSERT_EQ(ask(st, '#', "K C000 01250 0000"), "Y\r\n");
  ASSERT_EQ(ask(st, '#', "K C002 0020.00000"), "Y\r\n");
  st.set_mode(ClmMode::manual);
  EXPECT_FALSE(st.set_material_velocity(40.0)) << "the console's simulated wheel is not in use";
  TimePoint t{};
  for (int i = 0; i < 200; ++i) st.tick(t += 2ms);  // CANopen boot-up, axis 1 enabled by the CLM
  ASSERT_EQ(st.fault(), 0) << st.controller().error_message();
  EXPECT_EQ(ask(st, '?', "X 47 "), serial::clm14::make_telegram('X', ' ', "47 0 +0000.00 "));
  // The line moves the wheel node (the CLM never commands it): 40 IU/s = 120 rpm of a 20 IU wheel.
  motion::Axis& wheel = *axes[1];
  ASSERT_FALSE(wheel.enable());
  for (int i = 0; i < 200 && wheel.status().state != motion::AxisState::standstill; ++i) st.tick(t += 2ms);
  const double start = st.controller().master_position();
  EXPECT_NEAR(start, wheel.status().position, 0.01);
  ASSERT_FALSE(wheel.move_velocity(40.0));
  for (int i = 0; i < 1000; ++i) st.tick(t += 2ms);
  EXPECT_NEAR(st.controller().master_velocity(), 40.0, 0.2);
  EXPECT_NEAR(st.controller().master_position(), wheel.status().position, 0.1)
      << "the wheel's IU are the node's increments / 250";
  EXPECT_NE(ask(st, '?', "X 47 ").find("47 0 +0120.0"), std::string::npos) << ask(st, '?', "X 47 ");
  EXPECT_EQ(st.fault(), 0) << st.controller().error_message();
  // Giving the encoder back restores the simulated wheel.
  st.use_master_encoder(1, nullptr);
  EXPECT_TRUE(st.set_material_velocity(10.0));
}

TEST(ClmRetrofit, MachineRolesRefuseBadFiles) {
  const std::vector<std::string> only_encoder{"ME1"};
  EXPECT_FALSE(clm14_machine_roles(only_encoder, "m.yaml"));
  const std::vector<std::string> twice{"1", "ME2", "ME2"};
  const auto t = clm14_machine_roles(twice, "m.yaml");
  ASSERT_FALSE(t);
  EXPECT_NE(t.error().find("ME2 is given twice"), std::string::npos) << t.error();
  const std::vector<std::string> five{"1", "2", "3", "4", "5"};
  EXPECT_FALSE(clm14_machine_roles(five, "m.yaml"));
  const std::vector<std::string> both{"ME2", "x", "ME1", "y"};
  const auto b = clm14_machine_roles(both, "m.yaml");
  ASSERT_TRUE(b) << b.error();
  EXPECT_EQ(b->axes, (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ(b->encoders[0], std::optional<std::size_t>{2});
  EXPECT_EQ(b->encoders[1], std::optional<std::size_t>{0});
}

}  // namespace
}  // namespace hil::mocks::legacy
