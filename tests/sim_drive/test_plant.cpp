// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "hil/mocks/plant.hpp"

using namespace std::chrono_literals;
using hil::mocks::Plant;
using hil::mocks::PlantConfig;
using hil::mocks::PlantInput;

namespace {
PlantInput hold(double p) {
  return PlantInput{true, hil::CommandMode::position, p, 0.0};
}
}  // namespace

TEST(Plant, SettlesOnPositionCommand) {
  Plant plant(PlantConfig{.kv_per_s = 50, .velocity_lag_s = 0.001});
  for (int i = 0; i < 1000; ++i) plant.step(1ms, hold(1000.0));
  EXPECT_NEAR(plant.position_inc(), 1000.0, 0.01);
  EXPECT_EQ(plant.encoder_position_inc(), static_cast<std::int64_t>(std::floor(plant.position_inc() + 1e-9)));
}

TEST(Plant, FollowingErrorAtConstantSpeedIsVOverKv) {
  // Ramp command at v = 10000 inc/s, no feed-forward: steady lag = v / Kv = 200 inc.
  Plant plant(PlantConfig{.kv_per_s = 50, .velocity_lag_s = 0.0005});
  double cmd = 0.0;
  for (int i = 0; i < 2000; ++i) {
    cmd += 10.0;
    plant.step(1ms, PlantInput{true, hil::CommandMode::position, cmd, 10000.0});
  }
  // The command is a staircase (one set-point per 1 ms cycle): sampled at the end of a cycle the
  // lag is below its mean v/Kv by up to half a step's worth; the mean is exactly v/Kv.
  EXPECT_NEAR(cmd - plant.position_inc(), 10000.0 / 50.0, 10.0);
  EXPECT_NEAR(plant.velocity_inc_per_s(), 10000.0, 500.0);
}

TEST(Plant, FeedForwardRemovesLag) {
  Plant plant(PlantConfig{.kv_per_s = 50, .velocity_lag_s = 0.0, .velocity_feedforward = 1.0});
  double cmd = 0.0;
  for (int i = 0; i < 2000; ++i) {
    cmd += 10.0;
    plant.step(1ms, PlantInput{true, hil::CommandMode::position, cmd, 10000.0});
  }
  EXPECT_LT(std::abs(cmd - plant.position_inc()), 10.0);
}

TEST(Plant, MeasuredVelocityIsTheFeedWhereTheEndOfCycleValueIsNot) {
  // A steady feed of 40 000 inc/s in 2 ms set points at Kv 200, full feed-forward, 2 ms velocity
  // lag (the sim transport's defaults for a scenario axis): the position advances exactly 80 inc
  // per cycle, and so does the reported velocity; the instantaneous value at the end of a cycle,
  // which the drives reported before, reads about 3 % low.
  Plant plant(PlantConfig{.kv_per_s = 200, .velocity_lag_s = 0.002, .velocity_feedforward = 1.0});
  double cmd = 0.0;
  for (int i = 0; i < 1000; ++i) {
    cmd += 80.0;
    plant.step(2ms, PlantInput{true, hil::CommandMode::position, cmd, 40000.0});
  }
  const double before = plant.position_inc();
  cmd += 80.0;
  plant.step(2ms, PlantInput{true, hil::CommandMode::position, cmd, 40000.0});
  EXPECT_NEAR(plant.position_inc() - before, 80.0, 1e-6);
  EXPECT_NEAR(plant.measured_velocity_inc_per_s(), 40000.0, 1e-3);
  EXPECT_LT(plant.velocity_inc_per_s(), 0.99 * 40000.0);
}

TEST(Plant, VelocityLimitClamps) {
  Plant plant(PlantConfig{.kv_per_s = 100, .max_velocity_inc_per_s = 500, .velocity_lag_s = 0.0});
  for (int i = 0; i < 100; ++i) plant.step(1ms, hold(1e6));
  EXPECT_NEAR(plant.velocity_inc_per_s(), 500.0, 1e-6);
  EXPECT_NEAR(plant.position_inc(), 50.0, 0.5);
}

TEST(Plant, EncoderQuantisation) {
  Plant plant(
      PlantConfig{.kv_per_s = 50, .velocity_lag_s = 0.0, .encoder_step_inc = 16, .initial_position_inc = 100.0});
  EXPECT_EQ(plant.encoder_position_inc(), 96);
  plant.set_position(-1.0);
  EXPECT_EQ(plant.encoder_position_inc(), -16);
}

TEST(Plant, VelocityModeFollowsTargetThroughLag) {
  Plant plant(PlantConfig{.velocity_lag_s = 0.01});
  plant.step(10ms, PlantInput{true, hil::CommandMode::velocity, 0.0, 1000.0});
  EXPECT_NEAR(plant.velocity_inc_per_s(), 1000.0 * (1.0 - std::exp(-1.0)), 1.0);
}

TEST(Plant, EncoderFaultFreezesReading) {
  Plant plant(PlantConfig{.velocity_lag_s = 0.0});
  plant.inject(hil::PlantFault::encoder);
  for (int i = 0; i < 100; ++i) plant.step(1ms, PlantInput{true, hil::CommandMode::velocity, 0.0, 1000.0});
  EXPECT_EQ(plant.encoder_position_inc(), 0);
  EXPECT_GT(plant.position_inc(), 50.0);
  EXPECT_EQ(plant.fault(), hil::PlantFault::encoder);
  plant.inject(hil::PlantFault::encoder, false);
  plant.step(1ms, PlantInput{});
  EXPECT_GT(plant.encoder_position_inc(), 50);
}

TEST(Plant, BlowupStopsFollowingAndUnpoweredCoasts) {
  Plant plant(PlantConfig{.velocity_lag_s = 0.0});
  plant.inject(hil::PlantFault::following_blowup);
  for (int i = 0; i < 100; ++i) plant.step(1ms, hold(1000.0));
  EXPECT_NEAR(plant.position_inc(), 0.0, 1e-9);
  Plant coast(PlantConfig{.velocity_lag_s = 0.01});
  coast.step(100ms, PlantInput{true, hil::CommandMode::velocity, 0.0, 1000.0});
  coast.step(200ms, PlantInput{});
  EXPECT_LT(std::abs(coast.velocity_inc_per_s()), 1.0);
}

TEST(Plant, AnyGainIntegratesInABoundedNumberOfSubSteps) {
  // A gain far beyond what the sub-step resolves (the old loop ran 5 million sub-steps per 1 ms
  // cycle at Kv = 1e9 and never ended at 1e20) costs at most max_substeps and stays stable.
  for (double kv : {50.0, 1e4, 1e9, 1e20, std::numeric_limits<double>::infinity()}) {
    Plant plant(PlantConfig{.kv_per_s = kv, .velocity_lag_s = 0.001});
    std::size_t most = 0;
    for (int i = 0; i < 200; ++i) most = std::max(most, plant.step(1ms, hold(1000.0)));
    EXPECT_LE(most, Plant::max_substeps) << "kv " << kv;
    EXPECT_NEAR(plant.position_inc(), 1000.0, 1.0) << "kv " << kv;
  }
  Plant plant(PlantConfig{.kv_per_s = 1e20});
  EXPECT_LE(plant.step(std::chrono::seconds(3600), hold(5.0)), Plant::max_substeps) << "a long step too";
  EXPECT_TRUE(std::isfinite(plant.position_inc()));
}
