// SPDX-License-Identifier: MIT
// The ELG modes (digest §3-§5, §10): compute handshake, Gearing ON/OFF, single pitch with the tooth
// counter, HAE, following-error monitoring and the reset rules.
#include <gtest/gtest.h>

#include "hil/controllers/elg/gearbox.hpp"

namespace elg = hil::controllers::elg;

namespace {

elg::GearInput helical_single_pitch() {
  // The annex example (13.2): Z0 = 0, Z2 = 10, ud_z = 8.18511, ud_y = 0.
  return {0, 10, *elg::Decimal5::parse("8.18511"), *elg::Decimal5::parse("0")};
}

/// Steps the gearbox with one signal change and returns the status; the C axis follows ideally.
struct Rig {
  Rig() : Rig(elg::GearboxConfig{}) {}
  explicit Rig(const elg::GearboxConfig& config) : box(config) {}

  elg::Gearbox box;
  elg::Signals s;
  elg::AxisFeedback axes;

  const elg::GearboxStatus& step() {
    const auto& st = box.step(s, axes);
    if (st.c_mode == elg::CMode::follow || st.c_mode == elg::CMode::position) axes.c = st.c_set;
    return st;
  }
  /// Raises a signal for one cycle, then drops it.
  void pulse(bool elg::Signals::*signal) {
    s.*signal = true;
    step();
    s.*signal = false;
    step();
  }
};

}  // namespace

TEST(ElgGearbox, ComputeHandshakeSetsAndClearsTheAcknowledgement) {
  Rig rig;
  ASSERT_TRUE(rig.box.set_input(helical_single_pitch()));
  EXPECT_FALSE(rig.step().computed);
  rig.pulse(&elg::Signals::compute);
  EXPECT_TRUE(rig.box.status().computed);
  // A changed input parameter makes the constants stale (option clear_computed_on_parameter_change).
  auto changed = helical_single_pitch();
  changed.z2 = 12;
  rig.box.set_input(changed);
  EXPECT_FALSE(rig.box.status().computed);
}

TEST(ElgGearbox, GearingOnWithoutConstantsIsAlarm2207AndDoesNotCouple) {
  Rig rig;
  rig.box.set_input(helical_single_pitch());
  rig.pulse(&elg::Signals::gearing_on);
  EXPECT_FALSE(rig.box.status().coupled);
  EXPECT_TRUE(rig.box.has_alarm(elg::Alarm::gearing_not_permissible));
  EXPECT_TRUE(rig.box.status().alarm);
}

TEST(ElgGearbox, GearingOnNeedsTheApproachCondition) {
  Rig rig;
  rig.box.set_input(helical_single_pitch());
  rig.pulse(&elg::Signals::compute);
  rig.axes.c_following_error = 101;  // MD 166 default 100
  rig.pulse(&elg::Signals::gearing_on);
  EXPECT_FALSE(rig.box.status().coupled);
  EXPECT_TRUE(rig.box.has_alarm(elg::Alarm::gearing_not_permissible));
}

TEST(ElgGearbox, CoupledCFollowsTheLinkageAndOffWins) {
  Rig rig;
  rig.box.set_input({1, 40, {}, {}});
  rig.pulse(&elg::Signals::compute);
  rig.axes.c = 777;
  rig.s.gearing_on = true;
  rig.step();
  ASSERT_TRUE(rig.box.status().coupled);
  rig.axes.b = 720000;  // one hob revolution
  EXPECT_EQ(rig.step().c_set, 777 + 18000);
  EXPECT_EQ(rig.box.status().c_mode, elg::CMode::follow);
  // Parameters and the compute command are refused while coupled.
  EXPECT_FALSE(rig.box.set_input(helical_single_pitch()));
  // Both ON and OFF present: OFF wins.
  rig.s.gearing_off = true;
  EXPECT_FALSE(rig.step().coupled);
  EXPECT_EQ(rig.box.status().c_mode, elg::CMode::hold);
}

