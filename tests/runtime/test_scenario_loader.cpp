// SPDX-License-Identifier: MIT
// Scenario loader: every key of a full file lands where it should; bad files give ConfigErrors
// naming file, line, key path and what was expected; unknown keys are errors.
#include <gtest/gtest.h>

#include "hil/runtime/scenario_loader.hpp"

using namespace std::chrono_literals;
using namespace hil::runtime;

namespace {

const std::string data = "tests/runtime/data/";  // ctest runs from the source root

std::string axes_header() {
  return "machine:\n"
         "  axes:\n"
         "    - name: x\n"
         "      inc_per_unit: 1000\n"
         "      limits: {velocity: 100, acceleration: 1000}\n"
         "      drive: {transport: sim}\n";
}

hil::ConfigError error_of(const std::string& text) {
  auto r = parse_scenario(text, "t.yaml");
  EXPECT_FALSE(r.has_value()) << "expected a ConfigError for:\n" << text;
  return r ? hil::ConfigError{} : r.error();
}

}  // namespace

TEST(ScenarioLoader, FullFileEveryKey) {
  auto r = load_scenario(data + "minimal.yaml");
  ASSERT_TRUE(r.has_value()) << r.error().describe();
  const Scenario& s = *r;
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.description, "every key once");
  EXPECT_EQ(s.period, 500us);
  EXPECT_EQ(s.duration, 3s);
  EXPECT_TRUE(s.cut_off_expected);
  EXPECT_EQ(s.timeout, 10s);
  ASSERT_EQ(s.axes.size(), 2u);
  const AxisSpec& x = s.axes[0];
  EXPECT_EQ(x.name, "x");
  EXPECT_EQ(x.units, "mm");
  EXPECT_EQ(x.inc_per_unit_num, 4096);
  EXPECT_EQ(x.inc_per_unit_den, 5);
  EXPECT_FALSE(x.rotary);
  EXPECT_DOUBLE_EQ(x.max_velocity, 100);
  EXPECT_DOUBLE_EQ(x.max_acceleration, 1000);
  EXPECT_DOUBLE_EQ(x.max_jerk, 20000);
  EXPECT_DOUBLE_EQ(x.quick_stop_deceleration, 5000);
  EXPECT_DOUBLE_EQ(x.jog_velocity, 5);
  EXPECT_EQ(x.soft_limit_min, -5.0);
  EXPECT_EQ(x.soft_limit_max, 200.0);
  EXPECT_DOUBLE_EQ(x.backlash, 0.02);
  EXPECT_TRUE(x.following_error_dynamic);
  EXPECT_DOUBLE_EQ(x.following_error_kv_per_s, 30);
  EXPECT_DOUBLE_EQ(x.following_error_min, 0.1);
  EXPECT_DOUBLE_EQ(x.following_error_max, 2);
  EXPECT_DOUBLE_EQ(x.standstill_window, 0.05);
  EXPECT_DOUBLE_EQ(x.in_position_window, 0.01);
  EXPECT_EQ(x.in_position_timeout, 300ms);
  EXPECT_EQ(x.enable_timeout, 1s);
  EXPECT_EQ(x.feedback_timeout, 20ms);
  EXPECT_EQ(x.fault_reaction, FaultReaction::stop);
  EXPECT_EQ(x.transport, "sim");
  EXPECT_EQ(x.drive["extra_key_for_the_factory"].as<int>(), 1);
  const AxisSpec& c = s.axes[1];
  EXPECT_TRUE(c.rotary);
  EXPECT_EQ(c.units, "deg");
  EXPECT_DOUBLE_EQ(c.modulo, 360);
  EXPECT_EQ(c.inc_per_unit_num, 125);
  EXPECT_EQ(c.inc_per_unit_den, 10);
  EXPECT_DOUBLE_EQ(c.max_jerk, 0);  // trapezoidal
  EXPECT_DOUBLE_EQ(c.following_error_window, 1.5);
  EXPECT_DOUBLE_EQ(c.quick_stop_deceleration, 4 * 360.0);

  ASSERT_EQ(s.program.size(), 16u);
  EXPECT_EQ(std::get<EnableStep>(s.program[0].action).axes, (std::vector<std::string>{"x", "c"}));
  const auto& m = std::get<MoveAbsoluteStep>(s.program[1].action);
  EXPECT_EQ(m.axis, "x");
  EXPECT_DOUBLE_EQ(m.position, 100);
  EXPECT_EQ(m.limits.velocity, 50.0);
  EXPECT_EQ(m.limits.acceleration, 500.0);
  EXPECT_EQ(m.limits.jerk, 0.0);
  EXPECT_EQ(s.program[1].timeout, 5s);
  EXPECT_EQ(s.program[1].source.line, 33);
  EXPECT_EQ(s.program[1].source.path, "program[1]");
  const auto& mc = std::get<MoveAbsoluteStep>(s.program[2].action);
  EXPECT_EQ(mc.direction, MoveDirection::negative);
  EXPECT_EQ(s.program[2].at, 1500ms);
  EXPECT_FALSE(s.program[2].wait);
  EXPECT_DOUBLE_EQ(std::get<MoveRelativeStep>(s.program[3].action).distance, -10);
  EXPECT_DOUBLE_EQ(std::get<MoveVelocityStep>(s.program[4].action).velocity, -30);
  const auto& j = std::get<JogStep>(s.program[5].action);
  EXPECT_FALSE(j.positive);
  EXPECT_EQ(j.duration, 250ms);
  EXPECT_EQ(std::get<WaitStep>(s.program[6].action).duration, 100ms);
  EXPECT_EQ(std::get<WaitInPositionStep>(s.program[7].action).axes, (std::vector<std::string>{"x"}));
  const auto& w = std::get<WaitUntilStep>(s.program[8].action).condition;
  EXPECT_EQ(w.kind, Condition::Kind::compare);
  EXPECT_EQ(w.quantity, Quantity::position);
  EXPECT_EQ(w.comparison, Comparison::below);
  EXPECT_DOUBLE_EQ(w.value, 95);
  EXPECT_EQ(std::get<WaitUntilStep>(s.program[9].action).condition.state, "standstill");
  EXPECT_EQ(std::get<WaitUntilStep>(s.program[10].action).condition.kind, Condition::Kind::fault);
  EXPECT_EQ(std::get<WaitUntilStep>(s.program[10].action).condition.fault_code, "");
  const auto& inj = std::get<InjectFaultStep>(s.program[11].action);
  EXPECT_EQ(inj.fault, "encoder");
  EXPECT_FALSE(inj.active);
  EXPECT_EQ(std::get<ParallelStep>(s.program[12].action).steps.size(), 2u);
  EXPECT_EQ(std::get<HomeStep>(s.program[13].action).axes, (std::vector<std::string>{"x"}));
  EXPECT_EQ(std::get<ResetStep>(s.program[14].action).axes.size(), 2u);
  EXPECT_EQ(std::get<DisableStep>(s.program[15].action).axes.size(), 2u);

  ASSERT_EQ(s.expectations.size(), 7u);  // the [x, c] entry expands to two
  const auto& p = std::get<PositionExpectation>(s.expectations[0].kind);
  EXPECT_DOUBLE_EQ(p.value, 90);
  EXPECT_DOUBLE_EQ(p.tolerance, 0.01);
  EXPECT_EQ(p.at, 2500ms);
  EXPECT_EQ(s.expectations[1].axis, "x");
  EXPECT_EQ(s.expectations[2].axis, "c");
  EXPECT_TRUE(std::holds_alternative<NoFaultExpectation>(s.expectations[2].kind));
  EXPECT_EQ(std::get<FaultExpectation>(s.expectations[3].kind).code, "cia402:0x7305");
  EXPECT_EQ(std::get<FaultExpectation>(s.expectations[3].kind).by, 2s);
  EXPECT_EQ(std::get<StateExpectation>(s.expectations[4].kind).state, "disabled");
  EXPECT_DOUBLE_EQ(std::get<MaxFollowingErrorExpectation>(s.expectations[5].kind).value, 0.5);
  EXPECT_EQ(std::get<PositionExpectation>(s.expectations[6].kind).by, 3s);
  // Defaulted tolerance comes from the axis' in_position window.
  EXPECT_DOUBLE_EQ(std::get<PositionExpectation>(s.expectations[6].kind).tolerance, 0.01);
}

