// SPDX-License-Identifier: MIT
// Device parameters -> axes: the same parameter set gives the scaling and limits the manuals'
// formulas give (WF MD 19/20/21 with MD 49, IP247 vmax from fmax and gear, CLM Ax01/Ax19), and
// what the core cannot honour is an error naming the parameter or a warning.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "hil/controllers/parameter_controller.hpp"

namespace hil::controllers {
namespace {

std::string read(const char* path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The shipped WF set with some MDs replaced.
std::string wf_set(const std::vector<std::pair<std::string, std::string>>& replace) {
  std::istringstream in(read("tests/profiles/data/wf725_valid.txt"));
  std::string out, line;
  while (std::getline(in, line)) {
    for (const auto& [md, value] : replace)
      if (line.starts_with(md + " =")) line = md + " = " + value;
    out += line + "\n";
  }
  return out;
}

double ratio(const motion::Ratio& r) {
  return static_cast<double>(r.num) / static_cast<double>(r.den);
}

struct WfCase {
  const char* what;
  std::vector<std::pair<std::string, std::string>> md;
  std::int64_t num, den;  ///< increments per mm, exact
  double velocity;        ///< mm/s
};

class WfScaling : public ::testing::TestWithParam<WfCase> {};

TEST_P(WfScaling, GivesTheManualsIncrements) {
  const auto& c = GetParam();
  const auto p = load_parameter_text("wf725-726", wf_set(c.md), "md.txt");
  ASSERT_TRUE(p) << p.error().describe();
  const auto axes = wf725_axes(*p, ControllerSpec{});
  ASSERT_TRUE(axes) << axes.error().describe();
  const auto& a = axes->axes.at(0);
  EXPECT_EQ(a.config.inc_per_unit.num, c.num) << c.what;
  EXPECT_EQ(a.config.inc_per_unit.den, c.den) << c.what;
  EXPECT_DOUBLE_EQ(a.config.limits.velocity, c.velocity) << c.what;
  EXPECT_TRUE(motion::validate(a.config)) << c.what;
}

INSTANTIATE_TEST_SUITE_P(Manual, WfScaling,
                         ::testing::Values(
                             // §4.3 MD 21 a1: 1 µm, 10 mm pitch, 2500 lines x4 -> B_I = 1.0 -> 1000 increments per mm.
                             WfCase{"a1", {{"MD 19", "1"}, {"MD 20", "0"}, {"MD 3", "6000"}}, 1000, 1, 100.0},
                             // §4.3 MD 19/20: 1.347 µm per increment -> 1000 / 1.347 = 742.39 increments per mm.
                             WfCase{"1.347", {{"MD 19", "1"}, {"MD 20", "34700000"}}, 1000000, 1347, 10000.0 / 60.0},
                             // 10 µm resolution (MD 49 = 2), B_I = 0.5: 5 µm per increment -> 200 per mm.
                             WfCase{"res10",
                                    {{"MD 49", "2"},
                                     {"MD 19", "0"},
                                     {"MD 20", "50000000"},
                                     {"MD 11", "-24530"},
                                     {"MD 12", "-42720"},
                                     {"MD 13", "96410"},
                                     {"MD 14", "137420"},
                                     {"MD 1", "500"},
                                     {"MD 2", "500"},
                                     {"MD 24", "12000"},
                                     {"MD 25", "40"},
                                     {"MD 26", "1200"},
                                     {"MD 32", "30"},
                                     {"MD 33", "10"},
                                     {"MD 31", "0"}},
                                    200,
                                    1,
                                    10000.0 / 60.0}),
                         [](const ::testing::TestParamInfo<WfCase>& p) {
                           return std::string(p.param.what == std::string("1.347") ? "b1_347" : p.param.what);
                         });

TEST(WfAxes, LimitsWindowsAndWarnings) {
  const auto p = load_parameter_text("wf725-726", wf_set({{"MD 2", "800"}}), "md.txt");
  ASSERT_TRUE(p) << p.error().describe();
  const auto axes = wf725_axes(*p, ControllerSpec{});
  ASSERT_TRUE(axes) << axes.error().describe();
  const auto& a = axes->axes[0];
  EXPECT_EQ(a.name, "A");
  EXPECT_DOUBLE_EQ(*a.config.soft_limit_min, -24.537);  // MD 11
  EXPECT_DOUBLE_EQ(*a.config.soft_limit_max, 96.417);   // MD 13
  EXPECT_DOUBLE_EQ(a.config.limits.acceleration, 500.0);
  EXPECT_DOUBLE_EQ(a.config.quick_stop_deceleration, 800.0);
  EXPECT_NEAR(a.config.following_error.kv_per_s, 1000.0 / 60.0, 1e-12);  // MD 22 = 1.00 (m/min)/mm
  EXPECT_DOUBLE_EQ(a.config.following_error.max_window, 12.0);           // MD 24
  EXPECT_DOUBLE_EQ(a.config.following_error.min_window, 1.2);            // MD 26
  EXPECT_DOUBLE_EQ(a.config.standstill_window, 0.04);                    // MD 25
  EXPECT_DOUBLE_EQ(a.config.in_position_window, 0.011);                  // MD 33
  EXPECT_EQ(axes->cycle, std::chrono::milliseconds(4));
  ASSERT_GE(a.warnings.size(), 2U);
  EXPECT_NE(a.warnings[0].find("MD 1"), std::string::npos) << a.warnings[0];
}

TEST(WfAxes, RotaryNeedsWholeIncrementsPerTurn) {
  // §4.3 MD 21 a2 (rotary 360.000°, B_I = 0.717131474 at 10 µm): 50 200.0003 increments per turn.
  const auto p = load_parameter_text(
      "wf725-726",
      wf_set({{"MD 18", "360000"}, {"MD 19", "0"}, {"MD 20", "71713147"}, {"MD 11", "-24537"}, {"MD 13", "96417"}}),
      "md.txt");
  ASSERT_TRUE(p) << p.error().describe();
  const auto axes = wf725_axes(*p, ControllerSpec{});
  ASSERT_FALSE(axes);
  EXPECT_EQ(axes.error().key, "MD18") << axes.error().describe();
  // B_I = 0.5 on 360 000 m° gives 720 000 increments per turn: fine.
  const auto q =
      load_parameter_text("wf725-726", wf_set({{"MD 18", "360000"}, {"MD 19", "0"}, {"MD 20", "50000000"}}), "md.txt");
  ASSERT_TRUE(q) << q.error().describe();
  const auto r = wf725_axes(*q, ControllerSpec{});
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->axes[0].config.rotary);
  EXPECT_DOUBLE_EQ(r->axes[0].config.modulo, 360.0);
  EXPECT_EQ(r->axes[0].units, "deg");
  EXPECT_DOUBLE_EQ(ratio(r->axes[0].config.inc_per_unit), 2000.0);
}

TEST(WfAxes, OpenLoopIsASpeedLevelDrive) {
  // MD 4 = 3 (open loop): no MD 3 / MD 22-26; the drive reaches `open_loop_speed` at 10 V (level 100),
  // MD 1/2 are voltage ramps in mV/s (WF 726), capped by the drive's own acceleration.
  const auto p = load_parameter_file("wf725-726", "examples/controllers/wf725-axis-ak.txt");
  ASSERT_TRUE(p) << p.error().describe();
  ControllerSpec spec;
  spec.options = {{"open_loop_speed", "6000"}, {"open_loop_acceleration", "400"}};
  const auto axes = wf725_axes(*p, spec);
  ASSERT_TRUE(axes) << axes.error().describe();
  const auto& c = axes->axes[0].config;
  EXPECT_DOUBLE_EQ(c.limits.velocity, 0.99 * 6000.0 / 60.0) << "level 99 = 9.9 V";
  EXPECT_DOUBLE_EQ(c.limits.acceleration, 400.0) << "MD 1/2 = 0: a step, the drive's own ramp";
  EXPECT_DOUBLE_EQ(c.quick_stop_deceleration, 400.0);
  EXPECT_FALSE(c.following_error.dynamic) << "no position loop of the WF";
  EXPECT_DOUBLE_EQ(c.in_position_window, 0.030) << "MD 33";
  // MD 1 = MD 2 = 1200 mV/s on the same drive: 1.2 V/s of 600 mm/min per volt = 12 mm/s^2.
  std::string text;
  {
    std::ifstream in("examples/controllers/wf725-axis-ak.txt");
    std::string line;
    while (std::getline(in, line))
      text += (line == "MD 1 = 0" ? "MD 1 = 1200" : line == "MD 2 = 0" ? "MD 2 = 1200" : line) + "\n";
  }
  const auto q = load_parameter_text("wf725-726", text, "ak.txt");
  ASSERT_TRUE(q) << q.error().describe();
  const auto r = wf725_axes(*q, spec);
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_DOUBLE_EQ(r->axes[0].config.limits.acceleration, 12.0) << "MD 1 = MD 2 = 1200 mV/s";
  EXPECT_DOUBLE_EQ(r->axes[0].config.quick_stop_deceleration, 400.0) << "the drive's own";
  spec.options = {{"open_loop_speed", "fast"}};
  EXPECT_FALSE(wf725_axes(*q, spec)) << "a bad drive speed is refused";
}

TEST(Ip247Axes, VmaxFromFmaxAndGear) {
  // The manual's MD DB example (§6.3.8.1): mm, 200 pulses/rev, 2000 BU/rev, fmax 5 kHz, a = 50 Hz/ms.
  const auto p = load_parameter_file("ip247", "examples/serial/ip247-md-db1.s5db");
  ASSERT_TRUE(p) << p.error().describe();
  const auto axes = ip247_axes(*p, ControllerSpec{});
  ASSERT_TRUE(axes) << axes.error().describe();
  const auto& a = axes->axes.at(0);
  EXPECT_EQ(a.name, "1");
  EXPECT_EQ(a.units, "mm");
  EXPECT_EQ(a.config.inc_per_unit.num, 100);  // 200 * 1000 / 2000
  EXPECT_EQ(a.config.inc_per_unit.den, 1);
  EXPECT_DOUBLE_EQ(a.config.limits.velocity, 5000.0 * 2000.0 / (200.0 * 1000.0));  // 50 mm/s
  EXPECT_DOUBLE_EQ(a.config.limits.acceleration, 50.0 * 1000.0 / 100.0);           // 500 mm/s^2
  EXPECT_DOUBLE_EQ(*a.config.soft_limit_min, -400.0);
  EXPECT_DOUBLE_EQ(*a.config.soft_limit_max, 500.0);
  EXPECT_TRUE(a.limit_switches.normally_closed);  // DW 33 = 1
  ASSERT_TRUE(a.reference);
  EXPECT_EQ(a.reference->direction, -1);  // DW 26 = 20h
  EXPECT_FALSE(a.warnings.empty()) << "the exponential ramp is approximated";
}

TEST(Clm14Axes, FeedConstantAndEncoder) {
  const auto p = load_parameter_file("clm14", "examples/serial/clm14-parameters.par");
  ASSERT_TRUE(p) << p.error().describe();
  const auto axes = clm14_axes(*p, ControllerSpec{});
  ASSERT_TRUE(axes) << axes.error().describe();
  ASSERT_EQ(axes->axes.size(), 1U) << "B000: axes 2-4 disabled";
  const auto& a = axes->axes[0];
  // 4 x 1024 pulses per 10 IU (Ax19, Ax01): 409.6 increments per IU = 2048/5.
  EXPECT_EQ(a.config.inc_per_unit.num, 2048);
  EXPECT_EQ(a.config.inc_per_unit.den, 5);
  EXPECT_DOUBLE_EQ(a.config.limits.velocity, 100.0);     // A106
  EXPECT_DOUBLE_EQ(a.config.limits.acceleration, 10.0);  // A108, A109 = 000 000
  EXPECT_DOUBLE_EQ(*a.config.soft_limit_min, -111111.111);
  EXPECT_DOUBLE_EQ(*a.config.soft_limit_max, 100000.0);
  // Max lag = 3000 rpm * 10 IU / (Kv 1.00 * 1000) = 30 IU; Ax14 10 %.
  EXPECT_DOUBLE_EQ(a.config.following_error.max_window, 33.0);
  EXPECT_DOUBLE_EQ(a.config.following_error.min_window, 3.0);
  EXPECT_EQ(axes->cycle, std::chrono::milliseconds(2));  // B010 = 0.0, one axis
  ControllerSpec two;
  two.options.emplace("encoder_multiplication", "1");
  const auto x1 = clm14_axes(*p, two);
  ASSERT_TRUE(x1);
  EXPECT_DOUBLE_EQ(ratio(x1->axes[0].config.inc_per_unit), 102.4);
}

TEST(BuiltinControllers, FaultMapsGiveTheDevicesNumbers) {
  const auto wf = wf725_faults();
  EXPECT_EQ(wf.code(0, hil::MotionFault::software_limit, true), 0x95);
  EXPECT_EQ(wf.code(0, hil::MotionFault::software_limit, false), 0x96);
  const auto ip = ip247_faults();
  EXPECT_EQ(ip.code(0, hil::MotionFault::software_limit, true), 28);
  EXPECT_EQ(ip.code(0, hil::MotionFault::software_limit, false), 29);
  const auto clm = clm14_faults();
  EXPECT_EQ(clm.code(0, hil::MotionFault::software_limit, true), 0x50);
  EXPECT_EQ(clm.code(0, hil::MotionFault::software_limit, false), 0x51);
  EXPECT_EQ(clm.code(1, hil::MotionFault::software_limit, false), 0x81);
  const auto r = builtin_controllers();
  EXPECT_EQ(r.names(), (std::vector<std::string>{"clm14", "ip247", "wf725-726"}));
  ControllerSpec s;
  s.device = "wf725-726";
  s.parameters = "no/such.md";
  EXPECT_FALSE(r.create(s));
  s.parameters = "examples/controllers/wf725-axis-a.txt";
  s.options.emplace("bogus", "1");
  const auto bad = r.create(s);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("bogus"), std::string::npos);
}

}  // namespace
}  // namespace hil::controllers