TEST(ElgGearbox, AnnexSinglePitchHelicalCycleCutsTenGapsAndEndsAtTheStart) {
  // 11.1: M52 compute, M54 EZT on, then per gap: M50 ON, Z 10 -> 60 -> 10, M51 OFF, M56 index.
  Rig rig;
  rig.box.set_input(helical_single_pitch());
  rig.axes.z = 20000;  // Z = 10 mm at 0.5 um
  rig.axes.c = 0;
  rig.pulse(&elg::Signals::compute);
  ASSERT_TRUE(rig.box.status().computed);
  rig.s.single_pitch = true;
  rig.step();
  EXPECT_EQ(rig.box.status().tooth, 1);
  std::vector<int> teeth;
  for (int gap = 0; gap < 10; ++gap) {
    const std::int64_t c_start = rig.axes.c;
    teeth.push_back(rig.box.status().tooth);
    rig.pulse(&elg::Signals::gearing_on);
    ASSERT_TRUE(rig.box.status().coupled) << "gap " << gap;
    rig.axes.b += 5000000;  // the hob turns: ignored in single pitch (Z0 = 0 and EZT)
    for (std::int64_t z = 20000; z <= 120000; z += 1000) {
      rig.axes.z = z;
      rig.step();
    }
    EXPECT_EQ(rig.axes.c - c_start, 81851) << "gap " << gap;  // +40.92555 deg
    for (std::int64_t z = 120000; z >= 20000; z -= 1000) {
      rig.axes.z = z;
      rig.step();
    }
    EXPECT_EQ(rig.axes.c, c_start) << "gap " << gap;  // -40.92555 deg: back exactly
    rig.s.gearing_off = true;
    rig.step();
    rig.s.gearing_off = false;
    ASSERT_FALSE(rig.box.status().coupled);
    rig.s.index_plus = true;  // M56
    rig.step();
    EXPECT_EQ(rig.box.status().c_mode, elg::CMode::position);
    rig.s.index_plus = false;
    rig.step();
    EXPECT_EQ(rig.axes.c - c_start, 72000) << "gap " << gap;  // one pitch = 36 deg
  }
  EXPECT_EQ(rig.axes.c, 720000);  // ten pitches: the start position mod 360 deg
  EXPECT_EQ(teeth, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10}));
  rig.s.single_pitch = false;  // M55
  rig.step();
  EXPECT_EQ(rig.box.status().tooth, 0);
}

TEST(ElgGearbox, IndexingBackwardsWrapsTheToothCounter) {
  Rig rig;
  rig.box.set_input({0, 7, {}, {}});
  rig.pulse(&elg::Signals::compute);
  rig.s.single_pitch = true;
  rig.step();
  rig.pulse(&elg::Signals::index_minus);
  EXPECT_EQ(rig.box.status().tooth, 7);
  EXPECT_EQ(rig.axes.c, -102858);  // floor(-720000/7)
  for (int i = 0; i < 6; ++i) rig.pulse(&elg::Signals::index_minus);
  EXPECT_EQ(rig.axes.c, -720000);  // seven pitches are exactly one revolution
  EXPECT_EQ(rig.box.status().tooth, 1);
}

TEST(ElgGearbox, FollowingErrorLimitRulesOfTheManual) {
  // Digest §11.4: MD 169 = 20, R40 = 50; R40 = 10 is refused (limit stays 50); R40 = 100 gives 100;
  // coupled with monitoring on and FE = 101: contact opens, alarm 2215.
  Rig rig;
  EXPECT_TRUE(rig.box.set_tolerance(50));
  EXPECT_FALSE(rig.box.set_tolerance(10));
  EXPECT_EQ(rig.step().fe_limit, 50);
  EXPECT_TRUE(rig.box.set_tolerance(100));
  EXPECT_EQ(rig.step().fe_limit, 100);
  rig.box.set_input({1, 10, {}, {}});
  rig.pulse(&elg::Signals::compute);
  rig.s.gearing_on = true;
  rig.s.fe_monitor = true;
  rig.step();
  ASSERT_TRUE(rig.box.status().coupled);
  rig.axes.c_following_error = 100;  // equal to the limit: still closed
  EXPECT_TRUE(rig.step().contact_closed);
  rig.axes.c_following_error = 101;
  EXPECT_FALSE(rig.step().contact_closed);
  EXPECT_TRUE(rig.box.has_alarm(elg::Alarm::following_error_exceeded));
  // RESET does not clear alarms while coupled.
  rig.pulse(&elg::Signals::reset);
  EXPECT_TRUE(rig.box.has_alarm(elg::Alarm::following_error_exceeded));
  // Gearing OFF re-closes the contact; RESET with the coupling OFF clears the alarm.
  rig.axes.c_following_error = 0;
  rig.s.gearing_on = false;
  rig.s.gearing_off = true;
  EXPECT_TRUE(rig.step().contact_closed);
  EXPECT_TRUE(rig.box.has_alarm(elg::Alarm::following_error_exceeded));
  rig.pulse(&elg::Signals::reset);
  EXPECT_FALSE(rig.box.status().alarm);
}

