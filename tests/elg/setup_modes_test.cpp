// SPDX-License-Identifier: MIT
// The setting-up modes of C with the coupling OFF (manual ch. 7; digest §4.4): JOG/INC/REF speeds
// and steps from MD 288*/292*/296*/284*/300* and the override table, the reference point MD 240*,
// the refusals (coupled, wrong REF direction) and alarms 2035 and 184* raised by their conditions.
#include <gtest/gtest.h>

#include "hil/controllers/elg/gearbox.hpp"
#include "hil/controllers/elg/setup_modes.hpp"

namespace elg = hil::controllers::elg;
using elg::PanelMode;
using Kind = elg::SetupCommand::Kind;

namespace {

constexpr int percent_100 = 14;  // override switch position 14 = MD 112 = 100 %
constexpr int percent_20 = 8;    // position 8 = MD 106 = 20 %

/// 1000 units/min at 100 % in counts/s (1 unit = 2 counts).
constexpr double counts_per_s(double md) {
  return md * 1000.0 * 2.0 / 60.0;
}

struct SetupRig {
  explicit SetupRig(elg::SetupMachineData md = {}) : modes(md) {}
  elg::SetupModes modes;
  elg::PanelSignals p;
  std::int64_t c = 0;
  bool in_position = true;
  std::optional<elg::Alarm> step(bool coupled = false) { return modes.step(p, c, c, in_position, coupled, coupled); }
};

}  // namespace

TEST(ElgSetupModes, JogRunsAtMd288ScaledByTheOverrideWhileTheKeyIsHeld) {
  SetupRig rig;
  rig.p.mode = PanelMode::jog;
  rig.p.override_position = percent_100;
  rig.p.key_plus = true;
  EXPECT_FALSE(rig.step());
  EXPECT_EQ(rig.modes.state(), elg::SetupState::jogging);
  EXPECT_EQ(rig.modes.command().kind, Kind::velocity);
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, counts_per_s(2000));  // 66 666.7 counts/s
  rig.p.override_position = percent_20;  // the override acts during the motion
  rig.step();
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, counts_per_s(2000) * 0.2);
  rig.p.override_position = 1;  // 0 %: always a hard stop
  rig.step();
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, 0.0);
  rig.p.key_plus = false;
  rig.step();
  EXPECT_EQ(rig.modes.command().kind, Kind::none);
  EXPECT_FALSE(rig.modes.moving());
  rig.p.override_position = percent_100;
  rig.p.key_minus = true;
  rig.step();
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, -counts_per_s(2000));
}

TEST(ElgSetupModes, RapidTraverseIsMd292AndTakesTheOverrideOnlyWithRapidOverride) {
  SetupRig rig;
  rig.p.mode = PanelMode::jog;
  rig.p.override_position = percent_20;
  rig.p.rapid = true;
  rig.p.key_plus = true;
  rig.step();
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, counts_per_s(10000));  // 100 %
  rig.p.rapid_override = true;
  rig.step();
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, counts_per_s(10000) * 0.2);
  rig.p.override_position = 1;
  rig.step();
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, 0.0);
}

TEST(ElgSetupModes, Alarm2035WhenTheSetSpeedExceedsMd280AndCDoesNotTraverse) {
  SetupRig rig;  // MD 292 = 10 000, MD 280 = 10 000
  rig.p.mode = PanelMode::jog;
  rig.p.rapid = true;
  rig.p.rapid_override = true;
  rig.p.override_position = 15;  // 110 %: 11 000 > MD 280*
  rig.p.key_plus = true;
  EXPECT_EQ(rig.step(), elg::Alarm::program_speed_too_high);
  EXPECT_EQ(rig.modes.command().kind, Kind::none);
  EXPECT_FALSE(rig.modes.moving());
  EXPECT_FALSE(rig.step());  // the held key does not restart the motion
  EXPECT_FALSE(rig.modes.moving());
  // At exactly MD 280* the speed is permitted.
  rig.p.override_position = percent_100;
  rig.p.key_plus = false;
  rig.step();
  rig.p.key_plus = true;
  EXPECT_FALSE(rig.step());
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, counts_per_s(10000));
}

