// SPDX-License-Identifier: MIT
// The CLM1.4 on the controller runtime (issue 14): built from parameter and program files by the
// registry, its inputs and outputs on the runtime's IoImage, its axes the runtime's motion::Axis.
#include <gtest/gtest.h>

#include <array>

#include <filesystem>
#include <fstream>

#include "hil/controllers/clm14/runtime_controller.hpp"
#include "hil/controllers/io_address_clm.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace hil::controllers::clm14 {
namespace {

namespace hc = hil::controllers;
using namespace std::chrono_literals;

hc::BitAddress at(std::string_view s) {
  return hc::to_bit_address(hc::parse_clm_address(s).value());
}

TEST(ClmRuntime, RunsAProgramFromFilesOnTheRuntimesImageAndAxes) {
  const auto dir = std::filesystem::temp_directory_path() / "clm14_runtime_adapter";
  std::filesystem::create_directories(dir);
  {
    std::ofstream par(dir / "clm.par");
    par << "; hilbridge clm14 parameters\nB000 0 0 0\nB010 2.0\nB011 0000 0000 0\nB012 0000 0000\n"
           "A100 1 0 0 0 0\nA101 0010.00000\nA106 000100.000\nA107 000050.000\nA108 001000\nA109 000 000\n"
           "A110 0.000\nA119 01024 1024\nA120 0 0 00 1\n# K A124 00.00.0 +100 0$00\nA127 M2.00.0 0000.010\n";
    std::ofstream prg(dir / "clm.prg");
    prg << "; hilbridge clm14 program\n0000 AEA Q1.00.3 1\n0001 PSI 1 +000025.000 999\n0002 AEA Q1.00.3 0\n"
           "0003 JST 0000\n";
  }
  hc::ControllerRegistry registry;
  register_clm14(registry);
  hc::ControllerSpec spec;
  spec.device = "clm14";
  spec.parameters = dir / "clm.par";
  spec.programs = {dir / "clm.prg"};
  auto c = registry.create(spec);
  ASSERT_TRUE(c) << c.error().describe();
  auto& ctl = **c;
  ASSERT_EQ(ctl.axis_specs().size(), 1u);
  EXPECT_EQ(ctl.cycle_period(), 2ms);
  mocks::SimDriveConfig dc;
  dc.plant.kv_per_s = 200.0;
  dc.plant.velocity_feedforward = 1.0;
  motion::Axis axis(ctl.axis_specs()[0].config, std::make_unique<mocks::SimDrive>(dc));
  std::array<motion::Axis*, 1> axes{&axis};
  ASSERT_TRUE(ctl.bind_axes(axes));
  auto& io = ctl.io();
  io.set(at("I0.00.2"), true);  // E-Stop closed
  io.set(at("I0.00.4"), true);  // Immediate Stop closed
  io.set(at("I0.00.5"), true);  // Enable axis 1
  TimePoint now{};
  const auto step = [&] {
    now += 2ms;
    axis.update(CycleTime{now, 2ms});
    ctl.step(CycleTime{now, 2ms});
  };
  for (int i = 0; i < 20; ++i) step();
  EXPECT_TRUE(io.get(at("Q0.00.3"))) << "drive enable";
  io.set(at("I0.00.1"), true);  // Automatic
  step();
  io.set(at("I0.00.3"), true);  // Start
  step();
  io.set(at("I0.00.3"), false);
  step();
  EXPECT_TRUE(io.get(at("Q1.00.3")));
  EXPECT_TRUE(io.get(at("Q0.01.1"))) << "Run Task";
  for (int i = 0; i < 2000 && io.get(at("Q0.01.1")); ++i) step();
  EXPECT_FALSE(io.get(at("Q1.00.3")));
  EXPECT_NEAR(axis.status().position, 25.0, 0.011);
  EXPECT_TRUE(ctl.resolve_bit("M2.00.0").has_value());
  EXPECT_TRUE(ctl.errors().active().empty());

  // The CLM's values by name, as a scenario's `expect: {controller: NAME, value: V}` reads them.
  const auto value = [&](std::string_view name) {
    auto h = ctl.resolve_value(name);
    EXPECT_TRUE(h.has_value()) << name << ": " << (h ? "" : h.error());
    return h ? ctl.value(*h) : -1.0;
  };
  EXPECT_EQ(value("task1.line"), 0.0) << "JST 0000";
  EXPECT_EQ(value("run"), 2.0) << "stopped by JST";
  EXPECT_EQ(value("mode"), 2.0) << "Automatic";
  EXPECT_NEAR(value("axis1.position"), 25.0, 0.011);
  EXPECT_NEAR(value("V100"), 25.0, 0.011);
  EXPECT_EQ(value("V002"), 0.0);
  EXPECT_EQ(value("error"), 0.0);
  EXPECT_EQ(value("Q0.00"), static_cast<double>(ctl.io().get(hc::ByteAddress{hc::IoArea::output, 0})));
  EXPECT_EQ(value("Q1.00"), 0.0);
  EXPECT_EQ(value("task1.depth"), 0.0);
  ASSERT_TRUE(dynamic_cast<RuntimeController&>(ctl).model().set_variable(600, -87654321654321));
  EXPECT_EQ(value("V600"), -87654321.654321) << "exact to the millionth";
  for (const auto* bad : {"V6000", "V60", "counter.0001", "counter.3000", "task6.line", "task1.pc", "axis2.position",
                          "axis1.speed", "Q9.00", "nonsense"}) {
    auto h = ctl.resolve_value(bad);
    ASSERT_FALSE(h.has_value()) << bad;
    EXPECT_NE(h.error().find("the CLM shows: V000..V999"), std::string::npos) << h.error();
  }
  EXPECT_NE(ctl.resolve_value("counter.0001").error().find("line 0001 of the program holds no COU or BAC"),
            std::string::npos);
}

TEST(ClmRuntime, BadProgramFileNamesTheDevicesError) {
  const auto dir = std::filesystem::temp_directory_path() / "clm14_runtime_adapter_bad";
  std::filesystem::create_directories(dir);
  {
    std::ofstream par(dir / "clm.par");
    par << "B000 0 0 0\n";
    std::ofstream prg(dir / "clm.prg");
    prg << "0000 POI 7 +000010.000 999\n";
  }
  hc::ControllerRegistry registry;
  register_clm14(registry);
  hc::ControllerSpec spec;
  spec.device = "clm14";
  spec.parameters = dir / "clm.par";
  spec.programs = {dir / "clm.prg"};
  auto c = registry.create(spec);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().describe().find("CLM error 16"), std::string::npos) << c.error().describe();
}

