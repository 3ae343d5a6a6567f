// SPDX-License-Identifier: MIT
// SF FGEN (reference generator), REGL (PID controller, vector 6.9 with exact values) and IMES
// (pulse distance measurement): kinematics, limits, I/O bits, VALUE NEW and the START checks.
#include <gtest/gtest.h>

#include "sf_fixture.hpp"

namespace hil::controllers::amkasyn {
namespace {

using testing::command;
using testing::Init;
using testing::SfTest;

// ---------------------------------------------------------------------------------------- FGEN
// ID 2 = 1 ms. DD4 = 20000 increments per DW2 = 2000 (1 s): 20 increments per cycle; DD6 =
// 500000 incr/s^2: 0.5 increments per cycle per cycle (a 40-cycle ramp).
DataBlock fgen_command(int fct, int ba) {
  auto c = command(0, fct, 1, ba);
  c.set_dw(2, 2000).set_dw(3, 2).set_dd(4, 20000).set_dd(6, 500000);
  return c;
}

TEST_F(SfTest, FgenContinuousRampsUpRunsAndRampsDown) {
  init_ok(Init(5, 0).sink(129, 40).in(1, 10).out(1, 20));
  image.set_md(40, 1000);
  start_ok(fgen_command(1, 0));
  cycles(5);
  EXPECT_EQ(image.md(40), 1000) << "nothing moves without E1";
  EXPECT_EQ(image.a[20] & 1, 1) << "A1 = 1 at rest";
  image.e[10] = 1;
  cycles(40);  // 0.5 + 1 + ... + 20 = 410
  EXPECT_EQ(image.md(40), 1410);
  EXPECT_EQ(image.a[20] & 1, 0);
  cycles(10);
  EXPECT_EQ(image.md(40), 1610);
  image.e[10] = 0;
  cycles(40);  // 19.5 + 19 + ... + 0 = 390
  EXPECT_EQ(image.md(40), 2000);
  EXPECT_EQ(image.a[20] & 1, 1);
  cycles(10);
  EXPECT_EQ(image.md(40), 2000);
}

TEST_F(SfTest, FgenOverrideScalesAndZeroHoldsAtOnce) {
  init_ok(Init(5, 0).sink(129, 40).in(1, 10).out(1, 20));
  auto c = fgen_command(1, 0);
  c.set_dw(8, 12);
  start_ok(c);
  image.set_mw(12, 512);  // 50 %: 10 increments per cycle, reached after 20 cycles
  image.e[10] = 1;
  cycles(20);  // 0.5 + ... + 10 = 105
  EXPECT_EQ(image.md(40), 105);
  cycles(1);
  EXPECT_EQ(image.md(40), 115);
  image.set_mw(12, 0);
  cycles(3);
  EXPECT_EQ(image.md(40), 115) << "override 0: no output, at once";
  image.set_mw(12, -512);  // negative override: backwards, through the ramp from rest
  cycles(2);
  EXPECT_EQ(image.md(40), 115 - 2) << "-0.5 - 1.0 = -1.5: the output is the floor, the half is carried";
}

TEST_F(SfTest, FgenSecondAccelerationOnE2) {
  init_ok(Init(5, 0).sink(129, 40).in(1, 10).out(1, 20));
  auto c = fgen_command(1, 4);
  c.set_dd(24, 2000000);  // 2 increments per cycle per cycle
  start_ok(c);
  image.e[10] = 0b11;  // E1 + E2 (acceleration2)
  cycles(10);          // 2 + 4 + ... + 20 = 110
  EXPECT_EQ(image.md(40), 110);
  image.e[10] = 0b01;  // E2 = 0: DD6 again for the stop
  cycles(1);
  image.e[10] = 0b00;
  cycles(1);
  EXPECT_EQ(image.md(40), 110 + 20 + 19);
}

TEST_F(SfTest, FgenSequenceRampsUpAndDownToExactlyDd4) {
  init_ok(Init(5, 0).sink(129, 40).in(1, 10).out(1, 20));
  auto c = fgen_command(1, 2);
  c.set_dw(2, 100).set_dd(4, 1000);  // 1000 increments, 20 per cycle at full speed
  start_ok(c);
  image.e[10] = 1;
  std::int32_t prev = 0, last_step = 0;
  int n = 0;
  while (image.md(40) < 1000 && n < 200) {
    cycles(1);
    ++n;
    last_step = image.md(40) - prev;
    ASSERT_GE(last_step, 0);
    ASSERT_LE(last_step, 21);
    prev = image.md(40);
    if (n == 1) {
      EXPECT_EQ(image.md(40), 0) << "from rest: 0.5 in the first cycle";
    }
  }
  EXPECT_EQ(image.md(40), 1000);
  EXPECT_GE(n, 85) << "40 cycles up, ~10 at 20, 40 down";
  EXPECT_LE(n, 95);
  EXPECT_LE(last_step, 2) << "it arrives at rest";
  EXPECT_EQ(image.a[20] & 1, 1);
  cycles(10);
  EXPECT_EQ(image.md(40), 1000);
}

TEST_F(SfTest, FgenSequenceWithoutRampsAtItsEndsAsOption) {
  SfOptions o;
  o.fgen_sequence_without_ramps = true;
  rt.set_options(o);
  init_ok(Init(5, 0).sink(129, 40).in(1, 10).out(1, 20));
  auto c = fgen_command(1, 2);
  c.set_dw(2, 100).set_dd(4, 1000);  // 1000 increments in 50 ms: 20 per cycle
  start_ok(c);
  image.e[10] = 1;
  cycles(1);
  EXPECT_EQ(image.md(40), 20) << "a sequence begins at full velocity";
  cycles(49);
  EXPECT_EQ(image.md(40), 1000);
  cycles(5);
  EXPECT_EQ(image.md(40), 1000) << "ends on its own, exactly";
  EXPECT_EQ(image.a[20] & 1, 1);
  // A new edge starts a new sequence; E1 = 0 interrupts it with the ramp, E1 = 1 continues it.
  image.e[10] = 0;
  cycles(1);
  image.e[10] = 1;
  cycles(10);
  EXPECT_EQ(image.md(40), 1200);
  image.e[10] = 0;
  cycles(40);  // 19.5 + ... + 0 = 390
  EXPECT_EQ(image.md(40), 1590);
  EXPECT_EQ(image.a[20] & 1, 1);
  image.e[10] = 1;
  cycles(200);
  EXPECT_EQ(image.md(40), 2000) << "the rest of the sequence, then stop exactly";
  EXPECT_EQ(image.a[20] & 1, 1);
}

TEST_F(SfTest, FgenFeedbackZeroingAndPositionMonitoring) {
  init_ok(Init(5, 0).in(1, 10).out(1, 20));
  auto c = fgen_command(6, 0);
  c.set_dw(9, 0b101).set_dd(10, 100).set_dd(12, 200);  // AW1 -> limit 0 (A2), AW3 -> limit 1 (A3)
  start_ok(c);
  image.aw[0].position_feedback = 5000;
  image.aw[2].position_feedback = -300;
  cycles(1);
  EXPECT_EQ(image.ed(128), 5000) << "not zeroed before the first start";
  EXPECT_EQ(image.a[20] & 0b110, 0b010) << "AW1 at 5000 > 100";
  image.e[10] = 1;  // start: zero
  cycles(1);
  EXPECT_EQ(image.ed(128), 0);
  EXPECT_EQ(image.ed(136), 0);
  EXPECT_EQ(image.a[20] & 0b110, 0);
  image.aw[0].position_feedback = 5150;
  image.aw[2].position_feedback = -150;
  cycles(1);
  EXPECT_EQ(image.ed(128), 150);
  EXPECT_EQ(image.ed(136), 150);
  EXPECT_EQ(image.a[20] & 0b110, 0b010) << "AW1 150 > 100, AW3 150 <= 200";
}

TEST_F(SfTest, FgenStartChecksAndValueNew) {
  init_ok(Init(5, 0).sink(129, 40).in(1, 10).out(1, 20));
  auto bad = fgen_command(1, 0);
  bad.set_dw(3, 4);
  auto s = rt.command(bad, image);
  EXPECT_EQ(s.code, SfError::start_invalid);
  EXPECT_NE(s.text.find("DW3 SF cycle time = 4"), std::string::npos) << s.text;
  bad = fgen_command(7, 0);
  bad.set_dw(9, 0xFF);
  EXPECT_NE(rt.command(bad, image).text.find("at most 7 AWs"), std::string::npos);
  bad = fgen_command(1, 0);
  bad.set_dd(6, 0);
  EXPECT_NE(rt.command(bad, image).text.find("DD6 acceleration = 0"), std::string::npos);
  bad = fgen_command(1, 4);
  EXPECT_NE(rt.command(bad, image).text.find("DD24"), std::string::npos);
  EXPECT_EQ(rt.state(0), SfState::reset);
  SfOptions o;
  o.fgen_sequence_without_ramps = true;
  rt.set_options(o);
  start_ok(fgen_command(1, 0));
  auto vn = fgen_command(1, 1);
  vn.set_dr(1, 5);
  EXPECT_TRUE(rt.command(vn, image).error) << "VALUE NEW may not switch to external velocity";
  vn = fgen_command(1, 2);
  vn.set_dr(1, 5).set_dd(4, 1000).set_dw(2, 100);
  EXPECT_FALSE(rt.command(vn, image).error) << "continuous -> sequence is allowed";
  image.e[10] = 1;  // DD4 is not a VALUE NEW parameter: 20000 increments in 50 ms, 400 per cycle
  cycles(1);
  EXPECT_EQ(image.md(40), 400);
  cycles(59);
  EXPECT_EQ(image.md(40), 20000);
}

// ---------------------------------------------------------------------------------------- REGL
// 6.9: force control on top of the AW1 speed loop. ID 2 = 1 ms; the source is the analog input
// A1 (Config-AW message16, 12-bit offset binary, 1 N = 1 bit); F_command = DW18 = 100 N;
// n_command = DD20 = 5000000 (500 rpm in 0.0001 rpm); Kp 2, Ki 0.5, Kd 0.25; v = 1000;
// y_max = 1000000. Tn = 1 ms x 2 / 0.5 = 4 ms, Tv = 1 ms x 0.25 / 2 = 0.125 ms.
class Regl : public SfTest {
 protected:
  void start(int ba, int switches = 7) {
    init_ok(Init(6, 0).source(1, 2).sink(1, 16).in(1, 4).out(1, 0));
    auto c = command(0, 0, 1, ba);
    c.set_dw(3, 2).set_dw(4, switches).set_dw(6, 512).set_dw(7, 128).set_dw(8, 64);
    c.set_dd(10, 1000000).set_dw(12, 1000).set_dd(14, 1000000).set_dw(18, 100).set_dd(20, 5000000);
    start_ok(c);
  }
  void force(int newton) { image.aw[0].message16 = static_cast<std::int16_t>(2048 + newton); }
  std::int32_t y() const { return image.aw[0].swq2; }
};

TEST_F(Regl, Vector6_9ForceControlExactOutputs) {
  start(0);
  force(60);  // e = 100 - 60 = 40
  cycles(1);  // P 2*40 = 80, I 0.5*40 = 20, D 0 (no kick): 100 x 1000 + 5000000
  EXPECT_EQ(y(), 5100000);
  cycles(1);  // I 40
  EXPECT_EQ(y(), 5120000);
  cycles(2);  // after Tn = 4 ms the I part equals the P part: 80 + 80
  EXPECT_EQ(y(), 5160000);
  force(80);  // e = 20: P 40, I 90, D 0.25 x (20 - 40) = -5
  cycles(1);
  EXPECT_EQ(y(), 5125000);
  EXPECT_EQ(image.a[0] & 3, 0);
}

TEST_F(Regl, OutputLimitBeforeTheSummationPointAndLimitFlags) {
  start(0);
  force(-1900);  // e = 2000: P 4000 + I 1000 = 5000 x 1000 > y_max
  cycles(1);
  EXPECT_EQ(y(), 1000000 + 5000000) << "clamped before SP, then source2 added";
  EXPECT_EQ(image.a[0] & 3, 1) << "A1 = positive limitation";
  force(1900);  // e = -1800
  cycles(1);
  EXPECT_EQ(y(), -1000000 + 5000000);
  EXPECT_EQ(image.a[0] & 3, 2) << "A2 = negative limitation";
}

TEST_F(Regl, AsymmetricLimitAfterTheSummationPoint) {
  start(20);  // bit4 after SP, bit2: positive limit 0 -> y in [-y_max, 0]
  force(60);
  cycles(1);
  EXPECT_EQ(y(), 0) << "100000 + 5000000 clamped to 0";
  EXPECT_EQ(image.a[0] & 3, 1);
}

TEST_F(Regl, SwitchesFromInputsDeleteIntegratorAndExternalSync) {
  start(1 | 2 | 32);  // S1..S3 = E1..E3, external sync on E4, delete integrator
  force(60);
  image.e[4] = 0b0111;
  cycles(3);
  EXPECT_EQ(y(), 0) << "no control cycle without an E4 edge";
  image.e[4] = 0b1111;
  cycles(1);
  EXPECT_EQ(y(), 5100000);
  cycles(1);
  EXPECT_EQ(y(), 5100000) << "held until the next edge";
  image.e[4] = 0b0111;
  cycles(1);
  image.e[4] = 0b1111;
  cycles(1);
  EXPECT_EQ(y(), 5120000);
  image.e[4] = 0b0101;  // S2 open: loop interrupted, I cleared
  cycles(1);
  image.e[4] = 0b1101;
  cycles(1);
  EXPECT_EQ(y(), 5000000);
  image.e[4] = 0b0111;
  cycles(1);
  image.e[4] = 0b1111;
  cycles(1);
  EXPECT_EQ(y(), 5100000) << "the integrator restarted from 0";
  image.e[4] = 0b0110;  // S1 open: w1 = 0, e = -60
  cycles(1);
  image.e[4] = 0b1110;
  cycles(1);
  EXPECT_EQ(y(), 5000000 + 1000 * (-120 - 10 - 25)) << "P -120, I 20 - 30, D 0.25 x (-60 - 40)";
}

TEST_F(Regl, SourceAssessmentFilterAndValueNew) {
  init_ok(Init(6, 0).source(128, 10).sink(129, 40));
  auto c = command(0, 0, 1, 0);
  c.set_dw(4, 2).set_dr(5, 2).set_dl(5, 3).set_dw(6, 256).set_dd(10, 100000).set_dw(12, 1).set_dw(18, 0);
  start_ok(c);            // S2 only, P = 1; x = -MW10 (no ADC conversion), mean of 4
  image.set_mw(10, 400);  // e = 0 - (-400) = 400; mean of 4 starts with this sample
  cycles(1);
  EXPECT_EQ(image.md(40), 400);
  image.set_mw(10, 0);
  cycles(1);
  EXPECT_EQ(image.md(40), 200);
  auto vn = c;
  vn.set_dr(1, 5).set_dw(6, 512);
  ASSERT_FALSE(rt.command(vn, image).error);
  cycles(1);  // mean (-400 + 0 + 0)/3 -> e = 133, P 2
  EXPECT_EQ(image.md(40), 266);
  auto bad = c;
  bad.set_dw(12, 0);
  ASSERT_FALSE(rt.command(command(0, 0, 0, 0), image).error);
  const auto s = rt.command(bad, image);
  EXPECT_NE(s.text.find("DW12 output gain = 0"), std::string::npos) << s.text;
}

// ---------------------------------------------------------------------------------------- IMES
class Imes : public SfTest {
 protected:
  void start(int ba, int cs, int window = 0, int blocked = 0) {
    init_ok(Init(7, 0).source(0, 18).sink(128, 20).out(1, 30));
    auto c = command(0, 0, 1, ba);
    c.set_dd(4, cs).set_dd(6, window).set_dd(8, blocked);
    start_ok(c);
  }
  void pulse(std::int32_t at) {
    image.az[1] = at;
    image.az_zero[1].pulse(at);
    cycles(1);
  }
  int a() const { return image.a[30] & 3; }
};

TEST_F(Imes, DifferenceModuloCommandSpacing) {
  start(0, 1000);
  pulse(500);
  EXPECT_EQ(a(), 0) << "the first pulse only starts the measurement";
  pulse(1510);
  EXPECT_EQ(image.mw(20), 10);
  EXPECT_EQ(a(), 3) << "A1 new value, A2 valid";
  cycles(1);
  EXPECT_EQ(a(), 2) << "A1 for one SF cycle";
  pulse(2500);
  EXPECT_EQ(image.mw(20), -10);
  pulse(4505);  // a missing pulse: 2005 -> 5
  EXPECT_EQ(image.mw(20), 5);
}

TEST_F(Imes, NegativeAndPositiveLimitation) {
  start(8, 1000);  // bits3..2 = 10: negative
  pulse(0);
  pulse(990);
  EXPECT_EQ(image.mw(20), -10);
  EXPECT_EQ(a(), 3);
  pulse(2000);  // 1010 >= cs: invalid
  EXPECT_EQ(image.mw(20), -10);
  EXPECT_EQ(a(), 0);
  pulse(2980);  // no set down: 1990 from 990, not below cs either (decision: the literal rule)
  EXPECT_EQ(a(), 0) << "only set down (BA bit1) restarts the measurement after a missing pulse";
  ASSERT_FALSE(rt.command(command(0, 0, 0, 0), image).error);
  start(4, 1000);  // 01: positive
  pulse(0);
  pulse(1010);
  EXPECT_EQ(image.mw(20), 10);
  pulse(2000);
  EXPECT_EQ(a(), 0) << "990 < cs: invalid";
}

TEST_F(Imes, WindowBlockedRangeSetDownAbsoluteAndValueNew) {
  start(2, 1000, 20, 100);  // set down
  pulse(0);
  pulse(5);  // inside the blocked range: ignored
  EXPECT_EQ(a(), 0);
  pulse(1050);  // outside the window: invalid, set down
  EXPECT_EQ(a(), 0);
  pulse(2060);  // 1010 from the set-down pulse
  EXPECT_EQ(image.mw(20), 10);
  EXPECT_EQ(a(), 3);
  auto vn = command(0, 0, 5, 2);
  vn.set_dd(4, 500).set_dd(6, 0).set_dd(8, 0);
  ASSERT_FALSE(rt.command(vn, image).error);
  pulse(2760);  // 700 mod 500 = 200
  EXPECT_EQ(image.mw(20), 200);
  ASSERT_FALSE(rt.command(command(0, 0, 0, 0), image).error);
  start(1, 1000);  // absolute
  pulse(0);
  pulse(2345);
  EXPECT_EQ(image.mw(20), 2345);
}

TEST_F(Imes, StartChecks) {
  init_ok(Init(7, 0).source(0, 1).sink(128, 20));
  auto s = rt.command(command(0, 0, 1, 0), image);
  EXPECT_NE(s.text.find("32-bit AZ message"), std::string::npos) << s.text;
  init_ok(Init(7, 0).source(0, 16).sink(1, 16));
  s = rt.command(command(0, 0, 1, 0), image);
  EXPECT_NE(s.text.find("sink address = 1"), std::string::npos) << s.text;
  init_ok(Init(7, 0).source(0, 16).sink(128, 20));
  s = rt.command(command(0, 0, 1, 12), image);
  EXPECT_TRUE(s.error);
  auto c = command(0, 0, 1, 0);
  c.set_dd(4, 1 << 30);
  EXPECT_NE(rt.command(c, image).text.find("DD4 command spacing"), std::string::npos);
}

// ------------------------------------------------------------------------ SIDIFF minus SAK part
// SIDIFF (SF0) watches AW1, which an FIPW (SF1, time mode, 10 increments per cycle) drives with
// SAK 4032 (a lead of 4032 x 10 / 128 = 315): the drive's following error contains the lead, and
// SIDIFF removes it, so only the real offset (20, then 150) is monitored.
TEST_F(SfTest, SidiffRemovesTheSakPartOfTheFollowingError) {
  DataBlock t(8);
  t.set_dw(0, 4).set_dd(4, 5000).set_dd(6, 10000);
  dbs[20] = t;
  init_ok(Init(0, 0).sink(128, 20).out(1, 40));
  auto sd = command(0, 255, 1, 0);
  sd.set_dr(2, 1).set_dr(3, 1).set_dr(4, 1).set_dr(5, 1);  // AW1, display AW1, no mean, 1 agreement
  start_ok(sd);
  init_ok(Init(1, 1).sink(1, 4).tab(0, 20));
  auto fp = command(1, 0, 1, 4);
  fp.set_dw(2, 4032).set_dw(3, 2).set_dw(4, 1).set_dd(8, 1).set_dd(10, 2000);
  start_ok(fp);
  auto run = [&](int offset, int n) {
    for (int i = 0; i < n; ++i) {
      image.aw[0].message32 = image.aw[0].sak_part + offset;  // the drive lags by lead + offset
      cycles(1);
    }
  };
  run(20, 50);
  EXPECT_EQ(image.aw[0].sak_part, 315);
  EXPECT_EQ(image.mw(20), 20);
  EXPECT_EQ(image.a[40] & 1, 0) << "315 + 20 would exceed 100; 20 does not";
  run(150, 2);
  EXPECT_EQ(image.mw(20), 150);
  EXPECT_EQ(image.a[40] & 1, 1);
}

}  // namespace
}  // namespace hil::controllers::amkasyn
