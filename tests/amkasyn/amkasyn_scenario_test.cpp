// SPDX-License-Identifier: MIT
// The amkasyn-sf controller inside a run (bridge/runtime): a wrong DB is a configuration error
// naming the file, line and item (never a crash), a refused START reaches the run result as a
// device error with the MB 233 number, and the shipped SF files run from a scenario text.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "sim_registry.hpp"

namespace hil::runtime {
namespace {

std::expected<RunResult, ConfigError> run_text(const std::string& text) {
  auto s = parse_scenario(text, "examples/controllers/test.yaml");  // paths relative to the shipped files
  if (!s) return std::unexpected(s.error());
  static Scenario keep;
  keep = std::move(*s);
  return run_scenario(keep, hil::testing::sim_registry(), RunOptions{});
}

const std::string fipz_head = R"(
period: 1ms
controller:
  device: amkasyn-sf
  parameters: amkasyn-fipz-sf1.txt
  tables: "20=amkasyn-fipz-db20.txt, 21=amkasyn-fipz-db21.txt"
  aw1: S
machine:
  axes:
    - {name: S, drive: {transport: sim, kv: 200, feedforward: 1.0, velocity_lag: 0}}
)";

TEST(AmkasynScenario, AnSfCycleOtherThanId2IsTheProfilesErrorAtItsLine) {
  // No `cycle:`: ID 2 = 1 ms, but the file's DW3 = 4 (2 ms).
  const auto r = run_text(fipz_head);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().file, "examples/controllers/amkasyn-fipz-sf1.txt");
  EXPECT_EQ(r.error().line, 21);
  EXPECT_NE(r.error().key.find("DW3"), std::string::npos) << r.error().describe();
  EXPECT_NE(r.error().describe().find("ID 2"), std::string::npos) << r.error().describe();
}

TEST(AmkasynScenario, ShippedFipzRunsFromAScenarioText) {
  std::string text = fipz_head;
  text.replace(text.find("  aw1: S"), 8, "  aw1: S\n  cycle: 2ms");
  const auto r = run_text(text + R"(
io:
  - {pulse: "E 8.0", at: 100ms, width: 10ms}
program:
  - wait: 1500ms
expect:
  - {axis: S, position: 10000, tolerance: 0.5}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  EXPECT_EQ(r->controller, "amkasyn-sf");
  ASSERT_EQ(r->axes.size(), 1U);
  EXPECT_EQ(r->axes[0].units, "inc");
  EXPECT_TRUE(r->device_errors.empty());
}

TEST(AmkasynScenario, MissingTableAndUnknownAxisAreConfigurationErrors) {
  std::string text = fipz_head;
  text.replace(text.find("20=amkasyn-fipz-db20.txt, "), 26, "");
  text.replace(text.find("  aw1: S"), 8, "  aw1: S\n  cycle: 2ms");
  auto r = run_text(text);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().file, "examples/controllers/amkasyn-fipz-sf1.txt");
  EXPECT_EQ(r.error().key, "INIT DR6");
  EXPECT_NE(r.error().message.find("DB20"), std::string::npos) << r.error().describe();

  text = fipz_head;
  text.replace(text.find("  aw1: S"), 8, "  aw1: T\n  cycle: 2ms");
  r = run_text(text);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().describe().find("'T'"), std::string::npos) << r.error().describe();
}

const std::string apsf_head = R"(
period: 1ms
controller:
  device: amkasyn-sf
  parameters: amkasyn-apsf-sf0.txt
  tables: "20=amkasyn-apsf-db20.txt"
  cycle: 2ms
  aw1: S
  aw1_mode: 3C0043
  az1: P
machine:
  axes:
    - {name: P, drive: {transport: sim, kv: 200, feedforward: 1.0, velocity_lag: 0}}
    - {name: S, drive: {transport: sim, kv: 200, feedforward: 1.0, velocity_lag: 0}}
)";