TEST(ElgGearbox, MonitoringActsOnlyWhileCoupledAndEnabled) {
  Rig rig;
  rig.axes.c_following_error = 5000;
  rig.s.fe_monitor = true;
  EXPECT_TRUE(rig.step().contact_closed);  // not coupled
  rig.box.set_input({1, 10, {}, {}});
  rig.pulse(&elg::Signals::compute);
  rig.axes.c_following_error = 0;
  rig.s.fe_monitor = false;
  rig.s.gearing_on = true;
  rig.step();
  rig.axes.c_following_error = 5000;
  EXPECT_TRUE(rig.step().contact_closed);  // coupled, monitoring off
}

TEST(ElgGearbox, Alarm2200NeedsPowerOnReset) {
  elg::GearboxConfig config;
  config.md.contour_factor_c = 150;
  elg::Gearbox box(config);
  box.set_input({1, 10, {}, {}});
  elg::Signals s;
  s.compute = true;
  box.step(s, {});
  EXPECT_TRUE(box.has_alarm(elg::Alarm::power_on_error));
  EXPECT_FALSE(box.status().computed);
  s.compute = false;
  s.reset = true;
  box.step(s, {});
  EXPECT_TRUE(box.has_alarm(elg::Alarm::power_on_error));  // RESET is not enough
  box.power_on_reset();
  EXPECT_FALSE(box.status().alarm);
}

TEST(ElgGearbox, DataStartWhileCoupledIsAlarm2214) {
  Rig rig;
  rig.box.set_input({1, 10, {}, {}});
  rig.pulse(&elg::Signals::compute);
  rig.pulse(&elg::Signals::data_start);
  EXPECT_FALSE(rig.box.has_alarm(elg::Alarm::v24_not_permitted));
  rig.s.gearing_on = true;
  rig.step();
  rig.pulse(&elg::Signals::data_start);
  EXPECT_TRUE(rig.box.has_alarm(elg::Alarm::v24_not_permitted));
}

TEST(ElgGearbox, EmergencyOffStopsCAndLatchesUntilReset) {
  Rig rig;
  rig.s.emergency_off = true;
  EXPECT_EQ(rig.step().c_mode, elg::CMode::stop);
  rig.s.emergency_off = false;
  EXPECT_EQ(rig.step().c_mode, elg::CMode::stop);  // latched
  EXPECT_TRUE(rig.box.has_alarm(elg::Alarm::emergency_off));
  rig.pulse(&elg::Signals::reset);
  EXPECT_EQ(rig.box.status().c_mode, elg::CMode::hold);
  EXPECT_FALSE(rig.box.status().alarm);
}

