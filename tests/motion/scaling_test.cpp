// SPDX-License-Identifier: MIT
// Exact rational scaling, rotary wrap and direction rules, drift-free relative steps.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "hil/motion/scaling.hpp"

namespace hil::motion {
namespace {

TEST(Scaling, RoundTripOverMillionsOfIncrementsWithoutDrift) {
  const Scaling s({4096, 5}, false, 0.0);  // 819.2 inc/mm
  for (std::int64_t n = -3'000'000; n <= 3'000'000; n += 7) ASSERT_EQ(s.to_inc(s.to_units(n)), n) << n;
  // Far from zero, where a double product would lose increments.
  for (std::int64_t n = (std::int64_t{1} << 52) - 1000; n < (std::int64_t{1} << 52) + 1000; ++n) {
    ASSERT_EQ(s.to_inc(static_cast<double>(n / 4096 * 5)), n / 4096 * 4096);
  }
}

TEST(Scaling, ExactIntegerPartForHugePositions) {
  const Scaling s({1'000'003, 7}, false, 0.0);
  const double x = 3.0e12;  // x * num = 3e18 > 2^53: a double product would be off
  __extension__ typedef __int128 i128;
  const i128 big = static_cast<i128>(3'000'000'000'000LL) * 1'000'003;
  const auto expected = static_cast<std::int64_t>((big + 3) / 7);  // round half up, positive
  EXPECT_EQ(s.to_inc(x), expected);
  EXPECT_EQ(s.to_inc(-x), -expected);
}

TEST(Scaling, RoundsHalfAwayFromZero) {
  const Scaling s({1, 2}, false, 0.0);  // 0.5 inc per unit
  EXPECT_EQ(s.to_inc(1.0), 1);          // 0.5 -> 1
  EXPECT_EQ(s.to_inc(-1.0), -1);
  EXPECT_EQ(s.to_inc(3.0), 2);  // 1.5 -> 2
  EXPECT_EQ(s.to_inc(-3.0), -2);
  EXPECT_EQ(s.to_inc(2.9), 1);  // 1.45 -> 1
  EXPECT_EQ(s.to_units(3), 6.0);
}

TEST(Scaling, RelativeStepsCarryTheirFraction) {
  const Scaling s({4096, 5}, false, 0.0);
  double carry = 0.0;
  std::int64_t pos = 0;
  for (int i = 0; i < 1'000'000; ++i) pos += s.delta_to_inc(0.001, carry);  // 0.8192 inc each
  EXPECT_EQ(pos, 819'200);
  carry = 0.0;
  pos = 0;
  for (int i = 0; i < 1'000'000; ++i) pos += s.delta_to_inc(i % 2 ? 0.0123 : -0.0071, carry);
  EXPECT_EQ(pos, s.to_inc(500'000 * (0.0123 - 0.0071)));
  EXPECT_LE(std::fabs(carry), 0.5);
}

TEST(Scaling, FastPathAgreesAwayFromTies) {
  const Scaling s({10000, 3}, false, 0.0);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> d(-1e6, 1e6);
  for (int i = 0; i < 100000; ++i) {
    const double x = d(rng);
    ASSERT_LE(std::llabs(s.to_inc(x) - s.to_inc_fast(x)), 1);
    ASSERT_NEAR(s.to_units(s.to_inc(x)), x, 0.5 * 3.0 / 10000 + 1e-9);
  }
}

TEST(Scaling, RotaryWrapAndDisplay) {
  const Scaling s({3600, 360}, true, 360.0);  // 10 inc/degree, 3600 per turn
  EXPECT_EQ(s.inc_per_turn(), 3600);
  EXPECT_EQ(s.wrap_inc(3600 * 5 + 12), 12);
  EXPECT_EQ(s.wrap_inc(-1), 3599);
  EXPECT_DOUBLE_EQ(s.display_units(-10), 359.0);
}

TEST(Scaling, RotaryDirections) {
  const Scaling s({10, 1}, true, 360.0);
  const std::int64_t at350 = 3500 + 3600 * 2;         // two turns on, showing 350
  EXPECT_EQ(s.rotary_step(at350, 10.0, 0), 200);      // shortest: +20 degrees
  EXPECT_EQ(s.rotary_step(at350, 10.0, 1), 200);      // positive: +20
  EXPECT_EQ(s.rotary_step(at350, 10.0, -1), -3400);   // negative: -340
  EXPECT_EQ(s.rotary_step(100, 350.0, 0), -200);      // 10 -> 350 shortest: -20
  EXPECT_EQ(s.rotary_step(100, 350.0, 1), 3400);      // positive: +340
  EXPECT_EQ(s.rotary_step(0, 180.0, 0), 1800);        // tie goes positive
  EXPECT_EQ(s.rotary_step(0, 720.0 + 90.0, 0), 900);  // target taken modulo
  EXPECT_EQ(s.rotary_step(0, -90.0, 0), -900);
  EXPECT_EQ(s.rotary_step(0, 0.0, 1), 0);  // already there: no full turn
}

}  // namespace
}  // namespace hil::motion