TEST(ClmRuntime, MasterEncoderKeyDeclaresTheMaterialAxisAndTheFlyingCutoffCuts) {
  const auto dir = std::filesystem::temp_directory_path() / "clm14_runtime_master";
  std::filesystem::create_directories(dir);
  {
    std::ofstream par(dir / "clm.par");
    par << "B000 0 0 0\nB010 2.0\nB011 0000 0000 0\nB012 0000 0000\nA100 1 5 0 0 0\nA101 0010.00000\nA106 "
           "000100.000\nA108 001000\nA109 000 000\n"
           "A119 01024 1024\nA127 M2.00.0 0000.010\nC000 01250 0000\nC001 5 0 00 0 0 0\nC002 0020.00000\n";
    std::ofstream prg(dir / "clm.prg");
    prg << "0000 NOP\n0001 LML 1 000050.000\n0002 AEA Q1.00.0 1\n0003 WAI 00.050\n0004 AEA Q1.00.0 0\n0005 EOS\n"
           "0006 JMP 0001\n";
  }
  hc::ControllerRegistry registry;
  register_clm14(registry);
  hc::ControllerSpec spec;
  spec.device = "clm14";
  spec.parameters = dir / "clm.par";
  spec.programs = {dir / "clm.prg"};
  spec.options.emplace("master_encoder", "M");
  auto c = registry.create(spec);
  ASSERT_TRUE(c) << c.error().describe();
  auto& ctl = **c;
  ASSERT_EQ(ctl.axis_specs().size(), 2u);
  EXPECT_EQ(ctl.axis_specs()[1].name, "M");
  EXPECT_EQ(ctl.axis_specs()[1].config.inc_per_unit.num * 20, ctl.axis_specs()[1].config.inc_per_unit.den * 5000)
      << "1250 x 4 counts per 20 IU";
  mocks::SimDriveConfig dc;
  dc.plant.kv_per_s = 200.0;
  dc.plant.velocity_feedforward = 1.0;
  motion::Axis carriage(ctl.axis_specs()[0].config, std::make_unique<mocks::SimDrive>(dc));
  motion::Axis material(ctl.axis_specs()[1].config, std::make_unique<mocks::SimDrive>(dc));
  std::array<motion::Axis*, 2> axes{&carriage, &material};
  ASSERT_TRUE(ctl.bind_axes(axes));
  auto& io = ctl.io();
  io.set(at("I0.00.2"), true);
  io.set(at("I0.00.4"), true);
  io.set(at("I0.00.5"), true);
  TimePoint now{};
  const auto step = [&] {
    now += 2ms;
    carriage.update(CycleTime{now, 2ms});
    material.update(CycleTime{now, 2ms});
    ctl.step(CycleTime{now, 2ms});
  };
  ASSERT_FALSE(material.enable());
  for (int i = 0; i < 20; ++i) step();
  io.set(at("I0.00.1"), true);  // Automatic: the flying cutoff starts its program at once
  step();
  motion::Limits l;
  l.velocity = 40.0;
  l.acceleration = 400.0;
  ASSERT_FALSE(material.move_velocity(40.0, l));
  int cuts = 0;
  bool knife = false;
  for (int i = 0; i < 4000 && cuts < 3; ++i) {
    step();
    const bool q = io.get(at("Q1.00.0"));
    cuts += q && !knife;
    knife = q;
  }
  EXPECT_EQ(cuts, 3) << "three parts of 50 IU in 4000 cycles at 40 IU/s";
  auto& model = static_cast<RuntimeController&>(ctl).model();
  EXPECT_NEAR(model.last_cut_point(), 150.0, 0.0045);
  EXPECT_EQ(model.error(), 0) << model.error_message();
  EXPECT_TRUE(ctl.errors().active().empty());
}

