// SPDX-License-Identifier: MIT
// The linkage equations and the compute step against the manual's gear maths (digest §2.5-§2.7).
#include <gtest/gtest.h>

#include "hil/controllers/elg/gear.hpp"

namespace elg = hil::controllers::elg;

namespace {
elg::GearInput input(int z0, int z2, const char* ud_z = "0", const char* ud_y = "0") {
  return {z0, z2, *elg::Decimal5::parse(ud_z), *elg::Decimal5::parse(ud_y)};
}
}  // namespace

TEST(ElgDecimal, ParsesFiveDecimals) {
  EXPECT_EQ(elg::Decimal5::parse("8.18511")->e5, 818511);
  EXPECT_EQ(elg::Decimal5::parse("-0.5")->e5, -50000);
  EXPECT_EQ(elg::Decimal5::parse("12")->e5, 1200000);
  EXPECT_EQ(elg::Decimal5::parse(".25")->e5, 25000);
  EXPECT_FALSE(elg::Decimal5::parse("1.123456"));
  EXPECT_FALSE(elg::Decimal5::parse("1,5"));
  EXPECT_FALSE(elg::Decimal5::parse(""));
  EXPECT_FALSE(elg::Decimal5::parse("-"));
}

TEST(ElgGear, SpurOneHobRevolutionTurnsCByOneToothPitchOverZ2) {
  // Digest §2.7 [D]: Z0 = 1, Z2 = 40, N00 = N02 = 180 000: one hob revolution = 720 000 B counts,
  // C moves 9 deg = 18 000 counts (MS 0.0005 deg); up milling (Z0 = -1) moves it -9 deg.
  const elg::GearMachineData md;
  auto k = elg::compute_constants(input(1, 40), md);
  ASSERT_TRUE(k);
  elg::Linkage link(*k, 0, 0, 0, 0, true);
  EXPECT_EQ(*link.c_set(720000, 0, 0), 18000);
  auto up = elg::compute_constants(input(-1, 40), md);
  ASSERT_TRUE(up);
  EXPECT_EQ(*elg::Linkage(*up, 0, 0, 0, 0, true).c_set(720000, 0, 0), -18000);
}

TEST(ElgGear, DifferentEncoderResolutionsEnterTheRatio) {
  // N00 = 90 000 (coarser hob encoder): one hob revolution = 360 000 B counts, still 9 deg of C.
  elg::GearMachineData md;
  md.n00 = 90000;
  auto k = elg::compute_constants(input(1, 40), md);
  ASSERT_TRUE(k);
  EXPECT_EQ(*elg::Linkage(*k, 0, 0, 0, 0, true).c_set(360000, 0, 0), 18000);
}

TEST(ElgGear, HelicalAxialTermOfTheManualsExample) {
  // Digest §2.7 [D]: ud_z = 8.18511, Z2 = 10, Z from 10 to 60 mm (50 mm = 100 000 counts of
  // 0.5 um): C turns 50 * 8.18511 / 10 = 40.92555 deg = 81 851.1 counts -> 81 851.
  auto k = elg::compute_constants(input(0, 10, "8.18511"), elg::GearMachineData{});
  ASSERT_TRUE(k);
  elg::Linkage link(*k, 0, 20000, 0, 5000, true);
  EXPECT_EQ(*link.c_set(123456, 120000, 0), 5000 + 81851);
  EXPECT_EQ(*link.c_set(123456, 20000, 0), 5000);  // back to the start: exactly back
}

TEST(ElgGear, DiagonalFeedAddsTheTangentialTerm) {
  // ud_y = 114.59156 (gamma0 = 0, m_N = 1), Z2 = 20: Y +1 mm turns C by 5.729578 deg = 11 459.156
  // counts; with Z0 = 2 and half a hob revolution (360 000 counts) C adds 18 deg = 36 000 counts.
  auto k = elg::compute_constants(input(2, 20, "0", "114.59156"), elg::GearMachineData{});
  ASSERT_TRUE(k);
  elg::Linkage link(*k, 0, 0, 0, 0, true);
  EXPECT_EQ(*link.c_set(0, 0, 2000), 11459);
  EXPECT_EQ(*link.c_set(360000, 0, 2000), 36000 + 11459);
  // Single pitch drops the cutter term.
  elg::Linkage ezt(*k, 0, 0, 0, 0, false);
  EXPECT_EQ(*ezt.c_set(360000, 0, 2000), 11459);
}