struct BadFile {
  const char* file;
  int line;
  const char* key;
  const char* message_part;
};

// gtest prints the parameter into the ctest name; without this it would be the raw bytes of the
// struct (pointers included), a name that changes from build to build.
void PrintTo(const BadFile& b, std::ostream* os) {
  *os << b.file;
}

class ScenarioLoaderBadFile : public ::testing::TestWithParam<BadFile> {};

TEST_P(ScenarioLoaderBadFile, NamesFileLineKeyAndExpectation) {
  const BadFile& b = GetParam();
  const std::string path = data + "bad/" + b.file;
  auto r = load_scenario(path);
  ASSERT_FALSE(r.has_value());
  const hil::ConfigError& e = r.error();
  EXPECT_EQ(e.file, path);
  EXPECT_EQ(e.line, b.line) << e.describe();
  EXPECT_EQ(e.key, b.key) << e.describe();
  EXPECT_NE(e.message.find(b.message_part), std::string::npos) << e.describe();
  EXPECT_NE(e.describe().find(path + ":" + std::to_string(b.line)), std::string::npos) << e.describe();
}

INSTANTIATE_TEST_SUITE_P(
    Files, ScenarioLoaderBadFile,
    ::testing::Values(BadFile{"typo_key.yaml", 9, "machine.axes[0].limits.jerck",
                              "unknown key 'jerck'; allowed here: velocity, acceleration, jerk"},
                      BadFile{"bad_number.yaml", 9, "program[1].move_absolute.velocity",
                              "expected a velocity in units/s, got 'fast'"},
                      BadFile{"unknown_axis.yaml", 15, "program[1].parallel[1].move_relative.axis",
                              "unknown axis 'z'; the machine has: x, y"},
                      BadFile{"missing_drive.yaml", 3, "machine.axes[0].drive", "missing key 'drive'"},
                      BadFile{"bad_yaml.yaml", 5, "", "not valid YAML"},
                      BadFile{"bad_expectation.yaml", 9, "expect[1].fault", "expected a fault code 'category:number'"}),
    [](const ::testing::TestParamInfo<BadFile>& p) {
      std::string n = p.param.file;
      return n.substr(0, n.find('.'));
    });