TEST(ClmRuntime, UnknownControllerKeyAndUnusedEncoderAreConfigErrors) {
  const auto dir = std::filesystem::temp_directory_path() / "clm14_runtime_keys";
  std::filesystem::create_directories(dir);
  {
    std::ofstream par(dir / "clm.par");
    par << "B000 0 0 0\nC002 0000.00000\n";
    std::ofstream prg(dir / "clm.prg");
    prg << "0000 NOP\n";
  }
  hc::ControllerRegistry registry;
  register_clm14(registry);
  hc::ControllerSpec spec;
  spec.device = "clm14";
  spec.parameters = dir / "clm.par";
  spec.programs = {dir / "clm.prg"};
  spec.options.emplace("master_encodr", "M");
  auto c = registry.create(spec);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().describe().find("known: master_encoder"), std::string::npos) << c.error().describe();
  spec.options.clear();
  spec.options.emplace("master_encoder", "M");
  c = registry.create(spec);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().describe().find("C002 = 0"), std::string::npos) << c.error().describe();
  // homing / markerN / master_encoder2: their values are checked, errors name the key.
  const std::array<std::array<const char*, 3>, 4> bad{{{"homing", "both", "controller.homing"},
                                                       {"marker1", "I1.05", "controller.marker1"},
                                                       {"marker5", "0", "controller.marker5"},
                                                       {"master_encoder2", "W", "C006 = 0"}}};
  for (const auto& [key, value, expected] : bad) {
    spec.options.clear();
    spec.options.emplace(key, value);
    c = registry.create(spec);
    ASSERT_FALSE(c) << key;
    EXPECT_NE(c.error().describe().find(expected), std::string::npos) << c.error().describe();
  }
  spec.options.clear();
  spec.options.emplace("homing", "drive");
  spec.options.emplace("marker1", "I1.05.0");
  spec.options.emplace("marker2", "-1024");
  EXPECT_TRUE(registry.create(spec).has_value());
  // test_speed_step: a step 0..31, and only with the flying cutoff's test mode
  spec.options.clear();
  spec.options.emplace("test_speed_step", "32");
  c = registry.create(spec);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().describe().find("0..31"), std::string::npos) << c.error().describe();
  spec.options.clear();
  spec.options.emplace("test_speed_step", "10");
  c = registry.create(spec);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().describe().find("test mode"), std::string::npos) << c.error().describe();
  // wheel_window: the unit of the Ax16 windows, iu or percent
  spec.options.clear();
  spec.options.emplace("wheel_window", "mm");
  c = registry.create(spec);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().describe().find("controller.wheel_window"), std::string::npos) << c.error().describe();
  for (const char* unit : {"iu", "percent"}) {
    spec.options.clear();
    spec.options.emplace("wheel_window", unit);
    EXPECT_TRUE(registry.create(spec).has_value()) << unit;
  }
}

}  // namespace
}  // namespace hil::controllers::clm14
