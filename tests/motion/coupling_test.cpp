// SPDX-License-Identifier: MIT
// Coupling with supervision: the slave's output never exceeds its velocity/acceleration limits
// (random masters and laws, fixed seed: a fault instead), the coupling following-error monitor,
// superimposed moves add exactly, and a geared Axis over the simulated plant.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hil/mocks/sim_drive.hpp"
#include "hil/motion/axis.hpp"
#include "hil/motion/coupling.hpp"
#include "hil/motion/master.hpp"

namespace hil::motion {
namespace {

using std::chrono::milliseconds;

TEST(Coupling, OutputNeverExceedsTheSlaveLimits) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> vel(-60000.0, 60000.0), acc(1e4, 2e6);
  std::uniform_int_distribution<std::int64_t> num(-9, 9), ramp(0, 20000);
  const CamTable cam = *CamTable::make(
      {{{0, 0}, {2500, 400}, {5000, 3000}, {7500, 5600}, {10000, 6000}}, CamInterpolation::cubic_periodic, true});
  const double T = 0.001;
  int faults = 0, clean = 0;
  for (int trial = 0; trial < 300; ++trial) {
    SlaveLimits lim{1e5, 2e7, 1, 0.0};
    Coupling c("slave", lim);
    const bool use_cam = trial % 3 == 0;
    c.use(use_cam ? Coupling::Law::cam : Coupling::Law::gear);
    c.cam().set_table(&cam);
    VirtualMaster master(0);
    c.start(0, 0);
    if (!use_cam) {
      ASSERT_FALSE(c.gear().engage({num(rng), 4}, ramp(rng), 1000));
    }
    double prev_p = 0, prev_v = 0;
    for (int i = 0; i < 3000; ++i) {
      if (i % 500 == 0) master.set_velocity(vel(rng), acc(rng));
      if (!use_cam && i == 1500) (void)c.gear().change({{num(rng), 3}, ramp(rng), {}});
      if (trial % 5 == 1 && i == 700) (void)c.superimposed().move_by(5000, Limits{20000, 1e6, 1e9});
      const auto& out = c.update(master.update(milliseconds(1)), milliseconds(1));
      const double v = (out.position - prev_p) / T, a = (v - prev_v) / T;
      ASSERT_LE(std::fabs(v), lim.velocity * (1 + 1e-9)) << "trial " << trial << " cycle " << i;
      if (i > 0) {
        ASSERT_LE(std::fabs(a), lim.acceleration * (1 + 1e-6)) << "trial " << trial << " cycle " << i;
      }
      prev_p = out.position;
      prev_v = v;
    }
    if (c.faulted()) {
      ++faults;
      EXPECT_EQ(c.fault().code.category(), coupling_category());
      EXPECT_NE(c.fault().text.find("coupling 'slave'"), std::string::npos);
    } else {
      ++clean;
    }
  }
  // Both outcomes occur (the random demands are chosen around the limits).
  EXPECT_GT(faults, 20);
  EXPECT_GT(clean, 20);
}

TEST(Coupling, VelocityFaultBrakesToRestAndResetResynchronises) {
  Coupling c("y", SlaveLimits{10000, 1e7, 1, 0});
  c.use(Coupling::Law::gear);
  ASSERT_FALSE(c.gear().engage({1, 1}));
  c.start(0, 0);
  std::int64_t m = 0;
  for (int i = 0; i < 20; ++i) c.update(m += 5, milliseconds(1));  // 5000 inc/s: fine
  ASSERT_FALSE(c.faulted());
  c.update(m += 30, milliseconds(1));  // 30000 inc/s demanded
  ASSERT_TRUE(c.faulted());
  EXPECT_EQ(c.fault().code, make_error_code(CouplingFault::velocity_limit));
  for (int i = 0; i < 20; ++i) c.update(m += 30, milliseconds(1));
  EXPECT_EQ(c.output().velocity_inc_per_s, 0.0);
  const double held = c.output().position;
  c.reset(m);
  EXPECT_FALSE(c.faulted());
  c.update(m += 5, milliseconds(1));
  EXPECT_NEAR(c.output().position, held + 5, 1e-9);  // continues from where it stood
}

TEST(Coupling, FollowingErrorMonitor) {
  Coupling c("y", SlaveLimits{1e9, 1e12, 1, 50});
  c.use(Coupling::Law::gear);
  ASSERT_FALSE(c.gear().engage({2, 1}));
  c.start(0, 0);
  std::int64_t m = 0;
  for (int i = 0; i < 10; ++i) {
    const auto& o = c.update(m += 10, milliseconds(1), c.output().position_inc - 20);
    ASSERT_FALSE(o.faulted);
  }
  c.update(m += 10, milliseconds(1), c.output().position_inc - 51);
  ASSERT_TRUE(c.faulted());
  EXPECT_EQ(c.fault().code, make_error_code(CouplingFault::following_error));
}

TEST(Coupling, SuperimposedMoveAddsItsDistanceExactly) {
  Coupling c("y");
  c.use(Coupling::Law::gear);
  ASSERT_FALSE(c.gear().engage({1, 2}));
  c.start(0, 0);
  ASSERT_FALSE(c.superimposed().move_by(1234, Limits{50000, 1e6, 1e8}));
  std::int64_t m = 0;
  for (int i = 0; i < 2000; ++i) c.update(m += 7, milliseconds(1));
  EXPECT_FALSE(c.superimposed().busy());
  EXPECT_EQ(c.output().position_inc, 1234 + 7 * 2000 / 2);
  EXPECT_TRUE(c.superimposed().move_by(NAN, Limits{1, 1, 1}));
}

TEST(Coupling, GearedAxisOnTheSimulatedPlant) {
  AxisConfig cfg;
  cfg.name = "slave";
  cfg.inc_per_unit = {1000, 1};
  cfg.limits = {500.0, 5000.0, 1e6};
  cfg.quick_stop_deceleration = 20000.0;
  cfg.jog_velocity = 10.0;
  cfg.following_error.static_window = 5.0;
  cfg.standstill_window = 0.05;
  cfg.in_position_window = 0.01;
  ASSERT_TRUE(validate(cfg).has_value()) << validate(cfg).error();
  mocks::SimDriveConfig d;
  d.name = "sim:slave";
  d.plant.kv_per_s = 100.0;
  d.plant.max_velocity_inc_per_s = 1e7;
  Axis axis(cfg, std::make_unique<mocks::SimDrive>(d));
  hil::TimePoint now{};
  auto cycle = [&] { return axis.update(CycleTime{now += milliseconds(1), milliseconds(1)}); };
  cycle();
  ASSERT_FALSE(axis.enable());
  for (int i = 0; i < 50 && axis.status().state != AxisState::standstill; ++i) cycle();
  ASSERT_EQ(axis.status().state, AxisState::standstill);

  Coupling c("slave", SlaveLimits{500.0 * 1000, 5000.0 * 1000, 1, 3000});
  c.use(Coupling::Law::gear);
  VirtualMaster master(0);
  c.start(0, axis.status().position_inc);
  ASSERT_FALSE(c.gear().engage({3, 4}, 20000, 10000));  // engage over 20000 master inc from 10000
  master.set_velocity(200000, 1e6);
  for (int i = 0; i < 3000; ++i) {
    const auto& out = c.update(master.update(milliseconds(1)), milliseconds(1), axis.status().position_inc);
    ASSERT_FALSE(axis.follow(out.position_inc, out.velocity_inc_per_s, out.acceleration_inc_per_s2));
    ASSERT_EQ(cycle(), CycleResult::ok) << axis.status().fault.describe();
  }
  EXPECT_FALSE(c.faulted()) << c.fault().describe();
  EXPECT_EQ(axis.status().state, AxisState::moving);
  // Geared at 3/4 behind the ramp: the command is exact, the actual lags by v/Kv.
  const std::int64_t m = master.position();
  EXPECT_EQ(c.output().position_inc,
            static_cast<std::int64_t>(std::floor(7500 + 0.75 * static_cast<double>(m - 30000) + 0.5)));
  EXPECT_NEAR(axis.status().command_velocity, 150.0, 1.0);
  // stop() ends the coupling with a ramp under the axis limits.
  ASSERT_FALSE(axis.stop());
  for (int i = 0; i < 200; ++i) ASSERT_EQ(cycle(), CycleResult::ok);
  EXPECT_EQ(axis.status().state, AxisState::standstill);
}

}  // namespace
}  // namespace hil::motion