TEST(ElgSetupModes, IncStepsNTimesTwoMsAtMd300) {
  SetupRig rig;
  rig.c = 12345;
  rig.p.mode = PanelMode::inc;
  rig.p.inc_factor = 1000;  // 7.2: MS 0.0005 deg, switch at 1000: 1 deg = 2000 counts
  rig.p.override_position = percent_100;
  rig.p.key_plus = true;
  rig.step();
  EXPECT_EQ(rig.modes.command().kind, Kind::position);
  EXPECT_EQ(rig.modes.command().target, 12345 + 2000);
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, counts_per_s(500));
  rig.in_position = false;
  rig.p.override_position = 1;  // 0 % holds C in the middle of the step
  rig.step();
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, 0.0);
  rig.p.override_position = percent_100;
  rig.step();
  rig.c = 14345;
  rig.in_position = true;
  rig.step();
  EXPECT_FALSE(rig.modes.moving());
  rig.p.key_plus = false;
  rig.p.key_minus = true;
  rig.p.inc_factor = 10;
  rig.step();
  EXPECT_EQ(rig.modes.command().target, 14345 - 20);
}

TEST(ElgSetupModes, ReferenceApproachToCamThenZeroMarkSetsMd240) {
  elg::SetupMachineData md;
  md.ref_coordinate = 5000;
  md.zero_mark_counts = 720000;
  SetupRig rig(md);
  rig.p.mode = PanelMode::ref;
  rig.p.override_position = percent_20;  // no effect on REF without rapid_override
  rig.p.key_minus = true;                // the wrong direction (MD 564* bit 0 = 0: plus)
  rig.step();
  EXPECT_FALSE(rig.modes.moving());
  EXPECT_EQ(rig.modes.refusals(), 1);
  rig.p.key_minus = false;
  rig.step();
  rig.p.key_plus = true;  // latching: one press
  rig.step();
  rig.p.key_plus = false;
  rig.c = 100000;
  rig.step();
  EXPECT_EQ(rig.modes.state(), elg::SetupState::ref_to_cam);
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, counts_per_s(10000));  // MD 296*
  rig.p.ref_cam = true;
  rig.c = 700000;
  rig.step();
  EXPECT_EQ(rig.modes.state(), elg::SetupState::ref_to_zero_mark);
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, counts_per_s(300));  // MD 284*
  rig.c = 719999;
  rig.step();
  EXPECT_FALSE(rig.modes.referenced());
  rig.c = 720007;  // the zero mark at 720 000 was crossed
  rig.step();
  EXPECT_TRUE(rig.modes.referenced());
  EXPECT_FALSE(rig.modes.moving());
  EXPECT_EQ(rig.modes.offset(), 5000 - 720000);  // actual value at the mark = MD 240*
  EXPECT_EQ(rig.c + rig.modes.offset(), 5007);
}

TEST(ElgSetupModes, ReferenceInMinusDirectionWithMd564Bit0) {
  elg::SetupMachineData md;
  md.ref_minus = true;
  SetupRig rig(md);
  rig.p.mode = PanelMode::ref;
  rig.p.override_position = percent_100;
  rig.p.key_plus = true;  // wrong direction now
  rig.step();
  EXPECT_FALSE(rig.modes.moving());
  rig.p.key_plus = false;
  rig.p.key_minus = true;
  rig.p.ref_cam = true;  // already on the cam: straight to the zero mark
  rig.c = 10;
  rig.step();
  EXPECT_DOUBLE_EQ(rig.modes.command().velocity_counts_per_s, -counts_per_s(300));
  rig.c = -3;
  rig.step();
  EXPECT_TRUE(rig.modes.referenced());
  EXPECT_EQ(rig.modes.offset(), 0);  // mark 0, MD 240* = 0
}

TEST(ElgSetupModes, Alarm184WhenTheReferenceApproachStopsBetweenCamAndZeroMark) {
  elg::SetupMachineData md;
  md.axis_index = 1;  // C is axis 2: alarm 1841
  SetupRig rig(md);
  rig.p.mode = PanelMode::ref;
  rig.p.override_position = percent_100;
  rig.p.key_plus = true;
  rig.step();
  rig.p.ref_cam = true;
  rig.c = 1000;
  rig.step();
  rig.p.override_position = 1;  // 0 % stops the approach behind the cam
  EXPECT_EQ(rig.step(), static_cast<elg::Alarm>(1841));
  EXPECT_FALSE(rig.modes.moving());
  EXPECT_FALSE(rig.modes.referenced());
  EXPECT_EQ(elg::alarm_text(static_cast<elg::Alarm>(1841)), "STOP BEHIND REFERENCE CAMS");
  // Before the cam a mode change just ends the approach.
  SetupRig quiet(md);
  quiet.p.mode = PanelMode::ref;
  quiet.p.override_position = percent_100;
  quiet.p.key_plus = true;
  quiet.step();
  quiet.p.mode = PanelMode::jog;
  quiet.p.key_plus = false;
  EXPECT_FALSE(quiet.step());
  EXPECT_FALSE(quiet.modes.moving());
}