TEST(AmkasynScenario, ApsfRunsTheScenariosFunctionBlock) {
  // Vector 6.13: S travels exactly P's increments (n = diff x 30000 / 2 in 0.0001 rpm), across the
  // 16-bit wrap of the AZ high word; MD24, the FB's own flag, survives the PLC's flag image.
  std::string text = apsf_head;
  text.replace(text.find("  cycle: 2ms"), 12, "  cycle: 2ms\n  fb: \"FB10=amkasyn-apsf-fb10.awl\"");
  const auto r = run_text(text + R"(
io:
  - {set: "E 8.0", at: 50ms}
program:
  - wait: 100ms
  - move_relative: {axis: P, distance: 40000, velocity: 40000, acceleration: 400000}
  - wait_until: {axis: S, in_position: true}
expect:
  - {axis: S, position: 40000, tolerance: 0.5}
  - {io: "A 8.0", state: true}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  EXPECT_TRUE(r->device_errors.empty());
}

TEST(AmkasynScenario, ApsfWithoutItsFunctionBlockRefusesStart) {
  const auto r = run_text(apsf_head + "program:\n  - wait: 50ms\n");
  ASSERT_TRUE(r) << r.error().describe();
  ASSERT_EQ(r->device_errors.size(), 1U);
  EXPECT_EQ(r->device_errors.front().code, "1");  // START with invalid parameters (DW4)
  EXPECT_NE(r->device_errors.front().text.find("not loaded"), std::string::npos) << r->device_errors.front().text;
}

TEST(AmkasynScenario, FunctionBlockErrorsNameTheFileAndLine) {
  const auto dir = std::filesystem::temp_directory_path() / "amkvec_fb_test";
  std::filesystem::create_directories(dir);
  const auto fb = dir / "bad.awl";
  std::ofstream(fb) << "FB10\n      L    EB 217\n      L    QQ 1\n      BE\n";
  std::string text = apsf_head;
  text.replace(text.find("  cycle: 2ms"), 12, "  cycle: 2ms\n  fb: \"10=" + fb.string() + "\"");
  auto r = run_text(text);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().file, fb.string());
  EXPECT_EQ(r.error().line, 3);
  EXPECT_EQ(r.error().key, "FB10");
  EXPECT_NE(r.error().message.find("QQ"), std::string::npos) << r.error().describe();

  for (const char* bad : {"64=x.awl", "10", "10=amkasyn-apsf-fb10.awl, FB10=amkasyn-apsf-fb10.awl", "10=nowhere.awl"}) {
    text = apsf_head;
    text.replace(text.find("  cycle: 2ms"), 12, std::string("  cycle: 2ms\n  fb: \"") + bad + "\"");
    r = run_text(text);
    ASSERT_FALSE(r) << bad;
    EXPECT_EQ(r.error().key, "controller.fb") << bad << ": " << r.error().describe();
  }
  std::filesystem::remove_all(dir);
}

TEST(AmkasynScenario, RefusedStartIsADeviceErrorOfTheRun) {
  auto r = run_text(R"(
period: 1ms
controller:
  device: amkasyn-sf
  parameters: amkasyn-fipw-sf0.txt
  tables: "16=amkasyn-fipw-refused-db16.txt, 17=amkasyn-fipw-db17.txt, 18=amkasyn-fipw-db18.txt"
  cycle: 2ms
  az1: M
  aw1: S
machine:
  axes:
    - {name: M, drive: {transport: sim}}
    - {name: S, drive: {transport: sim}}
program:
  - wait: 100ms
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_FALSE(r->ok) << "an unexpected device error fails the run";
  ASSERT_EQ(r->device_errors.size(), 1U);
  const auto& e = r->device_errors.front();
  EXPECT_EQ(e.axis, "S");
  EXPECT_EQ(e.category, "amkasyn-sf.sf_status");
  EXPECT_EQ(e.code, "1");
  EXPECT_NE(e.text.find("Tab0 value difference = 40000"), std::string::npos) << e.text;
  EXPECT_NE(e.text.find("amkasyn-fipw-sf0.txt"), std::string::npos) << e.text;
}

const std::string regl_head = R"(
period: 1ms
duration: 12ms
cut_off: expected
controller:
  device: amkasyn-sf
  parameters: amkasyn-regl-sf0.txt
  cycle: 1ms
  aw1: S
  aw1_mode: 3C0043
  resolution: 600000
machine:
  axes:
    - {name: S, drive: {transport: sim, kv: 0.000001, feedforward: 1.0, velocity_lag: 0, max_velocity: 100000000}}
expect:
  - {axis: S, position: 19875, at: 9ms, tolerance: 0.5}
)";

TEST(AmkasynScenario, ReglReadsTheAnalogInputOfTheScenario) {
  // Vector 6.9: F = 60 N (2108) gives y = 5100000, 5120000, 5140000, 5160000 from t = 4 ms (the
  // shipped amkasyn-regl.yaml); without the analog input message16 reads 0 (-2048 N): y = y_max +
  // n_command every cycle, and the position expectation fails.
  std::string text = regl_head;
  text.replace(text.find("  resolution"), 2, "  aw1_message16: \"0ms=2108\"\n  ");
  auto r = run_text(text);
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  r = run_text(regl_head);
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_FALSE(r->ok);
}

TEST(AmkasynScenario, AnalogInputErrorsNameTheFileLineAndKey) {
  std::string text = regl_head;
  text.replace(text.find("  resolution"), 2, "  aw1_message16: \"0ms=2108, 1ms\"\n  ");
  const auto r = run_text(text);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().file, "examples/controllers/test.yaml");
  EXPECT_EQ(r.error().key, "controller.aw1_message16");
  EXPECT_GT(r.error().line, 0);
  EXPECT_NE(r.error().message.find("'1ms': write TIME=WORD"), std::string::npos) << r.error().describe();
}

}  // namespace
}  // namespace hil::runtime
