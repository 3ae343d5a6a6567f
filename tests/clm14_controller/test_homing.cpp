// SPDX-License-Identifier: MIT
// The CLM1.4's own homing (manual §7.9, digest §5.7): options 1-5 against a home cam in the
// image and the encoder's marker, the errors 49/4A/4B/4F/52, termination, the Ax24 output.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "hil/motion/zero_mark.hpp"
#include "rig.hpp"

namespace hil::controllers::clm14::testing {
namespace {

using namespace std::chrono_literals;

// 1024 lines × 4 = 4096 increments per revolution of 10 IU: a marker every 10 IU of raw travel.
constexpr double inc_per_iu = 409.6;

/// A home cam active while the raw (mechanical) position of axis 1 is in [from, to], wired to
/// I1.00.1 (the profile's Ax23 home switch), read as the CLM reads its inputs at the cycle start.
struct Cam {
  double from = 0.0;
  double to = 0.0;
};

double raw(const Rig& r, int axis = 1) {
  return r.motion_axes[static_cast<std::size_t>(axis - 1)]->status().position;
}

bool run_cam(Rig& r, Cam cam, const std::function<bool()>& done, Duration limit = 30s) {
  const TimePoint end = r.now + limit;
  while (r.now < end) {
    const double p = raw(r);
    r.set(bit("I1.00.1"), p >= cam.from && p <= cam.to);
    r.cycle();
    if (done()) return true;
  }
  return false;
}

/// Home with HOM 1 in Automatic; true when homed or an error stopped it.
bool hom_auto(Rig& r, Cam cam) {
  r.program({{0, "HOM 1"}, {1, "AKN M2.01.0 1"}, {2, "JST 0002"}});
  r.enter_auto();
  r.set(sys::start, true);
  if (!run_cam(r, cam, [&] { return r.clm.task(1).pc == 2 || r.clm.error() != 0; })) return false;
  (void)run_cam(
      r, cam, [] { return false; }, 100ms);  // the axis comes to rest
  return true;
}

/// The CLM position that raw position `p` reads at now.
double clm_at(const Rig& r, double p) {
  return r.pos() - (raw(r) - p);
}

TEST(ZeroMarkGrid, PassesEachMarkOnceInEitherDirection) {
  const motion::ZeroMarkGrid g{4096, 100};
  EXPECT_EQ(g.passed(0, 99), std::nullopt);
  EXPECT_EQ(g.passed(0, 100), 100);
  EXPECT_EQ(g.passed(100, 4195), std::nullopt) << "leaving a mark forward is not passing it";
  EXPECT_EQ(g.passed(100, 9000), 4196) << "the first mark in the direction of travel";
  EXPECT_EQ(g.passed(4196, 4195), 4196) << "a mark is left backward at once";
  EXPECT_EQ(g.passed(-3000, -5000), -3996);
  EXPECT_TRUE(g.on_mark(-3996));
  EXPECT_FALSE(g.on_mark(-3995));
  EXPECT_EQ(g.index(-3996), -1);
}

TEST(ClmHoming, Option1CamThenMarkerNormsTheMarkerToAx25) {
  Rig r({{"A124", "M2.01.0 +100 0"}, {"A125", "+00005.000"}});
  ASSERT_TRUE(hom_auto(r, {25.0, 1000.0})) << r.clm.error_message();
  ASSERT_EQ(r.clm.error(), 0) << r.clm.error_message();
  EXPECT_TRUE(r.clm.homed(1));
  EXPECT_TRUE(r.get(bit("M2.01.0")));
  // The first marker after the cam edge at 25 is the one at raw 30 (12288 increments): it reads Ax25.
  EXPECT_NEAR(clm_at(r, 30.0), 5.0, 1e-9);
  // Crept back to the marker at <= 1 increment per cycle: standing within a few increments of it.
  EXPECT_NEAR(raw(r), 30.0, 5.0 / inc_per_iu);
}

TEST(ClmHoming, Option1StartedOnTheCamLeavesItFirst) {
  Rig r({{"A124", "M2.01.0 +100 0"}});
  ASSERT_TRUE(hom_auto(r, {-3.0, 1000.0})) << r.clm.error_message();
  ASSERT_EQ(r.clm.error(), 0) << r.clm.error_message();
  // Edge at -3: the first marker after it is raw 0 (3 IU = 0.3 revolution behind the edge).
  EXPECT_NEAR(clm_at(r, 0.0), 0.0, 1e-9);
}

TEST(ClmHoming, Option1MarkerTooCloseToTheCamEdgeIs4B) {
  Rig r({{"A124", "M2.01.0 +100 0"}});
  ASSERT_TRUE(hom_auto(r, {29.9, 1000.0}));
  EXPECT_EQ(r.clm.error(), 0x4B) << "0.1 IU = 41 increments < 1/16 revolution: " << r.clm.error_message();
  EXPECT_FALSE(r.clm.homed(1));
  Rig l({{"A124", "M2.01.0 +100 0"}});
  ASSERT_TRUE(hom_auto(l, {20.1, 1000.0}));
  EXPECT_EQ(l.clm.error(), 0x4B) << "9.9 IU > 15/16 revolution: " << l.clm.error_message();
}

TEST(ClmHoming, CamTooShortIs49) {
  Rig r({{"A124", "M2.01.0 +100 0"}});
  ASSERT_TRUE(hom_auto(r, {25.0, 25.03}));
  EXPECT_EQ(r.clm.error(), 0x49) << "braked past a 0.03 IU cam: " << r.clm.error_message();
  Rig s({{"A124", "M2.01.0 +100 0"}});
  ASSERT_TRUE(hom_auto(s, {25.0, 27.0}));
  EXPECT_EQ(s.clm.error(), 0x49) << "the cam ends before its marker at 30: " << s.clm.error_message();
}

TEST(ClmHoming, NoMarkerIs4AAndAStuckMarkerIs4F) {
  Options o;
  o.markers[0].input = bit("I1.05.0");  // a wired index signal that never comes
  Rig r({{"A124", "M2.01.0 +100 0"}}, 1, o);
  ASSERT_TRUE(hom_auto(r, {25.0, 1000.0}));
  EXPECT_EQ(r.clm.error(), 0x4A) << r.clm.error_message();
  EXPECT_NEAR(raw(r), 35.0, 0.2) << "searched one revolution behind the edge";
  Rig s({{"A124", "M2.01.0 +100 1"}}, 1, o);
  s.set(bit("I1.05.0"), true);  // stuck high
  ASSERT_TRUE(hom_auto(s, {1000.0, 2000.0}));
  EXPECT_EQ(s.clm.error(), 0x4F) << s.clm.error_message();
}

TEST(ClmHoming, HomingNotPossibleIs52) {
  Rig r({{"A124", "M2.01.0 +100 0"}, {"A123", "00.00.0 00.00.0"}});
  ASSERT_TRUE(hom_auto(r, {25.0, 1000.0}));
  EXPECT_EQ(r.clm.error(), 0x52) << "option 1 without a home switch";
  EXPECT_EQ(r.clm.error_item(1), "0000") << "the HOM line";
  Rig l({{"A124", "M2.01.0 +100 2"}, {"A103", "-000010.000"}, {"A104", "+000020.000"}});
  ASSERT_TRUE(hom_auto(l, {500.0, 1000.0}));
  EXPECT_EQ(l.clm.error(), 0x52) << "no switch edge over the travel Ax04 - Ax03 = 30 IU";
  EXPECT_NEAR(raw(l), 30.0, 0.1);
  Rig p({{"A124", "M2.01.0 +100 4"}});
  ASSERT_TRUE(hom_auto(p, {25.0, 1000.0}));
  EXPECT_EQ(p.clm.error(), 0x52) << "option 5 is passive";
  Rig a({{"A124", "M2.01.0 +100 1"}, {"A120", "2 0 24 1"}});
  ASSERT_TRUE(hom_auto(a, {25.0, 1000.0}));
  EXPECT_EQ(a.clm.error(), 0x52) << "absolute encoder";
}

TEST(ClmHoming, Option2TakesTheSecondMarker) {
  Rig r({{"A124", "M2.01.0 -100 1"}, {"A125", "-00001.500"}});
  ASSERT_TRUE(hom_auto(r, {1000.0, 2000.0})) << r.clm.error_message();
  ASSERT_EQ(r.clm.error(), 0) << r.clm.error_message();
  // Backward from 0 (on a marker): the first marker passed is 0 itself, the second -10.
  EXPECT_NEAR(clm_at(r, -10.0), -1.5, 1e-9);
  EXPECT_NEAR(raw(r), -10.0, 5.0 / inc_per_iu);
}

TEST(ClmHoming, EncoderMarkerOffsetMovesTheReference) {
  Options o;
  o.markers[0].offset_inc = 1024;  // a quarter revolution: marks at raw 2.5, 12.5, ...
  Rig r({{"A124", "M2.01.0 +100 1"}}, 1, o);
  ASSERT_TRUE(hom_auto(r, {1000.0, 2000.0})) << r.clm.error_message();
  EXPECT_NEAR(clm_at(r, 12.5), 0.0, 1e-9);
}

TEST(ClmHoming, Option3TakesTheRisingSwitchEdge) {
  Rig r({{"A124", "M2.01.0 +100 2"}, {"A125", "+00100.000"}});
  ASSERT_TRUE(hom_auto(r, {25.0, 1000.0})) << r.clm.error_message();
  ASSERT_EQ(r.clm.error(), 0) << r.clm.error_message();
  // Sampled once per cycle: the edge is seen within one cycle of travel at V1 = 10 IU/s.
  EXPECT_NEAR(clm_at(r, 25.0), 100.0, 10.0 * 0.002 + 1e-9);
  // Started on the switch, option 3 needs a rising edge ahead; option 4 leaves the switch first.
  Rig on({{"A124", "M2.01.0 +100 2"}, {"A103", "-000010.000"}, {"A104", "+000020.000"}});
  ASSERT_TRUE(hom_auto(on, {-5.0, 1000.0}));
  EXPECT_EQ(on.clm.error(), 0x52);
  Rig leave({{"A124", "M2.01.0 +100 3"}});
  ASSERT_TRUE(hom_auto(leave, {-5.0, 1000.0})) << leave.clm.error_message();
  ASSERT_EQ(leave.clm.error(), 0) << leave.clm.error_message();
  EXPECT_NEAR(clm_at(leave, -5.0), 0.0, 10.0 * 0.002 + 1e-9);
}

TEST(ClmHoming, Option5HomesWhereJog1LeavesTheSwitch) {
  Rig r({{"A124", "M2.01.0 +100 4"}, {"A125", "-00002.000"}});
  r.run_for(20ms);
  EXPECT_FALSE(r.clm.homed(1));
  r.set(sys::jog_forward[0], true);
  ASSERT_TRUE(run_cam(
      r, {-1000.0, 5.0}, [&] { return r.clm.homed(1); }, 5s));
  r.set(sys::jog_forward[0], false);
  r.run_for(200ms);
  EXPECT_NEAR(clm_at(r, 5.0), -2.0, 50.0 * 0.002 + 1e-9) << "Ax07 50 IU/s, sampled per cycle";
}

TEST(ClmHoming, HomingInputInManualAndImmediateStopAbortsIt) {
  Rig r({{"A124", "M2.01.0 +100 1"}});
  r.run_for(20ms);
  r.pulse(bit("I1.00.0"));  // Ax23 homing start
  r.run_for(300ms);
  EXPECT_GT(raw(r), 1.0) << "searching the first marker";
  r.set(sys::immediate_stop_ok, false);
  r.run_for(500ms);
  const double stopped = raw(r);
  r.set(sys::immediate_stop_ok, true);
  r.run_for(1s);
  EXPECT_FALSE(r.clm.homed(1)) << "aborted; it must be started again";
  EXPECT_NEAR(raw(r), stopped, 1e-6);
  r.pulse(bit("I1.00.0"));
  ASSERT_TRUE(r.run_until([&] { return r.clm.homed(1); }, 10s));
  EXPECT_EQ(r.clm.error(), 0);
}

TEST(ClmHoming, ImmediateStopInAutomaticRestartsHomOnStart) {
  Rig r({{"A124", "M2.01.0 +100 1"}});
  r.program({{0, "HOM 1"}, {1, "AKN M2.01.0 1"}, {2, "JST 0002"}});
  r.start_auto();
  r.run_for(300ms);
  r.set(sys::immediate_stop_ok, false);
  r.run_for(500ms);
  EXPECT_FALSE(r.clm.homed(1));
  r.set(sys::immediate_stop_ok, true);
  r.run_for(200ms);
  EXPECT_FALSE(r.clm.homed(1)) << "waits for Start";
  r.pulse(sys::start);
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 2; }, 10s));
  EXPECT_TRUE(r.clm.homed(1));
}

TEST(ClmHoming, TheProgramMayClearTheHomedOutput) {
  Rig r({{"A124", "M2.01.0 +100 1"}});
  r.program({{0, "HOM 1"}, {1, "AKN M2.01.0 1"}, {2, "POI 1 +000001.000 999"}, {3, "AEA M2.01.0 0"}, {4, "JST 0004"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 4; }, 10s)) << r.clm.error_message();
  r.run_for(100ms);
  EXPECT_FALSE(r.get(bit("M2.01.0")));
  EXPECT_TRUE(r.clm.homed(1));
}

TEST(ClmHoming, DriveHomingOption) {
  Options o;
  o.drive_homing = true;
  Rig r({{"A124", "M2.01.0 +100 0"}, {"A125", "+00007.000"}}, 1, o);
  r.program({{0, "HOM 1"}, {1, "AKN M2.01.0 1"}, {2, "JST 0002"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 2; }, 2s)) << r.clm.error_message();
  EXPECT_NEAR(r.pos(), 7.0, 1e-9) << "the drive homed where it stood";
}

}  // namespace
}  // namespace hil::controllers::clm14::testing