TEST(ElgSetupModes, WhileCoupledJogIncRefAreNotAvailable) {
  elg::GearboxConfig config;
  elg::Gearbox box(config);
  ASSERT_TRUE(box.set_input({1, 40, *elg::Decimal5::parse("0"), *elg::Decimal5::parse("0")}));
  elg::Signals s;
  elg::AxisFeedback axes;
  auto step = [&] { return box.step(s, axes); };
  s.compute = true;
  step();
  s.compute = false;
  s.gearing_on = true;
  step();
  ASSERT_TRUE(box.status().coupled);
  s.panel.mode = PanelMode::jog;
  s.panel.override_position = percent_100;
  s.panel.key_plus = true;
  const auto& st = step();
  EXPECT_EQ(st.c_mode, elg::CMode::follow);  // C keeps following the coupling
  EXPECT_EQ(box.setup().refusals(), 1);
  EXPECT_FALSE(box.setup().moving());
  EXPECT_TRUE(box.alarms().empty());
  // Uncoupled, the same key press jogs C.
  s.panel.key_plus = false;
  s.gearing_on = false;
  s.gearing_off = true;
  step();
  s.gearing_off = false;
  s.panel.key_plus = true;
  step();
  EXPECT_EQ(box.status().c_mode, elg::CMode::velocity);
  EXPECT_DOUBLE_EQ(box.status().c_velocity, counts_per_s(2000));
}

TEST(ElgSetupModes, GearingOnWhileCIsJoggedIsAlarm2207) {
  elg::Gearbox box(elg::GearboxConfig{});
  ASSERT_TRUE(box.set_input({1, 40, *elg::Decimal5::parse("0"), *elg::Decimal5::parse("0")}));
  elg::Signals s;
  elg::AxisFeedback axes;
  s.compute = true;
  box.step(s, axes);
  s.compute = false;
  s.panel.mode = PanelMode::jog;
  s.panel.override_position = percent_100;
  s.panel.key_minus = true;
  box.step(s, axes);
  ASSERT_TRUE(box.setup().moving());
  s.gearing_on = true;
  box.step(s, axes);
  EXPECT_FALSE(box.status().coupled);
  EXPECT_TRUE(box.has_alarm(elg::Alarm::gearing_not_permissible));
}

TEST(ElgSetupModes, EmergencyOffEndsAMotionAndResetEndsItQuietly) {
  elg::Gearbox box(elg::GearboxConfig{});
  elg::Signals s;
  elg::AxisFeedback axes;
  s.panel.mode = PanelMode::jog;
  s.panel.override_position = percent_100;
  s.panel.key_plus = true;
  box.step(s, axes);
  ASSERT_EQ(box.status().c_mode, elg::CMode::velocity);
  s.emergency_off = true;
  box.step(s, axes);
  EXPECT_EQ(box.status().c_mode, elg::CMode::stop);
  EXPECT_FALSE(box.setup().moving());
}

TEST(ElgSetupModes, HaeOffsetStepsFollowTheIncSelectorInInc) {
  elg::Gearbox box(elg::GearboxConfig{});  // configured n = 1000, MD 170 = 1 rpm: 24 counts per cycle
  ASSERT_TRUE(box.set_input({1, 40, *elg::Decimal5::parse("0"), *elg::Decimal5::parse("0")}));
  elg::Signals s;
  elg::AxisFeedback axes;
  s.compute = true;
  box.step(s, axes);
  s.compute = false;
  s.gearing_on = true;
  box.step(s, axes);
  ASSERT_TRUE(box.status().coupled);
  const std::int64_t c0 = box.status().c_set;
  s.hae = true;
  s.panel.mode = PanelMode::inc;
  s.panel.inc_factor = 10;  // the selector at 10: 20 counts
  s.inc_plus = true;
  box.step(s, axes);
  s.inc_plus = false;
  box.step(s, axes);
  EXPECT_EQ(box.status().c_set, c0 + 20);
}