TEST(ScenarioLoader, MissingFile) {
  auto r = load_scenario("tests/runtime/data/does_not_exist.yaml");
  ASSERT_FALSE(r.has_value());
  EXPECT_NE(r.error().describe().find("does_not_exist.yaml: cannot open"), std::string::npos);
}

TEST(ScenarioLoader, RejectsStructuralMistakes) {
  struct Case {
    std::string text;
    std::string key;
    std::string part;
  };
  const std::vector<Case> cases = {
      {"- just a list\n", "", "a scenario is a map"},
      {"machine: {axes: []}\n", "machine.axes", "at least one axis"},
      {axes_header() + "program:\n  - {enable: x, disable: x}\n", "program[0].disable", "exactly one action"},
      {axes_header() + "program:\n  - {at: 1}\n", "program[0]", "a step needs one action"},
      {axes_header() + "program:\n  - wait: -1\n", "program[0].wait", "expected a duration"},
      {axes_header() + "cut_off: expected\n", "cut_off", "add 'duration:'"},
      {axes_header() + "duration: 1s\ncut_off: maybe\n", "cut_off", "expected one of: fail, expected"},
      {axes_header() + "program:\n  - wait: 3 parsecs\n", "program[0].wait", "expected a duration"},
      {axes_header() + "program:\n  - move_absolute: {axis: x, position: 1, direction: shortest}\n",
       "program[0].move_absolute.direction", "rotary axes only"},
      {axes_header() + "program:\n  - jog: {axis: x, direction: up, duration: 1}\n", "program[0].jog.direction",
       "expected one of: positive, negative"},
      {axes_header() + "program:\n  - wait_until: {axis: x}\n", "program[0].wait_until", "a condition needs one of"},
      {axes_header() + "program:\n  - wait_until: {axis: x, state: flying}\n", "program[0].wait_until.state",
       "expected an axis state"},
      {axes_header() + "expect:\n  - {axis: x, position: 3, tolerance: 0}\n", "expect[0].tolerance", "(> 0)"},
      {axes_header() + "expect:\n  - {axis: q, no_fault: true}\n", "expect[0].axis", "unknown axis 'q'"},
      {axes_header() + "expect:\n  - {axis: x, no_fault: true, at: 1}\n", "expect[0].at", "does not apply"},
      {axes_header() + "expect:\n  - {axis: x, position: 1, tolerance: 0.1, at: 1, by: 2}\n", "expect[0].by",
       "either 'at'"},
      {axes_header() + "period: 1us\n", "period", "between 50us and 1s"},
      {"machine:\n  axes:\n    - {name: x, inc_per_unit: 0, limits: {velocity: 1, acceleration: 1}, drive: {transport: "
       "sim}}\n",
       "machine.axes[0].inc_per_unit", "expected increments per unit"},
      {"machine:\n  axes:\n    - {name: all, inc_per_unit: 1, limits: {velocity: 1, acceleration: 1}, drive: "
       "{transport: sim}}\n",
       "machine.axes[0].name", "not 'all'"},
      {"machine:\n  axes:\n    - {name: x, inc_per_unit: 1, limits: {velocity: 1, acceleration: 1}, drive: {transport: "
       "sim}}\n"
       "    - {name: x, inc_per_unit: 1, limits: {velocity: 1, acceleration: 1}, drive: {transport: sim}}\n",
       "machine.axes[1].name", "defined twice"},
      {"machine:\n  axes:\n    - {name: x, inc_per_unit: 1, limits: {velocity: 1, acceleration: 1}, drive: {port: "
       "3}}\n",
       "machine.axes[0].drive.transport", "missing key 'transport'"},
      {"machine:\n  axes:\n    - {name: x, inc_per_unit: 1, modulo: 360, limits: {velocity: 1, acceleration: 1}, "
       "drive: {transport: sim}}\n",
       "machine.axes[0].modulo", "needs 'rotary: true'"},
      {"machine:\n  axes:\n    - {name: x, inc_per_unit: 1, limits: {velocity: 1, acceleration: .nan}, drive: "
       "{transport: sim}}\n",
       "machine.axes[0].limits.acceleration", "expected an acceleration"},
      {"machine:\n  axes:\n    - {name: x, inc_per_unit: 1, limits: {velocity: 1, acceleration: 1}, drive: {transport: "
       "sim}}\n"
       "machine: {}\n",
       "machine", "key 'machine' appears twice"},
  };
  for (const auto& c : cases) {
    const auto e = error_of(c.text);
    EXPECT_EQ(e.key, c.key) << e.describe() << "\n---\n" << c.text;
    EXPECT_NE(e.message.find(c.part), std::string::npos) << e.describe() << "\n---\n" << c.text;
    EXPECT_EQ(e.file, "t.yaml");
    EXPECT_GT(e.line, 0) << e.describe();
  }
}