TEST(ElgGear, UdHelpersFollowTheManualsFormulas) {
  EXPECT_NEAR(elg::ud_z_from_gear(30.0, 7.0), 8.18511, 5e-6);   // sin 30 / (7 pi) * 360
  EXPECT_NEAR(elg::ud_y_from_gear(0.0, 1.0), 114.59156, 5e-6);  // 360 / pi
  EXPECT_EQ(elg::Decimal5::from_double(elg::ud_z_from_gear(30.0, 7.0)).e5, 818511);
}

TEST(ElgGear, Alarm2203OnTheManualsConditions) {
  const elg::GearMachineData md;
  EXPECT_EQ(elg::compute_constants(input(1, 0), md).error(), elg::Alarm::constants_error);  // Z2 = 0
  elg::GearMachineData no_c = md;
  no_c.n02 = 0;
  EXPECT_EQ(elg::compute_constants(input(1, 10), no_c).error(), elg::Alarm::constants_error);
  EXPECT_TRUE(elg::compute_constants(input(0, 10), no_c));  // N02 = 0 is fine with Z0 = 0
  // Transmission parameter too high: 999/2 hob starts per tooth with a 1-pulse hob encoder.
  elg::GearMachineData odd = md;
  odd.n00 = 1;
  odd.n02 = 2000000;
  EXPECT_EQ(elg::compute_constants(input(999, 2), odd).error(), elg::Alarm::constants_error);
  // Differential parameter too high: 1 mm per Z count at 1000 deg/mm.
  elg::GearMachineData coarse = md;
  coarse.ms_z_nm = 1000000;
  coarse.n02 = 2000000;
  EXPECT_EQ(elg::compute_constants(input(0, 2, "999.99999"), coarse).error(), elg::Alarm::constants_error);
  // Odd encoder counts are fine: the constants stay exact ratios.
  elg::GearMachineData prime = md;
  prime.n02 = 1999993;
  prime.ms_z_nm = 100;
  EXPECT_TRUE(elg::compute_constants(input(3, 991, "999.99997"), prime));
}

TEST(ElgGear, Alarm2200OnTheMachineData) {
  elg::GearMachineData md;
  md.n02 = 2500000;  // MD 396* above the maximum input 2 000 000
  EXPECT_EQ(elg::compute_constants(input(1, 10), md).error(), elg::Alarm::power_on_error);
  md = {};
  md.contour_factor_c = 150;  // MD 252* < 200
  EXPECT_EQ(elg::compute_constants(input(1, 10), md).error(), elg::Alarm::power_on_error);
  md = {};
  md.hae_speed = 30001;  // MD 170 too high
  EXPECT_EQ(elg::compute_constants(input(1, 10), md).error(), elg::Alarm::power_on_error);
  md = {};
  md.axis_declaration_ok = false;  // MD 5020/5021 order
  EXPECT_EQ(elg::compute_constants(input(1, 10), md).error(), elg::Alarm::power_on_error);
}

TEST(ElgGear, PitchIsExactForAnyToothCount) {
  // 4 * 180 000 / 7 is not an integer: the pitch stays an exact ratio.
  auto k = elg::compute_constants(input(0, 7), elg::GearMachineData{});
  ASSERT_TRUE(k);
  EXPECT_EQ(k->pitch.num * 7, 720000 * k->pitch.den);
  EXPECT_EQ(k->pitch_counts, 102857);
}

TEST(ElgGear, OverflowIsAlarm2202NotUndefinedBehaviour) {
  auto k = elg::compute_constants(input(999, 2), elg::GearMachineData{});
  ASSERT_TRUE(k);
  elg::Linkage link(*k, 0, 0, 0, 0, true);
  EXPECT_EQ(link.c_set(std::int64_t{1} << 62, 0, 0).error(), elg::Alarm::partial_set_value_overflow);
  EXPECT_EQ(link.c_set(std::numeric_limits<std::int64_t>::min(), 0, 0).error(), elg::Alarm::partial_set_value_overflow);
}

TEST(ElgAlarm, CategoryCarriesTheManualsNumbersAndTexts) {
  const std::error_code code = elg::Alarm::following_error_exceeded;
  EXPECT_EQ(code.value(), 2215);
  EXPECT_STREQ(code.category().name(), "sinumerik-elg");
  EXPECT_EQ(code.message(), "ELG - MAX. FOLLOWING ERROR MONITORING VALUE EXCEEDED");
}