TEST(ElgGearbox, PartialSetValueLimitWarnsThenClampsWith2206And2205) {
  elg::GearboxConfig config;
  config.max_partial_counts = 1000;
  Rig rig(config);
  rig.box.set_input({1, 1, {}, {}});  // C follows B 1:1
  rig.pulse(&elg::Signals::compute);
  rig.s.gearing_on = true;
  rig.step();
  rig.axes.b += 950;  // 95 % of the limit: pre-warning 2206, still output
  EXPECT_EQ(rig.step().c_set, 950);
  EXPECT_TRUE(rig.box.has_alarm(elg::Alarm::partial_set_value_near_limit));
  EXPECT_FALSE(rig.box.has_alarm(elg::Alarm::partial_set_value_too_high));
  rig.axes.b += 5000;  // too high: 2205 and the maximum permissible partial set value
  EXPECT_EQ(rig.step().c_set, 1950);
  EXPECT_TRUE(rig.box.has_alarm(elg::Alarm::partial_set_value_too_high));
}

TEST(ElgGearbox, HaeCentresBetweenTheTwoFlanksAtTheMd170Speed) {
  elg::GearboxConfig config;
  config.inc_increments = 1000;  // one INC press = 2000 counts = 1 deg (7.2 example)
  Rig rig(config);
  rig.box.set_input({1, 10, {}, {}});
  rig.pulse(&elg::Signals::compute);
  rig.s.gearing_on = true;
  rig.step();
  rig.s.hae = true;
  EXPECT_EQ(rig.step().hae, elg::HaeState::approach);
  rig.pulse(&elg::Signals::inc_plus);  // +1 deg towards the first flank
  for (int i = 0; i < 20000 && rig.axes.c != 2000; ++i) rig.step();
  ASSERT_EQ(rig.axes.c, 2000);
  rig.pulse(&elg::Signals::transfer_actual);  // P1 = +2000
  EXPECT_EQ(rig.box.status().hae, elg::HaeState::one_point);
  for (int k = 0; k < 3; ++k) rig.pulse(&elg::Signals::inc_minus);  // to -4000
  for (int i = 0; i < 40000 && rig.axes.c != -4000; ++i) rig.step();
  ASSERT_EQ(rig.axes.c, -4000);
  rig.pulse(&elg::Signals::transfer_actual);  // P2 = -4000 -> centre -1000
  EXPECT_EQ(rig.box.status().hae, elg::HaeState::centring);
  // MD 170 = 1 rpm of C = 12 000 counts/s = 24 counts per 2 ms cycle: 3000 counts take 125 cycles.
  int cycles = 0;
  while (!rig.step().tooth_gap_reached && cycles < 1000) ++cycles;
  EXPECT_EQ(rig.axes.c, -1000);
  EXPECT_NEAR(cycles + 2, 125, 1);  // the two cycles of the transfer pulse move too
  rig.s.hae = false;
  EXPECT_EQ(rig.step().hae, elg::HaeState::idle);
}

TEST(ElgGearbox, RelativeIndexingCountsFromWhereTheCouplingLeftC) {
  elg::GearboxConfig config;
  config.index_on_grid = false;  // the manual's literal "moves C by one tooth pitch"
  Rig rig(config);
  rig.box.set_input({0, 10, *elg::Decimal5::parse("8.18511"), {}});
  rig.pulse(&elg::Signals::compute);
  rig.s.single_pitch = true;
  rig.step();
  rig.pulse(&elg::Signals::gearing_on);
  rig.axes.z = 1000;  // the feed does not return exactly: C stands 818.5 -> 819 counts on
  rig.step();
  rig.s.gearing_on = false;
  rig.s.gearing_off = true;
  rig.step();
  rig.s.gearing_off = false;
  rig.pulse(&elg::Signals::index_plus);
  EXPECT_EQ(rig.axes.c, 819 + 72000);
  // On the grid (the default) the same sequence lands on the pitch exactly.
  Rig grid;
  grid.box.set_input({0, 10, *elg::Decimal5::parse("8.18511"), {}});
  grid.pulse(&elg::Signals::compute);
  grid.s.single_pitch = true;
  grid.step();
  grid.pulse(&elg::Signals::gearing_on);
  grid.axes.z = 1000;
  grid.step();
  grid.s.gearing_on = false;
  grid.s.gearing_off = true;
  grid.step();
  grid.s.gearing_off = false;
  grid.pulse(&elg::Signals::index_plus);
  EXPECT_EQ(grid.axes.c, 72000);
}