TEST(ScenarioLoader, DurationsRatiosAndFaultCodes) {
  EXPECT_EQ(parse_duration("1.5"), 1500ms);
  EXPECT_EQ(parse_duration("250ms"), 250ms);
  EXPECT_EQ(parse_duration(" 2 s "), 2s);
  EXPECT_EQ(parse_duration("100us"), 100us);
  EXPECT_EQ(parse_duration("1min"), 60s);
  EXPECT_FALSE(parse_duration("-1"));
  EXPECT_FALSE(parse_duration("1h"));
  EXPECT_FALSE(parse_duration("1e300"));
  EXPECT_FALSE(parse_duration(""));
  EXPECT_EQ(parse_ratio("1000"), (std::pair<std::int64_t, std::int64_t>{1000, 1}));
  EXPECT_EQ(parse_ratio("4096/5"), (std::pair<std::int64_t, std::int64_t>{4096, 5}));
  EXPECT_EQ(parse_ratio("0.25"), (std::pair<std::int64_t, std::int64_t>{25, 100}));
  EXPECT_FALSE(parse_ratio("0"));
  EXPECT_FALSE(parse_ratio("-3"));
  EXPECT_FALSE(parse_ratio("1/0"));
  EXPECT_FALSE(parse_ratio("abc"));
  auto f = parse_fault_code("cia402:0x7305");
  ASSERT_TRUE(f);
  EXPECT_EQ(f->category, "cia402");
  EXPECT_EQ(f->value, 0x7305);
  EXPECT_EQ(parse_fault_code("motion:1")->value, 1);
  EXPECT_FALSE(parse_fault_code("motion"));
  EXPECT_FALSE(parse_fault_code(":1"));
  EXPECT_FALSE(parse_fault_code("motion:x1"));
}

