// SPDX-License-Identifier: MIT
// The IP247 module on the controller runtime, end to end through the scenario runner on virtual
// time: the shipped NPV program (vectors ip247.md 11) on the sim transport and on step/dir mock
// lines (verified edge streams) gives the same positions; the PLC interface DB (plc: steps), the
// data-word interface of the controller, and the configuration errors of the module and of the
// plc: keys (file, line, key).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <unistd.h>

#include "hil/controllers/s5/ip247_controller.hpp"
#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/mocks/sim_transport.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "ip247_program_rig.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path examples = fs::absolute("examples/controllers");

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Writes `text` as a scenario next to a copy of the example's data files; returns its path.
fs::path scenario_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("hil_ip247_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const auto* f : {"ip247-md-linear.s5db", "ip247-npv-main.txt", "ip247-npv-sub.txt"})
    fs::copy_file(examples / f, dir / f, fs::copy_options::overwrite_existing);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

hil::TransportRegistry transports() {
  hil::TransportRegistry registry;
  registry.add("sim", [] { return hil::mocks::make_sim_transport(); });
  registry.add("stepdir", [] { return std::make_unique<hil::drives::stepdir::StepDirTransportFactory>(); });
  return registry;
}

hil::runtime::RunResult run(const fs::path& file) {
  auto scenario = hil::runtime::load_scenario(file);
  EXPECT_TRUE(scenario) << (scenario ? "" : scenario.error().describe());
  if (!scenario) return {};
  const hil::TransportRegistry registry = transports();
  hil::runtime::RunOptions opts;
  opts.virtual_time = true;
  opts.verify_steps = true;
  auto result = hil::runtime::run_scenario(*scenario, registry, opts);
  EXPECT_TRUE(result) << (result ? "" : result.error().describe());
  return result ? *result : hil::runtime::RunResult{};
}

std::string load_error(const std::string& text) {
  auto s = hil::runtime::load_scenario(scenario_file("bad.yaml", text));
  if (s) {
    // Errors found when the machine is built (controller, plc operands) come from the runner.
    const hil::TransportRegistry registry = transports();
    hil::runtime::RunOptions opts;
    opts.virtual_time = true;
    auto r = hil::runtime::run_scenario(*s, registry, opts);
    return r ? "" : r.error().describe();
  }
  return s.error().describe();
}

const char* head = R"(name: t
period: 1ms
controller:
  device: ip247
  parameters: ip247-md-linear.s5db
  programs: [ip247-npv-main.txt, ip247-npv-sub.txt]
machine:
  axes:
    - name: "1"
      drive: {transport: sim}
)";

}  // namespace

TEST(Ip247Controller, NpvProgramGivesTheSamePositionsOnSimAndStepDir) {
  const std::string sim = slurp(examples / "ip247-npv.yaml");
  auto r_sim = run(scenario_file("npv-sim.yaml", sim));
  for (const auto& f : r_sim.failures) ADD_FAILURE() << f;
  ASSERT_TRUE(r_sim.ok);
  // The same scenario with the axis on a step/dir stage (mock lines), following the module's pulses.
  const std::string stepdir = std::regex_replace(
      sim, std::regex(R"(drive: \{transport: sim[^}]*\})"),
      "drive: {transport: stepdir, profile: motion, fmax_hz: 20000, fss_hz: 500, accel_hz_per_s: 200000, "
      "pulse_us: 10}");
  ASSERT_NE(stepdir, sim);
  auto r_sd = run(scenario_file("npv-stepdir.yaml", stepdir));
  for (const auto& f : r_sd.failures) ADD_FAILURE() << f;
  ASSERT_TRUE(r_sd.ok);
  ASSERT_EQ(r_sim.axes.size(), 1U);
  ASSERT_EQ(r_sd.axes.size(), 1U);
  // Open loop: the step/dir axis is exactly where the module's pulses put it (0 mm); the simulated
  // plant within a pulse of it.
  EXPECT_EQ(r_sd.axes[0].final_position, 0.0);
  EXPECT_NEAR(r_sim.axes[0].final_position, r_sd.axes[0].final_position, 0.01);
  bool verified = false;
  for (const auto& rep : r_sd.reports)
    for (const auto& l : rep.report.lines) {
      EXPECT_EQ(l.find("VIOLATION"), std::string::npos) << l;
      verified = verified || l.find("timing rules held") != std::string::npos;
    }
  EXPECT_TRUE(verified);
}

