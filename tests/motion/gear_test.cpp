// SPDX-License-Identifier: MIT
// The electronic gear: exact ratio over 10^7 cycles (no drift), transitions at a master
// position within the cycle that crosses it, ratio ramps with their closed-form end offset,
// master reversal inside a ramp, invalid transitions. Virtual time, fixed seeds.
#include <gtest/gtest.h>

#include <random>

#include "hil/motion/coupling.hpp"
#include "hil/motion/gear.hpp"
#include "hil/motion/master.hpp"

namespace hil::motion {
namespace {

using std::chrono::milliseconds;

// floor(s0 + num * (m - m0) / den), exactly.
std::int64_t exact(std::int64_t s0, GearRatio r, std::int64_t dm) {
  return s0 + static_cast<std::int64_t>(floor_div(static_cast<i128>(dm) * r.num, static_cast<i128>(r.den)));
}

TEST(Gear, TenMillionCyclesWithinOneIncrementOfRatioTimesMaster) {
  // A virtual master with random velocity changes (fractional increments per cycle, reversals),
  // a coupled slave through Coupling (as an axis uses it), checked every cycle.
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<double> vel(-250000.0, 250000.0);
  const GearRatio r{-7919, 10007};
  Coupling c("geared");
  c.use(Coupling::Law::gear);
  ASSERT_FALSE(c.gear().engage(r));
  VirtualMaster master(123456789);
  c.start(master.position(), -42);
  const std::int64_t m0 = master.position();
  std::int64_t worst = 0;
  for (int i = 0; i < 10'000'000; ++i) {
    if (i % 20000 == 0) master.set_velocity(vel(rng), 5e6);
    const std::int64_t m = master.update(milliseconds(1));
    const auto& out = c.update(m, milliseconds(1));
    const std::int64_t d = out.position_inc - exact(-42, r, m - m0);
    worst = std::max(worst, d < 0 ? -d : d);
    if (worst > 1) FAIL() << "cycle " << i << ": slave " << out.position_inc << " vs exact " << exact(-42, r, m - m0);
  }
  EXPECT_LE(worst, 1);
  EXPECT_FALSE(c.faulted());
}

TEST(Gear, SteadyIsExactFloor) {
  Gear g(GearRatio{3, 7});
  g.start(0, 0);
  for (std::int64_t m = 0; m < 100000; m += 13) {
    g.update(m);
    ASSERT_EQ(g.slave_inc(), exact(0, {3, 7}, m));
  }
  for (std::int64_t m = 100000; m > -100000; m -= 17) {
    g.update(m);
    ASSERT_EQ(g.slave_inc(), exact(0, {3, 7}, m));
  }
}

TEST(Gear, EngageAtMasterPositionHitsItWithinTheCrossingCycle) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::int64_t> speed(10, 5000), pos(10000, 200000);
  for (int trial = 0; trial < 500; ++trial) {
    const std::int64_t v = speed(rng) * (trial % 2 ? 1 : -1);
    const std::int64_t p = pos(rng) * (trial % 2 ? 1 : -1);
    const GearRatio r{static_cast<std::int64_t>(trial % 9) - 4, 3};
    Gear g;
    g.start(0, 1000);
    ASSERT_FALSE(g.engage(r, 0, p));
    std::int64_t m = 0;
    bool engaged = false;
    for (int i = 0; i < 100000; ++i) {
      const std::int64_t prev = m;
      m += v;
      g.update(m);
      const bool crossed = (prev < p && m >= p) || (prev > p && m <= p);
      if (!engaged && !crossed) {
        ASSERT_EQ(g.slave_inc(), 1000) << "moved before the master reached " << p;
        continue;
      }
      if (crossed) {
        ASSERT_FALSE(engaged);
        engaged = true;
        ASSERT_EQ(g.phase(), GearPhase::steady);
        ASSERT_EQ(g.ratio(), r);
      }
      // From the engage position on, exactly ratio x (master - p).
      ASSERT_EQ(g.slave_inc(), exact(1000, r, m - p)) << "trial " << trial;
      if (i > 0 && std::abs(m - p) > 3 * std::abs(v)) break;
    }
    ASSERT_TRUE(engaged);
  }
}

TEST(Gear, RampedEngageEndsWithTheClosedFormOffset) {
  // 0 -> 3/2 over L = 10000 master increments from p = 5000: the slave covers r L / 2 = 7500
  // during the ramp, then 3/2 per master increment.
  Gear g;
  g.start(0, 0);
  ASSERT_FALSE(g.engage({3, 2}, 10000, 5000));
  double prev_slope = 0.0;
  for (std::int64_t m = 0; m <= 40000; m += 7) {
    g.update(m);
    if (m < 5000) {
      ASSERT_EQ(g.slave_inc(), 0);
    }
    ASSERT_GE(g.slope(), prev_slope - 1e-12);  // the slope only grows towards the ratio
    prev_slope = g.slope();
    if (m >= 5000 && m <= 15000) {
      const double u = static_cast<double>(m - 5000);
      ASSERT_NEAR(g.slave_position(), 1.5 * u * u / 20000.0, 1e-6);
    }
    if (m > 15000) {
      ASSERT_EQ(g.slave_inc(), 7500 + exact(0, {3, 2}, m - 15000));
    }
  }
  EXPECT_EQ(g.phase(), GearPhase::steady);
  EXPECT_EQ(g.ratio(), (GearRatio{3, 2}));
}

TEST(Gear, RatioChangeRampAndDisengage) {
  Gear g(GearRatio{1, 1});
  g.start(0, 0);
  g.update(1000);
  ASSERT_EQ(g.slave_inc(), 1000);
  ASSERT_FALSE(g.change({GearRatio{3, 1}, 2000, {}}));  // at once, over 2000
  g.update(1500);
  EXPECT_NEAR(g.slave_position(), 1000 + 500 + 2.0 * 500 * 500 / 4000.0, 1e-9);
  g.update(5000);  // 1000 + (1+3)/2*2000 over the ramp (to master 3000), then 3 x 2000
  EXPECT_EQ(g.slave_inc(), 1000 + 4000 + 6000);
  ASSERT_FALSE(g.disengage(1000, 6000));
  g.update(6000);
  EXPECT_EQ(g.slave_inc(), 14000);
  g.update(8000);  // ramp 3 -> 0 over 1000: +1500, then held
  EXPECT_EQ(g.slave_inc(), 15500);
  EXPECT_FALSE(g.engaged());
  g.update(20000);
  EXPECT_EQ(g.slave_inc(), 15500);
}

TEST(Gear, MasterReversalInsideARampRetracesTheRamp) {
  Gear g;
  g.start(0, 0);
  ASSERT_FALSE(g.engage({2, 1}, 1000));
  g.update(10);  // the master's direction fixes the ramp's: positive
  g.update(600);
  const double at600 = g.slave_position();
  g.update(300);
  EXPECT_NEAR(g.slave_position(), 2.0 * 300 * 300 / 2000.0, 1e-9);
  g.update(-50);  // behind the ramp start: ratio 0
  EXPECT_EQ(g.slave_inc(), 0);
  g.update(600);
  EXPECT_DOUBLE_EQ(g.slave_position(), at600);
}

TEST(Gear, RejectsInvalidTransitions) {
  Gear g;
  EXPECT_TRUE(g.engage({1, 0}));
  EXPECT_TRUE(g.engage({1, -3}));
  EXPECT_TRUE(g.engage({std::int64_t{1} << 40, 1}));
  EXPECT_TRUE(g.engage({1, 1}, -5));
  ASSERT_FALSE(g.engage({1, 1}, 100));
  g.update(10);
  EXPECT_EQ(g.phase(), GearPhase::ramping);
  EXPECT_EQ(g.change({{2, 1}, 0, {}}), make_error_code(CouplingFault::invalid));
}

TEST(Masters, EncoderUnwrapsSixteenBitCounters) {
  EncoderInput e(16);
  e.update(65530);
  EXPECT_EQ(e.update(4), 10);     // wrapped forwards
  EXPECT_EQ(e.update(65534), 4);  // and back by 6
  EncoderInput e32(32);
  e32.update(0xFFFFFFF0u);
  EXPECT_EQ(e32.update(0x10u), 32);
}

TEST(Masters, VirtualMasterIntegratesExactly) {
  VirtualMaster v(0);
  v.set_velocity(2500.5, 1e12);
  for (int i = 0; i < 1000; ++i) v.update(milliseconds(1));
  // 999.5 cycles at 2.5005 inc/cycle (the first cycle ramps from 0: trapezoid), fraction carried.
  EXPECT_EQ(v.position(), 2499);
  EXPECT_NEAR(v.exact_position(), 999.5 * 2.5005, 1e-6);
  TimeMaster t(std::chrono::microseconds(500));
  for (int i = 0; i < 10; ++i) t.update(milliseconds(1));
  EXPECT_EQ(t.position(), 20);
}

}  // namespace
}  // namespace hil::motion
