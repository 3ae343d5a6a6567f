// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include "hil/core/clock.hpp"

using namespace std::chrono_literals;

TEST(VirtualClock, MovesOnlyWhenAdvanced) {
  hil::VirtualClock c;
  EXPECT_EQ(c.now().time_since_epoch(), 0ns);
  c.advance(1ms);
  EXPECT_EQ(c.now().time_since_epoch(), 1ms);
  c.advance_to(hil::TimePoint{5ms});
  EXPECT_EQ(c.now().time_since_epoch(), 5ms);
  c.advance_to(hil::TimePoint{2ms});  // never backwards
  EXPECT_EQ(c.now().time_since_epoch(), 5ms);
}

TEST(SteadyClock, IsMonotonic) {
  hil::SteadyClock c;
  auto a = c.now();
  auto b = c.now();
  EXPECT_LE(a, b);
  EXPECT_GE(a.time_since_epoch(), 0ns);
}

TEST(Seconds, RoundTrip) {
  EXPECT_DOUBLE_EQ(hil::to_seconds(1500us), 0.0015);
  EXPECT_EQ(hil::from_seconds(0.25), 250ms);
}