TEST(Ip247Controller, SameProgramSamePositionsOnMockLinesAndSim) {
  // The program the kernel test runs on gpio-sim (test_ip247_gpiosim.cpp), here on mock step/dir
  // lines (verified edge streams) and on the sim plant.
  const auto lines = ip247_rig::run(
      "mock",
      "{transport: stepdir, profile: motion, fmax_hz: 20000, fss_hz: 500, accel_hz_per_s: 200000, pulse_us: 10}");
  for (const auto& f : lines.failures) ADD_FAILURE() << f;
  EXPECT_TRUE(lines.ok);
  EXPECT_TRUE(lines.verified);
  for (const auto& l : lines.report) EXPECT_EQ(l.find("VIOLATION"), std::string::npos) << l;
  EXPECT_EQ(lines.final_position_mm, 2.5);
  const auto sim = ip247_rig::run("sim", "{transport: sim, kv: 1000, feedforward: 1.0, velocity_lag: 0}");
  for (const auto& f : sim.failures) ADD_FAILURE() << f;
  EXPECT_TRUE(sim.ok);
  EXPECT_NEAR(sim.final_position_mm, 2.5, 0.01);
}

TEST(Ip247Controller, DataWordsOfTheInterfaceAndTheImages) {
  hil::controllers::ControllerSpec spec;
  spec.device = "ip247";
  spec.parameters = examples / "ip247-md-linear.s5db";
  spec.programs = {examples / "ip247-syntax-3.txt", examples / "ip247-syntax-4.txt"};
  spec.options = {{"interface_db", "12"}};
  auto c = hil::controllers::s5::Ip247Controller::create(spec);
  ASSERT_TRUE(c) << c.error().describe();
  auto& ctl = **c;
  // Interface DB12: status words from the start (attributes: finished, mm, reference missing).
  EXPECT_EQ(ctl.read_data_word(12, 12).value(), 0xA200);
  ASSERT_TRUE(ctl.write_data_word(12, 0, 0x0501));
  EXPECT_EQ(ctl.read_data_word(12, 0).value(), 0x0501);
  // The image's data area holds it: DB bits are I/O signals.
  const auto bit = ctl.resolve_bit("DB12 D 0.8");
  ASSERT_TRUE(bit) << bit.error();
  EXPECT_TRUE(ctl.io().get(*bit));
  // VP DB 3 refused (syntax error 6 in N20), VP DB 4 accepted, MD DB 20 readable, not writable.
  EXPECT_EQ(ctl.read_data_word(3, 3).value(), 6);
  EXPECT_EQ(ctl.read_data_word(3, 4).value(), 20);
  EXPECT_EQ(ctl.read_data_word(4, 3).value(), 0);
  EXPECT_EQ(ctl.read_data_word(20, 0).value(), 70);
  EXPECT_EQ(ctl.read_data_word(20, 2).value(), 0x4214);
  EXPECT_FALSE(ctl.write_data_word(20, 5, 1));
  EXPECT_FALSE(ctl.write_data_word(4, 5, 1));
  const auto missing = ctl.read_data_word(30, 0);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().find("no DB30"), std::string::npos) << missing.error();
  EXPECT_TRUE(ctl.read_data_word(12, 74));  // 3 axis DBs of 20 words and the data-job block
  EXPECT_FALSE(ctl.read_data_word(12, 75));
}