// Coupling keys (docs/scenarios.md "Coupling"): a complete set, and mistakes named by key.
namespace {
std::string coupled(const std::string& tail) {
  return "machine:\n"
         "  masters:\n    - {name: line, units: mm, inc_per_unit: 1000}\n"
         "  axes:\n"
         "    - {name: x, inc_per_unit: 1000, limits: {velocity: 10, acceleration: 100}, drive: {transport: sim}}\n"
         "    - {name: y, inc_per_unit: 1000, limits: {velocity: 10, acceleration: 100}, drive: {transport: sim}}\n"
         "  cams:\n"
         "    - {name: c, interpolation: cubic_periodic, periodic: true, points: [[0, 0], [1, 1], [2, 3], [3, 3]]}\n" +
         tail;
}
}  // namespace

TEST(ScenarioLoader, CouplingKeys) {
  auto r = parse_scenario(coupled("  couplings:\n    - {slave: y, master: x, source: actual, limits: {velocity: 5, "
                                  "following_error: 0.5}}\n"
                                  "program:\n"
                                  "  - couple: {master: line, velocity: 5, acceleration: 50}\n"
                                  "  - couple: {slave: y, gear: \"-3/4\", at: 1.5, ramp: 2}\n"
                                  "  - couple: {slave: y, superimpose: 1, velocity: 1, acceleration: 10}\n"
                                  "  - couple: {slave: y, disengage: true}\n"),
                          "t.yaml");
  ASSERT_TRUE(r.has_value()) << r.error().describe();
  ASSERT_EQ(r->couplings.size(), 1u);
  EXPECT_EQ(r->couplings[0].source_kind, hil::runtime::MasterSource::axis_actual);
  EXPECT_EQ(r->couplings[0].velocity, 5.0);
  EXPECT_EQ(r->couplings[0].following_error, 0.5);
  ASSERT_EQ(r->cams.size(), 1u);
  EXPECT_EQ(r->cams[0].table.points.size(), 4u);
  const auto& g = std::get<hil::runtime::CoupleStep>(r->program[1].action);
  EXPECT_EQ(g.action, hil::runtime::CoupleStep::Action::gear);
  EXPECT_EQ(g.ratio_num, -3);
  EXPECT_EQ(g.ratio_den, 4);
  EXPECT_EQ(*g.at, 1.5);
  EXPECT_EQ(g.ramp, 2.0);
}

TEST(ScenarioLoader, CouplingMistakes) {
  struct Case {
    std::string text, key, part;
  };
  const std::vector<Case> cases = {
      {coupled("  couplings:\n    - {slave: z, master: x}\n"), "machine.couplings[0].slave", "unknown axis 'z'"},
      {coupled("  couplings:\n    - {slave: y, master: y}\n"), "machine.couplings[0].master", "its own master"},
      {coupled("  couplings:\n    - {slave: y, master: q}\n"), "machine.couplings[0].master", "unknown master 'q'"},
      {coupled("  couplings:\n    - {slave: y, master: line, source: actual}\n"), "machine.couplings[0].source",
       "axis masters only"},
      {coupled("  couplings:\n    - {slave: y, master: x}\n    - {slave: y, master: line}\n"),
       "machine.couplings[1].slave", "already the slave"},
      {coupled("  couplings:\n    - {slave: y, master: x}\nprogram:\n  - couple: {slave: x, gear: 1}\n"),
       "program[0].couple.slave", "not the slave of a coupling"},
      {coupled("  couplings:\n    - {slave: y, master: x}\nprogram:\n  - couple: {slave: y, gear: fast}\n"),
       "program[0].couple.gear", "expected a gear ratio"},
      {coupled("  couplings:\n    - {slave: y, master: x}\nprogram:\n  - couple: {slave: y, gear: 1, cam: c}\n"),
       "program[0].couple", "exactly one of"},
      {coupled("  couplings:\n    - {slave: y, master: x}\nprogram:\n  - couple: {slave: y, cam: d}\n"),
       "program[0].couple.cam", "unknown cam 'd'"},
      {coupled("  couplings:\n    - {slave: y, master: x}\nprogram:\n  - couple: {slave: y, cam: c, ramp: 1}\n"),
       "program[0].couple.ramp", "without a ramp"},
      {"machine:\n  axes:\n    - {name: x, inc_per_unit: 1, limits: {velocity: 1, acceleration: 1}, drive: {transport: "
       "sim}}\n  cams:\n    - {name: c, points: [[0, 0], [2, 1], [1, 3]]}\n",
       "machine.cams[0].points", "is not above"},
  };
  for (const auto& c : cases) {
    const auto e = error_of(c.text);
    EXPECT_EQ(e.key, c.key) << e.describe() << "\n---\n" << c.text;
    EXPECT_NE(e.message.find(c.part), std::string::npos) << e.describe() << "\n---\n" << c.text;
  }
}

