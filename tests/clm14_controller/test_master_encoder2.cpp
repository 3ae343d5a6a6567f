// SPDX-License-Identifier: MIT
// CLM1.4 master encoder 2 (C004-C006, §8.4) and the VEO sources beside 4/5: FUN's channel 6
// (V042 / V043), VEO 6 (master encoder 2) and VEO 0 (off) [decided], undocumented sources 0A.
#include <gtest/gtest.h>

#include "rig.hpp"

namespace hil::controllers::clm14::testing {
namespace {

using namespace std::chrono_literals;

/// A rig with master encoder 2 (1000 pulses, 4000 counts per 10 IU) on a simulated drive.
struct Me2Rig {
  explicit Me2Rig(bool attach = true) : r({{"C004", "01000 0000"}, {"C005", "0 0 00 0 0 0"}, {"C006", "0010.00000"}}) {
    auto s = make_settings([this](std::string_view n) {
      const auto it = r.params.find(std::string(n));
      return it != r.params.end() ? it->second : r.data->parameter_default(n);
    });
    EXPECT_TRUE(s.has_value());
    mocks::SimDriveConfig dc;
    dc.name = "sim:me2";
    dc.plant.kv_per_s = 200.0;
    dc.plant.max_velocity_inc_per_s = 1e8;
    dc.plant.velocity_feedforward = 1.0;
    auto cfg = master_encoder_config(s->me2, s->axes[0], "me2");
    EXPECT_TRUE(motion::validate(cfg).has_value());
    wheel = std::make_unique<motion::Axis>(cfg, std::make_unique<mocks::SimDrive>(dc));
    encoder = std::make_unique<MotionMasterEncoder>(*wheel);
    if (attach) r.clm.attach_master_encoder2(encoder.get());
    (void)wheel->enable();
  }
  void cycle() {
    r.cycle();
    wheel->update(CycleTime{r.now, r.period});
  }
  void run_for(Duration d) {
    const TimePoint end = r.now + d;
    while (r.now < end) cycle();
  }
  /// Automatic and a Start edge, the wheel updated every cycle.
  void start() {
    run_for(20ms);
    r.set(sys::automatic, true);
    cycle();
    cycle();
    r.set(sys::start, true);
    cycle();
    r.set(sys::start, false);
    cycle();
  }
  Rig r;
  std::unique_ptr<motion::Axis> wheel;
  std::unique_ptr<MotionMasterEncoder> encoder;
};

TEST(ClmMasterEncoder2, FunChannel6MeasuresItsTravel) {
  Me2Rig m;
  m.r.program({{0, "FUN 2222202"}, {1, "AKN I1.00.0 1"}, {2, "FUN 2222202"}, {3, "JMP 0003"}});
  m.start();
  m.run_for(20ms);
  (void)m.wheel->move_relative(25.0);
  m.run_for(1s);
  EXPECT_NEAR(to_double(m.r.clm.variable(42)), 25.0, 1e-9) << "4000 counts per 10 IU: exact";
  EXPECT_NEAR(m.r.clm.master2_position(), 25.0, 1e-9);
  m.r.set(bit("I1.00.0"), true);
  m.run_for(20ms);
  EXPECT_NEAR(to_double(m.r.clm.variable(43)), 25.0, 1e-9) << "digit 0: buffered in V043";
  EXPECT_NEAR(to_double(m.r.clm.variable(42)), 0.0, 1e-9) << "and restarted";
  (void)m.wheel->move_relative(-5.0);
  m.run_for(1s);
  EXPECT_NEAR(to_double(m.r.clm.variable(42)), -5.0, 1e-9);
}

TEST(ClmMasterEncoder2, VeoSource6FollowsItsVelocityAndSource0CancelsTheVeo) {
  Me2Rig m;
  m.r.program({{0, "VEO 1 6 1 000 0"},
               {1, "POI 1 +000500.000 999"},
               {2, "AKN I1.00.0 1"},
               {3, "VEO 1 0 1 000 0"},
               {4, "POI 1 +000500.000 999"},
               {5, "JMP 0005"}});
  m.run_for(50ms);  // the wheel's drive enables
  ASSERT_FALSE(m.wheel->move_velocity(50.0));
  m.run_for(500ms);
  m.start();
  m.run_for(1500ms);
  // override = |v_ME2| / Ax06 × FOL factor = 50 / 100: 99.9 IU/s × 0.5
  EXPECT_NEAR(m.r.motion_axes[0]->status().command_velocity, 49.95, 0.05);
  m.r.set(bit("I1.00.0"), true);
  m.run_for(1500ms);
  EXPECT_NEAR(m.r.motion_axes[0]->status().command_velocity, 99.9, 1e-6) << "VEO 0: no override";
}

TEST(ClmMasterEncoder2, WithoutItAndUndocumentedSourcesAre0A) {
  for (const char* line : {"FUN 2222202", "VEO 1 6 1 500 0", "VEO 1 7 1 500 0", "VEO 1 2 1 500 0"}) {
    Me2Rig m(false);
    m.r.program({{0, line}, {1, "JMP 0001"}});
    m.start();
    EXPECT_EQ(m.r.clm.error(), 0x0A) << line;
  }
}

}  // namespace
}  // namespace hil::controllers::clm14::testing
