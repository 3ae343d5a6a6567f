// SPDX-License-Identifier: MIT
// The `modbus` transport factory as `hilbridge run` uses it: drive blocks from YAML (including
// examples/modbus-demo.yaml), in-process servers stepped in begin_cycle, lockstep exchanges on
// virtual time, fault injection into the server, `host:` for an external drive, config errors.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "hil/core/fault_injection.hpp"
#include "hil/drives/modbus_transport.hpp"
#include "hil/mocks/modbus_server.hpp"
#include "hil/modbus/profile.hpp"

namespace hil::test {
namespace {

using std::chrono::milliseconds;

struct RunHarness {
  VirtualClock clock;
  RunEnvironment env{clock, true, nullptr, "tests/modbus/inline.yaml", milliseconds(1), false, {}};
  std::unique_ptr<TransportFactory> factory = drives::make_modbus_transport();
  std::vector<DrivePtr> drives;
  std::vector<DriveCommand> commands;

  std::expected<Drive*, ConfigError> add(const std::string& yaml, const std::string& axis = "x") {
    auto d = factory->make_drive(axis, YAML::Load(yaml), env);
    if (!d) return std::unexpected(d.error());
    drives.push_back(std::move(*d));
    commands.emplace_back();
    return drives.back().get();
  }
  void cycle() {
    clock.advance(milliseconds(1));
    const CycleTime t{clock.now(), milliseconds(1)};
    factory->begin_cycle(t);
    for (auto& d : drives) d->read(t);
    for (std::size_t i = 0; i < drives.size(); ++i) drives[i]->write(t, commands[i]);
    factory->end_cycle(t);
  }
  template <class Pred>
  bool until(Pred p, int max) {
    for (int i = 0; i < max; ++i) {
      cycle();
      if (p()) return true;
    }
    return false;
  }
};

TEST(ModbusTransport, InProcessAxesEnableMoveAndSurviveServerDown) {
  RunHarness run;
  auto x = run.add("{transport: modbus, profile: cia402, response_timeout: 0.05, backoff_min: 0.02}", "x");
  ASSERT_TRUE(x) << x.error().describe();
  auto y = run.add("{transport: modbus, profile: vendor_simple, plant: {kv: 100}}", "y");
  ASSERT_TRUE(y) << y.error().describe();
  EXPECT_EQ((*x)->name().substr(0, 17), "modbus:127.0.0.1:");
  (*x)->request(DriveRequest::enable);
  (*y)->request(DriveRequest::enable);
  ASSERT_TRUE(run.until(
      [&] {
        return (*x)->feedback().state == DriveState::operation_enabled &&
               (*y)->feedback().state == DriveState::operation_enabled;
      },
      20));
  run.commands[0].position_inc = 3000;
  run.commands[1].position_inc = -3000;
  for (int i = 0; i < 500; ++i) run.cycle();
  EXPECT_NEAR(static_cast<double>((*x)->feedback().position_inc), 3000.0, 2.0);
  EXPECT_NEAR(static_cast<double>((*y)->feedback().position_inc), -3000.0, 2.0);

  auto* inj = dynamic_cast<FaultInjectable*>(*x);
  ASSERT_NE(inj, nullptr);
  EXPECT_FALSE(inj->inject_fault("no_such_fault", true));
  ASSERT_TRUE(inj->inject_fault("server_down", true));
  ASSERT_TRUE(run.until([&] { return (*x)->feedback().state == DriveState::fault; }, 5));
  EXPECT_STREQ((*x)->feedback().fault.code.category().name(), "modbus");
  EXPECT_EQ((*y)->feedback().state, DriveState::operation_enabled);  // the other axis is unaffected
  ASSERT_TRUE(inj->inject_fault("server_down", false));
  for (int i = 0; i < 300; ++i) run.cycle();
  (*x)->request(DriveRequest::fault_reset);
  ASSERT_TRUE(run.until([&] { return (*x)->feedback().state == DriveState::switch_on_disabled; }, 10));
  run.commands[0].position_inc = (*x)->feedback().position_inc;
  (*x)->request(DriveRequest::enable);
  ASSERT_TRUE(run.until([&] { return (*x)->feedback().state == DriveState::operation_enabled; }, 20));

  // Plant faults and "busy" go through the same interface.
  ASSERT_TRUE(dynamic_cast<FaultInjectable*>(*y)->inject_fault("encoder", true));
  ASSERT_TRUE(run.until([&] { return (*y)->feedback().state == DriveState::fault; }, 5));
  EXPECT_EQ((*y)->feedback().fault.code.value(), 1);  // vendor fault number 1: encoder
  ASSERT_TRUE(inj->inject_fault("busy", true));
  ASSERT_TRUE(run.until([&] { return (*x)->feedback().fault.code.value() == 6; }, 5));
  ASSERT_TRUE(inj->inject_fault("busy", false));
  ASSERT_TRUE(inj->inject_fault("slow_response", true));  // replies 3x the 50 ms timeout late
  ASSERT_TRUE(run.until([&] { return (*x)->feedback().fault.code.value() == 0x101; }, 5));
  ASSERT_TRUE(inj->inject_fault("slow_response", false));

  const auto report = run.factory->finish(CycleTime{run.clock.now(), milliseconds(1)});
  ASSERT_EQ(report.lines.size(), 2u);
  EXPECT_NE(report.lines[0].find("exchanges"), std::string::npos) << report.lines[0];
}

TEST(ModbusTransport, HostNamesAnExternalDrive) {
  auto profile = modbus::load_profile("profiles/modbus/cia402.yaml");
  ASSERT_TRUE(profile);
  mocks::ModbusDriveServer server(mocks::DriveDevice(*profile), {});
  ASSERT_FALSE(server.start());
  RunHarness run;
  auto d = run.add(fmt::format("{{transport: modbus, profile: cia402, host: '127.0.0.1:{}'}}", server.port()));
  ASSERT_TRUE(d) << d.error().describe();
  EXPECT_EQ(dynamic_cast<FaultInjectable*>(*d), nullptr);  // a real drive: nothing to inject
  (*d)->request(DriveRequest::enable);
  ASSERT_TRUE(run.until(
      [&] {
        server.step(milliseconds(1));
        return (*d)->feedback().state == DriveState::operation_enabled;
      },
      20));
  EXPECT_GT(server.stats().requests, 0u);
}

TEST(ModbusTransport, ConfigErrorsNameTheKey) {
  struct Case {
    const char* yaml;
    const char* key;
    const char* part;
  };
  const std::vector<Case> cases = {
      {"{transport: modbus}", "axes.x.drive.profile", "missing"},
      {"{transport: modbus, profile: cia402, hots: x}", "axes.x.drive.hots", "unknown key"},
      {"{transport: modbus, profile: nope}", "", "cannot open"},
      {"{transport: modbus, profile: cia402, host: 'h:99999'}", "axes.x.drive.host", "1..65535"},
      {"{transport: modbus, profile: cia402, host: h, plant: {kv: 1}}", "axes.x.drive.plant", "in-process"},
      {"{transport: modbus, profile: cia402, unit: 300}", "axes.x.drive.unit", "0..255"},
      {"{transport: modbus, profile: cia402, response_timeout: -1}", "axes.x.drive.response_timeout", "seconds"},
      {"{transport: modbus, profile: cia402, plant: {kv: -1}}", "axes.x.drive.plant.kv", "must be in (0, 10000]"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.yaml);
    RunHarness run;
    auto d = run.add(c.yaml);
    ASSERT_FALSE(d);
    if (*c.key) {
      EXPECT_EQ(d.error().key, c.key) << d.error().describe();
    }
    EXPECT_NE(d.error().describe().find(c.part), std::string::npos) << d.error().describe();
  }
}

TEST(ModbusTransport, ExampleScenarioDriveBlocksWork) {
  const YAML::Node doc = YAML::LoadFile("examples/modbus-demo.yaml");
  RunHarness run;
  run.env.source_file = "examples/modbus-demo.yaml";
  for (const auto& axis : doc["machine"]["axes"]) {
    ASSERT_EQ(axis["drive"]["transport"].as<std::string>(), "modbus");
    auto d = run.factory->make_drive(axis["name"].as<std::string>(), axis["drive"], run.env);
    ASSERT_TRUE(d) << d.error().describe();
    (*d)->request(DriveRequest::enable);
    run.drives.push_back(std::move(*d));
    run.commands.emplace_back();
  }
  ASSERT_EQ(run.drives.size(), 2u);
  ASSERT_TRUE(run.until(
      [&] {
        return run.drives[0]->feedback().state == DriveState::operation_enabled &&
               run.drives[1]->feedback().state == DriveState::operation_enabled;
      },
      20));
}

}  // namespace
}  // namespace hil::test