TEST(Ip247Controller, OneMachineAxisPerMachineDataSet) {
  hil::controllers::ControllerSpec spec;
  spec.device = "ip247";
  spec.parameters = examples / "ip247-md-two-axes.s5db";
  auto c = hil::controllers::s5::Ip247Controller::create(spec);
  ASSERT_TRUE(c) << c.error().describe();
  auto& ctl = **c;
  ASSERT_EQ(ctl.axis_specs().size(), 2U);
  EXPECT_EQ(ctl.axis_specs()[0].name, "1");
  EXPECT_EQ(ctl.axis_specs()[1].name, "2");
  // Axis k's inputs and outputs are image byte k-1; its axis DB starts at DW 20(k-1).
  const auto bit = ctl.resolve_bit("limit_minus_2");
  ASSERT_TRUE(bit) << bit.error();
  EXPECT_EQ(bit->byte, 1U);
  EXPECT_EQ(bit->bit, 0);
  EXPECT_EQ(ctl.read_data_word(10, 12).value(), 0xA200);  // axis 1: finished, mm, reference missing
  EXPECT_EQ(ctl.read_data_word(10, 32).value(), 0xA200);  // axis 2
  EXPECT_EQ(ctl.read_data_word(10, 52).value(), 0xE000);  // axis 3: no MD (40h)
  EXPECT_EQ(ctl.read_data_word(21, 3).value(), 0x0002);   // MD DB21 = axis 2
  EXPECT_EQ(ctl.trace_signals().size(), 6U);
  EXPECT_EQ(ctl.trace_signals()[3], "actual_value_BU_2");
  // 'axis' names the machine axis of a one-axis module only.
  spec.options = {{"axis", "X"}};
  auto e = hil::controllers::s5::Ip247Controller::create(spec);
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().describe().find("one-axis module"), std::string::npos) << e.error().describe();
  // Two sets for one axis.
  std::string twice = slurp(examples / "ip247-md-two-axes.s5db");
  twice.replace(twice.find("3: KH = 0002"), 12, "3: KH = 0001");
  const fs::path dup = scenario_file("dup.s5db", twice);
  spec.options.clear();
  spec.parameters = dup;
  e = hil::controllers::s5::Ip247Controller::create(spec);
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().describe().find("DB20 and DB21 are both MD of axis 1"), std::string::npos)
      << e.error().describe();
}

TEST(Ip247Controller, ModulesByTheModuleNumberOfTheMachineData) {
  hil::controllers::ControllerSpec spec;
  spec.device = "ip247";
  spec.parameters = examples / "ip247-md-two-modules.s5db";
  spec.options = {{"tile", "8"}};
  auto c = hil::controllers::s5::Ip247Controller::create(spec);
  ASSERT_TRUE(c) << c.error().describe();
  auto& ctl = static_cast<hil::controllers::s5::Ip247Controller&>(**c);
  ASSERT_EQ(ctl.module_count(), 2U);
  ASSERT_EQ(ctl.axis_specs().size(), 2U);
  EXPECT_EQ(ctl.axis_specs()[0].name, "m0a1");
  EXPECT_EQ(ctl.axis_specs()[1].name, "m1a1");
  // Module k: SSNR base tile + 4k, SYS-ID = the MD's module number, interface DB 10 + k, I/O bytes 3k..
  EXPECT_EQ(ctl.module(0).base_tile(), 8);
  EXPECT_EQ(ctl.module(1).base_tile(), 12);
  EXPECT_EQ(ctl.module(1).sysid().module, 1);
  EXPECT_EQ(ctl.module(0).md_db(1), 20);
  EXPECT_EQ(ctl.module(1).md_db(1), 21);
  ASSERT_EQ(ctl.data_blocks().size(), 2U);
  EXPECT_EQ(ctl.data_blocks()[1].number, 11);
  const auto bit = ctl.resolve_bit("limit_plus_m1a1");
  ASSERT_TRUE(bit) << bit.error();
  EXPECT_EQ(bit->byte, 3U);
  EXPECT_EQ(bit->bit, 1);
  EXPECT_EQ(ctl.read_data_word(11, 12).value(), 0xA200);  // module 1 axis 1: finished, mm, reference missing
  EXPECT_EQ(ctl.read_data_word(11, 32).value(), 0xE000);  // module 1 axis 2: no MD
  EXPECT_EQ(ctl.read_data_word(21, 3).value(), 0x0101);   // MD DB21 = module 1, axis 1
  // With several modules the SYS-ID is the MD's module number: sysid_module is refused.
  spec.options = {{"sysid_module", "1"}};
  auto e = hil::controllers::s5::Ip247Controller::create(spec);
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().describe().find("drop sysid_module"), std::string::npos) << e.error().describe();
  // The interface DB of module 1 (DB 11) must not be an MD or program DB number.
  spec.options = {{"interface_db", "20"}};
  e = hil::controllers::s5::Ip247Controller::create(spec);
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().describe().find("DB20 is the machine-data DB"), std::string::npos) << e.error().describe();
}