TEST(ScenarioLoader, ControllerExpectationsAndMoves) {
  const std::string ctl = "controller: {device: clm14, parameters: clm.par, program: clm.prg}\n";
  auto r = parse_scenario(ctl + axes_header() +
                              "expect:\n"
                              "  - {controller: V600, value: -87654321.654321}\n"
                              "  - {controller: Q1.02, value: 0b0111_0011, at: 2s}\n"
                              "  - {controller: error, value: 0x73, by: 1s}\n"
                              "  - {controller: V601, value: 300, tolerance: 0.011}\n"
                              "  - {device_error: \"clm14.diagnostic:0E\", by: 500ms}\n"
                              "  - {axis: x, moves: 10}\n",
                          "t.yaml");
  ASSERT_TRUE(r.has_value()) << r.error().describe();
  ASSERT_EQ(r->controller->programs.size(), 1u) << "program: FILE is programs: [FILE]";
  const auto& c = r->controller_expectations;
  ASSERT_EQ(c.size(), 5u);
  EXPECT_EQ(c[0].name, "V600");
  EXPECT_EQ(c[0].value, -87654321.654321);
  EXPECT_EQ(c[0].tolerance, 0.0);
  EXPECT_EQ(c[1].value, 0x73);
  EXPECT_EQ(c[1].value_text, "0b0111_0011");
  EXPECT_EQ(c[1].at, 2s);
  EXPECT_EQ(c[2].value, 0x73);
  EXPECT_EQ(c[2].by, 1s);
  EXPECT_DOUBLE_EQ(c[3].tolerance, 0.011);
  EXPECT_EQ(c[4].kind, ControllerExpectation::Kind::device_error);
  EXPECT_EQ(c[4].code, "clm14.diagnostic:0E");
  EXPECT_EQ(c[4].by, 500ms);
  ASSERT_EQ(r->expectations.size(), 1u);
  EXPECT_EQ(std::get<MovesExpectation>(r->expectations[0].kind).count, 10u);

  struct Case {
    std::string text;
    std::string key;
    std::string part;
  };
  const std::vector<Case> cases = {
      {axes_header() + "expect:\n  - {controller: V600, value: 1}\n", "expect[0].controller", "'controller:' block"},
      {ctl + axes_header() + "expect:\n  - {controller: V600}\n", "expect[0].value", "missing key 'value'"},
      {ctl + axes_header() + "expect:\n  - {controller: V600, value: 0x}\n", "expect[0].value", "0x.. (hex)"},
      {ctl + axes_header() + "expect:\n  - {controller: V600, value: 1, at: 1, by: 2}\n", "expect[0].by",
       "either 'at'"},
      {ctl + axes_header() + "expect:\n  - {controller: V600, value: 1, edges: 2}\n", "expect[0].edges", "unknown key"},
      {ctl + axes_header() + "expect:\n  - {device_error: motion:1}\n", "expect[0].device_error",
       "as the manual writes it"},
      {ctl + axes_header() + "expect:\n  - {device_error: \"clm14.diagnostic:0E\", at: 1}\n", "expect[0].at",
       "unknown key"},
      {axes_header() + "expect:\n  - {axis: x, moves: 2.5}\n", "expect[0].moves", "whole number of moves"},
  };
  for (const auto& k : cases) {
    const auto e = error_of(k.text);
    EXPECT_EQ(e.key, k.key) << e.describe() << "\n---\n" << k.text;
    EXPECT_NE(e.message.find(k.part), std::string::npos) << e.describe() << "\n---\n" << k.text;
  }
  const auto twice =
      error_of(axes_header() + "controller: {device: clm14, parameters: a, program: b, programs: [c]}\n");
  EXPECT_EQ(twice.key, "controller.program") << twice.describe();
}
