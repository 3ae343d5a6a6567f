// SPDX-License-Identifier: MIT
// `io: - {analog: NAME, value: V, at: T, ramp: D}`: the schedule's value over time, the CLM1.4's
// AE1..AE4 driven from a scenario (V007, the B017 average), and the loader's / builder's errors.
#include <gtest/gtest.h>

#include "hil/controllers/analog_stimulus.hpp"
#include "scenario_text.hpp"

namespace hil::runtime {
namespace {

using scenario_text::run_text;
using scenario_text::wf_head;

using namespace std::chrono_literals;
using controllers::analog_value_at;
using controllers::AnalogStep;

TEST(AnalogStimulus, StepsAndRampsOverTime) {
  const std::vector<AnalogStep> s{{1s, 5.0, {}}, {2s, 10.0, 1s}, {4s, 0.0, 2s}, {5s, 8.0, {}}};
  EXPECT_EQ(analog_value_at(s, -1.0, 0s), -1.0) << "before the first step: the initial value";
  EXPECT_EQ(analog_value_at(s, -1.0, 1s), 5.0);
  EXPECT_EQ(analog_value_at(s, -1.0, 2s), 5.0) << "a ramp starts from the value it finds";
  EXPECT_EQ(analog_value_at(s, -1.0, 2500ms), 7.5);
  EXPECT_EQ(analog_value_at(s, -1.0, 3s), 10.0);
  EXPECT_EQ(analog_value_at(s, -1.0, 4500ms), 7.5);
  EXPECT_EQ(analog_value_at(s, -1.0, 5s), 8.0) << "a later step cuts the ramp short";
  EXPECT_EQ(analog_value_at(s, -1.0, 100s), 8.0);
  // a step during a ramp starts from the ramp's value at that time
  const std::vector<AnalogStep> t{{0s, 10.0, 2s}, {1s, 0.0, 1s}};
  EXPECT_EQ(analog_value_at(t, 0.0, 1500ms), 2.5);
}

const std::string clm_head = R"(
period: 2ms
controller: {device: clm14, parameters: clm14-analog.par, program: clm14-analog-override.prg}
machine:
  axes:
    - name: "1"
      drive: {transport: sim, kv: 200, feedforward: 1.0, max_velocity: 1e8}
io:
  - {set: I0.00.2, at: 0s}
  - {set: I0.00.4, at: 0s}
)";

TEST(AnalogStimulus, ClmAnalogInputFollowsTheRampThroughTheB017Average) {
  // AE1 ramps 0 -> 10 V over 1 s. B017 averages 8 NC cycles (2 ms): at 500 ms V007 is the mean of
  // the samples at 486..500 ms, 4.86 .. 5.00 V: 0.493. At the end it holds 0.75 exactly.
  const auto r = run_text(clm_head + R"(
  - {analog: AE1, value: 10, at: 0s, ramp: 1s}
  - {analog: AE1, value: 7.5, at: 1200ms}
program:
  - wait: 1500ms
expect:
  - {controller: V007, value: 0.493, at: 500ms}
  - {controller: V007, value: 0.75}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
}

TEST(AnalogStimulus, ErrorsNameTheEntry) {
  const auto unknown = run_text(clm_head + "  - {analog: AE5, value: 1, at: 0s}\n");
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().describe().find("AE1..AE4"), std::string::npos) << unknown.error().describe();
  const auto range = run_text(clm_head + "  - {analog: AE2, value: 12, at: 0s}\n");
  ASSERT_FALSE(range);
  EXPECT_NE(range.error().describe().find("-10 .. 10 V"), std::string::npos) << range.error().describe();
  EXPECT_NE(range.error().describe().find("io[2].value"), std::string::npos) << range.error().describe();
  const auto order = run_text(clm_head + "  - {analog: AE2, value: 1, at: 1s}\n  - {analog: AE2, value: 2, at: 1s}\n");
  ASSERT_FALSE(order);
  EXPECT_NE(order.error().describe().find("increasing time"), std::string::npos) << order.error().describe();
  const auto key = run_text(clm_head + "  - {analog: AE2, value: 1, at: 1s, width: 2ms}\n");
  ASSERT_FALSE(key);
  EXPECT_NE(key.error().describe().find("width"), std::string::npos) << key.error().describe();
  const auto missing = run_text(clm_head + "  - {analog: AE2, at: 1s}\n");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().describe().find("value"), std::string::npos) << missing.error().describe();
  const auto wf = run_text(wf_head + "io:\n  - {analog: AE1, value: 1, at: 0s}\n");
  ASSERT_FALSE(wf);
  EXPECT_NE(wf.error().describe().find("has no analog inputs"), std::string::npos) << wf.error().describe();
}

}  // namespace
}  // namespace hil::runtime