TEST(Ip247Controller, ConfigurationErrorsNameFileLineAndKey) {
  // plc: keys
  auto e = load_error(std::string(head) + "program:\n  - plc: {write: {db: 10, dw: 0, valu: 1}}\n");
  EXPECT_NE(e.find(":12"), std::string::npos) << e;
  EXPECT_NE(e.find("program[0].plc.write"), std::string::npos) << e;
  EXPECT_NE(e.find("valu"), std::string::npos) << e;
  e = load_error(std::string(head) + "program:\n  - plc: {wait: {db: 10, dw: 4, bit: 16}}\n");
  EXPECT_NE(e.find("program[0].plc.wait.bit"), std::string::npos) << e;
  e = load_error(std::string(head) + "program:\n  - plc: {write: {db: 10, dw: 0, value: 0x10000}}\n");
  EXPECT_NE(e.find("program[0].plc.write.value"), std::string::npos) << e;
  e = load_error(std::string(head) + "program:\n  - plc: {write: {db: 10, dw: 0, value: 1}, wait: {db: 10, dw: 0}}\n");
  EXPECT_NE(e.find("does one thing"), std::string::npos) << e;
  e = load_error(std::string(head) + "program:\n  - plc: {wait: {db: 10, dw: 4, value: 1, state: true}}\n");
  EXPECT_NE(e.find("'state' belongs to 'bit'"), std::string::npos) << e;
  // a DB the module does not have: found before the run, at the step's line
  e = load_error(std::string(head) + "program:\n  - wait: 1ms\n  - plc: {expect: {db: 77, dw: 0, value: 1}}\n");
  EXPECT_NE(e.find(":13"), std::string::npos) << e;
  EXPECT_NE(e.find("no DB77"), std::string::npos) << e;
  e = load_error(std::string(head) + "program:\n  - plc: {write: {db: 1, dw: 0, value: 1}}\n");
  EXPECT_NE(e.find("not written word by word"), std::string::npos) << e;
  // without a controller
  e = load_error(
      "name: t\nmachine:\n  axes:\n    - name: x\n      inc_per_unit: 1\n      limits: {velocity: 1, "
      "acceleration: 1}\n      drive: {transport: sim}\nprogram:\n  - plc: {wait: {db: 10, dw: 4, bit: 0}}\n");
  EXPECT_NE(e.find("add a 'controller:' block"), std::string::npos) << e;
  // the module's own keys
  std::string bad = head;
  bad.insert(bad.find("machine:"), "  interface_db: 20\n");
  e = load_error(bad);
  EXPECT_NE(e.find("machine-data DB"), std::string::npos) << e;
  bad = head;
  bad.insert(bad.find("machine:"), "  interfac_db: 11\n");
  e = load_error(bad);
  EXPECT_NE(e.find("controller.interfac_db"), std::string::npos) << e;
  bad = head;
  bad.insert(bad.find("machine:"), "  interface_db: 1\n");  // program 1 is DB1
  e = load_error(bad);
  EXPECT_NE(e.find("program 1 would be DB1"), std::string::npos) << e;
  // a drive that plans its own trajectory cannot follow the module's pulses
  bad = head;
  bad.replace(bad.find("drive: {transport: sim}"), 23,
              "drive: {transport: stepdir, profile: ip247, fmax_hz: 20000, fss_hz: 500, accel_hz_per_s: 200000, "
              "pulse_us: 10}");
  e = load_error(bad);
  EXPECT_NE(e.find("cyclic drive"), std::string::npos) << e;
  const fs::path nohead = scenario_file("nohead.txt", "N10 X1 F100\nN20 M02\n");
  bad = head;
  bad.replace(bad.find("[ip247-npv-main.txt, ip247-npv-sub.txt]"), 39, nohead.filename().string());
  e = load_error(bad);
  EXPECT_NE(e.find("nohead.txt:1"), std::string::npos) << e;
  EXPECT_NE(e.find("program header"), std::string::npos) << e;
}
