// SPDX-License-Identifier: MIT
// Supervisor rules on their own: the WF 725/726 speed-dependent window and the settle sequence.
#include <gtest/gtest.h>

#include "hil/motion/supervision.hpp"

namespace hil::motion {
namespace {

AxisConfig wf_config() {
  // MD 3 = 10 m/min, MD 24 = 11 000 um, MD 26 = 100 um -> Kv = v_max / s_max.
  AxisConfig c;
  c.name = "wf";
  c.following_error.dynamic = true;
  c.following_error.kv_per_s = (10000.0 / 60.0) / 11.0;  // 1/s
  c.following_error.min_window = 0.1;                    // mm
  c.following_error.max_window = 11.0;
  c.standstill_window = 0.04;
  c.in_position_window = 0.011;
  c.in_position_timeout = std::chrono::milliseconds(150);
  return c;
}

TEST(Supervision, DynamicWindowIsOnePointFiveFeedOverKvClamped) {
  const AxisConfig c = wf_config();
  // s_limit = 1.5 v / Kv equals MD 26 at 60.606 mm/min and MD 24 at 6.667 m/min.
  EXPECT_NEAR(Supervisor::motion_window(c, 60.606 / 60.0), 0.1, 1e-4);
  EXPECT_NEAR(Supervisor::motion_window(c, 30.0 / 60.0), 0.1, 1e-12);  // below: minimum
  EXPECT_NEAR(Supervisor::motion_window(c, 1000.0 / 60.0), 1.5 * (1000.0 / 60.0) / c.following_error.kv_per_s, 1e-12);
  EXPECT_NEAR(Supervisor::motion_window(c, 6667.0 / 60.0), 11.0, 1e-3);
  EXPECT_NEAR(Supervisor::motion_window(c, 9000.0 / 60.0), 11.0, 1e-12);  // above: maximum
  AxisConfig s = c;
  s.following_error.dynamic = false;
  s.following_error.static_window = 0.5;
  EXPECT_EQ(Supervisor::motion_window(s, 123.0), 0.5);
}

TEST(Supervision, SettleThenStandstill) {
  const AxisConfig c = wf_config();
  Supervisor sv;
  sv.start_move();
  hil::TimePoint t{};
  const auto ms = [](int n) { return std::chrono::milliseconds(n); };
  // 1 m/min: window 1.5 * 16.667 / 15.15 = 1.65 mm
  EXPECT_FALSE(sv.check(c, 1.6, 1000.0 / 60.0, true, 5.0, t));
  const hil::Fault f = sv.check(c, -1.7, 1000.0 / 60.0, true, 5.0, t);
  EXPECT_EQ(f.code, make_error_code(MotionFault::following_error_dynamic));
  EXPECT_NE(f.text.find("speed-dependent window 1.65"), std::string::npos) << f.text;
  // Profile done: settling; 0.02 off the target is outside MD 33 but the motion window applies.
  EXPECT_FALSE(sv.check(c, 0.02, 1000.0 / 60.0, false, 0.02, t));
  EXPECT_FALSE(sv.in_position());
  EXPECT_FALSE(sv.check(c, 0.02, 1000.0 / 60.0, false, 0.02, t + ms(150)));  // exactly the timeout: not yet
  const hil::Fault to = sv.check(c, 0.02, 1000.0 / 60.0, false, 0.02, t + ms(151));
  EXPECT_EQ(to.code, make_error_code(MotionFault::in_position_timeout));
  // Reached: standstill window armed.
  sv.start_move();
  EXPECT_FALSE(sv.check(c, 0.005, 10.0, false, 0.005, t));
  EXPECT_TRUE(sv.in_position());
  EXPECT_FALSE(sv.check(c, 0.039, 10.0, false, 0.039, t));
  const hil::Fault ss = sv.check(c, 0.041, 10.0, false, 0.041, t);
  EXPECT_EQ(ss.code, make_error_code(MotionFault::standstill));
  EXPECT_NE(ss.text.find("standstill window 0.04"), std::string::npos) << ss.text;
}

}  // namespace
}  // namespace hil::motion
