// SPDX-License-Identifier: MIT
// Mock GPIO lines: timestamped recording, protocol checks, scripted inputs, forced inputs, and the
// step/dir decoder that gives the plant position as a function of time.
#include <gtest/gtest.h>

#include "hil/mocks/gpio/mock_lines.hpp"

using namespace hil::gpio;
using hil::VirtualClock;

namespace {
std::vector<LineSpec> specs() {
  return {{"step", 0U, "", LineDirection::output, false, Bias::as_is, false},
          {"dir", 1U, "", LineDirection::output, false, Bias::as_is, true},
          {"ready", 2U, "", LineDirection::input, false, Bias::as_is, false}};
}
}  // namespace

TEST(MockLines, RecordsSetValueAtClockTimeAndBatchesAtTheirTimes) {
  VirtualClock clock;
  mock::MockLines l(specs(), clock);
  clock.advance(std::chrono::microseconds(5));
  EXPECT_FALSE(l.set_value(0, true));
  EXPECT_FALSE(l.set_value(0, true));  // no change: nothing recorded
  const std::vector<Edge> batch = {{10'000, 0, false}, {20'000, 1, false}};
  l.output(batch);
  ASSERT_EQ(l.recorded().size(), 3U);
  EXPECT_EQ(l.recorded()[0], (Edge{5'000, 0, true}));
  EXPECT_EQ(l.recorded()[2], (Edge{20'000, 1, false}));
  EXPECT_TRUE(l.errors().empty());
  EXPECT_TRUE(l.set_value(2, true));  // an input cannot be driven
}

TEST(MockLines, FlagsProtocolErrors) {
  VirtualClock clock;
  mock::MockLines l(specs(), clock);
  const std::vector<Edge> bad = {{10, 0, true}, {5, 0, false}, {6, 0, false}, {7, 2, true}};
  l.output(bad);
  // 5: earlier than 10; 6: earlier than 10 and no level change; 7: an input line.
  ASSERT_EQ(l.errors().size(), 4U);
  EXPECT_NE(l.errors()[0].find("earlier"), std::string::npos);
  EXPECT_NE(l.errors()[1].find("earlier"), std::string::npos);
  EXPECT_NE(l.errors()[2].find("does not change"), std::string::npos);
  EXPECT_NE(l.errors()[3].find("not an output"), std::string::npos);
}

TEST(MockLines, ScriptedAndForcedInputs) {
  VirtualClock clock;
  mock::MockLines l(specs(), clock);
  mock::InputScript script{false, {{1'000, true}, {3'000, false}}};
  l.set_input_source(2, [script](std::int64_t t) { return script.level_at(t); });
  EXPECT_EQ(l.get_value(2).value(), false);
  clock.advance(std::chrono::nanoseconds(1'000));
  EXPECT_EQ(l.get_value(2).value(), true);
  l.force_input(2, false);  // broken wire
  EXPECT_EQ(l.get_value(2).value(), false);
  l.force_input(2, std::nullopt);
  clock.advance(std::chrono::nanoseconds(2'000));
  EXPECT_EQ(l.get_value(2).value(), false);
  EXPECT_FALSE(l.get_value(7).has_value());
}

TEST(StepDirDecoder, PositionAtTimeCountsOnlyEdgesUpToThatTime) {
  VirtualClock clock;
  mock::MockLines l(specs(), clock);
  mock::StepDirDecoder d(l, 0, 1, true, true, 100);
  const std::vector<Edge> e = {{10, 0, true},  {12, 0, false}, {20, 0, true}, {22, 0, false},
                               {30, 1, false}, {40, 0, true},  {42, 0, false}};
  l.output(e);
  EXPECT_EQ(d.position_at(9), 100);
  EXPECT_EQ(d.position_at(10), 101);
  EXPECT_EQ(d.position_at(25), 102);
  EXPECT_EQ(d.position_at(50), 101);
}
