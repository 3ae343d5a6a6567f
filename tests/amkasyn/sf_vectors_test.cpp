// SPDX-License-Identifier: MIT
// The behavioural examples of shared/vectors/amkasyn-sf.md as exact expectations: ECOPY (6.1),
// VARSYNC examples 1 and 2 with SAK (6.5), DFKT (6.7), BINEA (6.11), CAM (6.15), plus the SAK
// constants of the manual (4032, 7936).
#include <gtest/gtest.h>

#include "hil/controllers/amkasyn/sf_types.hpp"
#include "sf_fixture.hpp"

namespace hil::controllers::amkasyn {
namespace {

using testing::command;
using testing::Init;
using testing::SfTest;

TEST(Sak, ManualConstants) {
  EXPECT_EQ(sak_factor(2.0, 1000.0, false), 4032);   // ID 2 = 2 ms, ID 104 = 1000 rpm, internal
  EXPECT_EQ(sak_factor(1.0, 1000.0, true), 7936);    // ID 2 = 1 ms, external
  EXPECT_EQ(sak_lead(1000, 990, 7936), 1000 + 620);  // 62 cycles of lead at 10 inc/cycle
  EXPECT_EQ(sak_lead(1000, 990, 0), 1000);
}

// 6.1 ECOPY: AA1 10 V / 5 V by M 100.0, acknowledged on M 101.0 (E/A-M mode 3).
TEST_F(SfTest, EcopySwitchesAnalogOutputByFlag) {
  init_ok(Init(0, 0).mode(3).sink(64, 0).in(1, 100).out(1, 101));
  auto c = command(0, 2, 1, 3);  // BA 3: the errata (printed BA 0 copies the source for both states)
  c.set_dd(2, 10000).set_dd(4, 5000);
  start_ok(c);
  cycles(1);
  EXPECT_EQ(image.analog_out[0], 10000);
  EXPECT_EQ(image.m[101] & 1, 0);
  image.m[100] |= 1;
  cycles(1);
  EXPECT_EQ(image.analog_out[0], 5000);
  EXPECT_EQ(image.m[101] & 1, 1);
  image.m[100] &= ~1;
  cycles(1);
  EXPECT_EQ(image.analog_out[0], 10000);
  EXPECT_EQ(image.m[101] & 1, 0);
}

TEST_F(SfTest, EcopyAsPrintedWithBa0CopiesTheSource) {
  init_ok(Init(0, 0).mode(3).sink(64, 0).in(1, 100).out(1, 101));
  auto c = command(0, 2, 1, 0);
  c.set_dd(2, 10000).set_dd(4, 5000);
  start_ok(c);
  image.m[100] |= 1;
  cycles(1);
  EXPECT_EQ(image.analog_out[0], 0) << "no source (AZ offset 0): the source value 0 is copied";
  EXPECT_EQ(image.m[101] & 1, 1);
}

// 6.5 VARSYNC example 1: AW3 follows the AZ message 1 high word at +1 (E16.2 = 0) or -1
// (E16.2 = 1), A16.2 = E16.2, SAK 7936 (62 cycles of lead).
TEST_F(SfTest, VarsyncExample1MirrorsOnE16_2) {
  init_ok(Init(3, 2).source(0, 1).sink(3, 4).in(4, 16).out(4, 16));
  auto c = command(2, 1, 1, 0);
  c.set_dw(2, 7936).set_dw(4, 10000).set_dw(6, -10000);
  start_ok(c);
  auto master_step = [&](int d) { image.az[0] += d * 65536; };  // high word counts the master
  std::int16_t prev = image.aw[2].swq1;
  for (int i = 0; i < 100; ++i) {
    master_step(7);
    cycles(1);
    const auto now = image.aw[2].swq1;
    if (i == 0) {
      EXPECT_EQ(static_cast<std::int16_t>(now - prev), 7 + 62 * 7 / 1) << "first cycle: the step plus its lead";
    } else {
      EXPECT_EQ(static_cast<std::int16_t>(now - prev), 7);
    }
    prev = now;
  }
  EXPECT_EQ(image.a[16] & 4, 0);
  const std::int16_t at_switch = image.aw[2].swq1;
  image.e[16] |= 4;  // E16.2 = 1: mirror
  master_step(7);
  cycles(1);
  EXPECT_EQ(image.a[16] & 4, 4);
  // y: +7 -> -7 per cycle; the lead turns from +434 to -434.
  EXPECT_EQ(static_cast<std::int16_t>(image.aw[2].swq1 - at_switch), -7 - 2 * 434);
  prev = image.aw[2].swq1;
  for (int i = 0; i < 50; ++i) {
    master_step(7);
    cycles(1);
    EXPECT_EQ(static_cast<std::int16_t>(image.aw[2].swq1 - prev), -7);
    prev = image.aw[2].swq1;
  }
}

// 6.5 VARSYNC example 2: the ratio of AW1 is EW16/10000, read every SF cycle (BA 3).
TEST_F(SfTest, VarsyncExample2RatioFromInputWord) {
  init_ok(Init(3, 3).source(0, 1).sink(1, 4));
  auto c = command(3, 1, 1, 3);
  c.set_dw(2, 0).set_dw(3, 2).set_dr(4, 16).set_dl(4, 1);  // SAK off here to read the ratio directly
  start_ok(c);
  image.set_ew(16, 10000);
  std::int16_t prev = image.aw[0].swq1;
  for (int i = 0; i < 10; ++i) {
    image.az[0] += 100 * 65536;
    cycles(1);
    EXPECT_EQ(static_cast<std::int16_t>(image.aw[0].swq1 - prev), 100);
    prev = image.aw[0].swq1;
  }
  image.set_ew(16, -2500);  // -0.25
  for (int i = 0; i < 10; ++i) {
    image.az[0] += 100 * 65536;
    cycles(1);
    EXPECT_EQ(static_cast<std::int16_t>(image.aw[0].swq1 - prev), -25);
    prev = image.aw[0].swq1;
  }
  image.set_ew(16, 3333);  // remainders carried: 100 x 0.3333 = 33.33 per cycle, no drift
  const std::int16_t base = image.aw[0].swq1;
  for (int i = 0; i < 300; ++i) {
    image.az[0] += 100 * 65536;
    cycles(1);
  }
  EXPECT_EQ(static_cast<std::int16_t>(image.aw[0].swq1 - base), 9999);
}

TEST_F(SfTest, VarsyncBa3RefusesACycleTimeOtherThanId2) {
  init_ok(Init(3, 3).source(0, 1).sink(1, 4));
  auto c = command(3, 1, 1, 3);
  c.set_dw(3, 4).set_dr(4, 16).set_dl(4, 1);
  const auto s = rt.command(c, image);
  EXPECT_TRUE(s.error);
  EXPECT_EQ(s.code, SfError::start_invalid);
  EXPECT_EQ(image.m[233], 1);
  EXPECT_NE(s.text.find("DW3"), std::string::npos) << s.text;
  EXPECT_EQ(rt.state(3), SfState::reset);
}

// 6.7 DFKT: AW2 speed = table(AW1 speed) x V/V_N (V_N = 4000/2000 = 2), mirrored below 0,
// extrapolated above 2000 rpm, clamped at 4000 rpm (status bit 2); A1 = 1 until E24.4 = 1.
class Dfkt : public SfTest {
 protected:
  void SetUp() override {
    DataBlock t(20);
    t.set_dw(0, 10);  // 9 points + 1
    for (int k = 0; k < 9; ++k) t.set_dd(static_cast<std::size_t>(2 * (k + 1)), 500 * k);
    dbs[17] = t;
    dbs[18] = t;
    dbs[16] = DataBlock(6);  // output table Tab7
    init_ok(Init(4, 4).source(1, 19).sink(2, 16).in(16, 24).out(16, 24).tab(0, 17).tab(1, 18).tab(7, 16));
    auto c = command(4, 0, 1, 6);
    c.set_dw(3, 4).set_dw(4, 2).set_dw(5, 1).set_dw(6, 1000).set_dw(8, 1000);
    c.set_dw(10, 20000).set_dw(11, 2000).set_dw(12, 4000).set_dw(14, -4000);
    c.set_dw(16, 2000).set_dw(18, -2000).set_dw(20, 1000).set_dw(22, 2).set_dw(23, 1);
    start_ok(c);
  }
  std::int32_t out_for(double rpm) {
    image.aw[0].message32 = static_cast<std::int32_t>(rpm * 10000);  // ID 40 speed feedback, 0.0001 rpm
    cycles(1);
    return image.aw[1].swq2 / 10000;
  }
};

TEST_F(Dfkt, ManualExampleMapping) {
  EXPECT_EQ(out_for(1000), 0) << "stopped until E24.4";
  EXPECT_EQ(image.a[24] & 16, 16) << "A1 = 1: axis stopped";
  image.e[24] |= 16;
  EXPECT_EQ(out_for(0), 0);
  EXPECT_EQ(image.a[24] & 16, 0);
  EXPECT_EQ(out_for(250), 250);
  EXPECT_EQ(out_for(1000), 1000);
  EXPECT_EQ(out_for(2000), 2000);
  EXPECT_EQ(out_for(-1000), -1000);
  EXPECT_EQ(out_for(3000), 3000);
  EXPECT_EQ(dbs[16].dw(1) & 4, 0);
  EXPECT_EQ(dbs[16].dw(1) & 16, 16) << "upper table end exceeded";
  EXPECT_EQ(out_for(5000), 4000);
  EXPECT_EQ(dbs[16].dw(1) & 4, 4) << "status bit2: upper output speed exceeded";
  EXPECT_EQ(dbs[16].dw(2), 1000);
  EXPECT_EQ(dbs[16].dw(3), 1000);
  image.e[24] &= ~16;
  EXPECT_EQ(out_for(1000), 0);
  EXPECT_EQ(image.a[24] & 16, 16);
}

// 6.11 BINEA: two tracks from the AW2 position (low word, incremental), period 20000, a 2-bit
// Gray code with period 10000: P(x-1) < x' <= Px gives A-value Px.
TEST_F(SfTest, BineaGrayCode) {
  DataBlock t(40);
  t.set_dw(0, 9);
  const int values[8] = {0, 1, 3, 2, 0, 1, 3, 2};
  for (int x = 0; x < 8; ++x) {
    t.set_dd(static_cast<std::size_t>(4 + 4 * x), 2500 * (x + 1));
    t.set_dr(static_cast<std::size_t>(6 + 4 * x), static_cast<std::uint8_t>(values[x]));
  }
  dbs[16] = t;
  init_ok(Init(8, 0).source(2, 5).out(1, 8).tab(0, 16));
  auto c = command(0, 0, 1, 1);
  c.set_dw(3, 2).set_dw(4, 2);
  start_ok(c);
  auto at = [&](int pos) {
    image.aw[1].position_feedback = pos;
    cycles(1);
    return image.a[8] & 3;
  };
  // (x' range, A2A1) from Figure 29, in both directions and across the modulo point.
  EXPECT_EQ(at(1), 0);
  EXPECT_EQ(at(2500), 0);
  EXPECT_EQ(at(2501), 1);
  EXPECT_EQ(at(5000), 1);
  EXPECT_EQ(at(5001), 3);
  EXPECT_EQ(at(7500), 3);
  EXPECT_EQ(at(7501), 2);
  EXPECT_EQ(at(10000), 2);
  EXPECT_EQ(at(10001), 0);
  EXPECT_EQ(at(15001), 3);
  EXPECT_EQ(at(19999), 2);
  EXPECT_EQ(at(20001), 0) << "x' = 1 after the modulo";
  EXPECT_EQ(at(22600), 1);
  EXPECT_EQ(at(19999), 2) << "backwards across the modulo point";
}

// 6.15 CAM: four tracks from the AW1 position, incremental modulo 20000: a staircase of
// consecutive 1000-increment windows from 10000, each once per revolution.
TEST_F(SfTest, CamStaircase) {
  DataBlock t(100);
  t.set_dw(0, 10000);
  for (int k = 0; k < 4; ++k) {
    const auto base = static_cast<std::size_t>(32 + 8 * k);  // 2 cams per track: (on, off), (0, 0)
    t.set_dd(base, 10000 + 1000 * k).set_dd(base + 2, 11000 + 1000 * k);
  }
  dbs[56] = t;
  init_ok(Init(12, 0).source(1, 5).in(1, 1).out(1, 1).tab(0, 56));
  auto c = command(0, 0, 1, 1);
  c.set_dw(3, 2).set_dw(4, 0);
  c.set_dr(6, 2).set_dl(6, 2).set_dr(7, 2).set_dl(7, 2);
  c.set_dd(14, 20000);
  start_ok(c);
  auto tracks = [&](int pos) {
    image.aw[0].position_feedback = pos;
    cycles(1);
    return image.a[1] & 15;
  };
  for (int rev = 0; rev < 3; ++rev) {
    const int b = rev * 20000;
    EXPECT_EQ(tracks(b + 9999), 0);
    EXPECT_EQ(tracks(b + 10000), 1);
    EXPECT_EQ(tracks(b + 10999), 1);
    EXPECT_EQ(tracks(b + 11000), 2);
    EXPECT_EQ(tracks(b + 12500), 4);
    EXPECT_EQ(tracks(b + 13999), 8);
    EXPECT_EQ(tracks(b + 14000), 0);
    EXPECT_EQ(tracks(b + 19000), 0);
  }
}

// CAM hysteresis (V02.13): one cam [10000, 11000) with H = 10 x 100 increments, absolute input,
// through the rules of the manual: positive approach, reversal before and after X_Free, negative
// approach.
TEST_F(SfTest, CamHysteresisFollowsTheDirectionRules) {
  DataBlock t(40);
  t.set_dd(32, 10000).set_dd(34, 11000);
  dbs[56] = t;
  init_ok(Init(12, 0).source(1, 21).out(1, 1).tab(0, 56));
  auto c = command(0, 0, 1, 0);
  c.set_dw(3, 2).set_dr(6, 1).set_dw(16, 10);
  image.aw[0].position_feedback = 9000;
  start_ok(c);
  auto at = [&](int x) {  // moves in steps of 100 (or less) to x, returns the track bit
    while (image.aw[0].position_feedback != x) {
      const int d = x - image.aw[0].position_feedback;
      image.aw[0].position_feedback += d > 100 ? 100 : (d < -100 ? -100 : d);
      cycles(1);
    }
    return image.a[1] & 1;
  };
  EXPECT_EQ(at(9900), 0);
  EXPECT_EQ(at(10000), 1) << "positive: on at X_On";
  EXPECT_EQ(at(9500), 1) << "back: stays 1 down to X_On - H";
  EXPECT_EQ(at(9000), 1);
  EXPECT_EQ(at(8999), 0);
  EXPECT_EQ(at(10500), 1);
  EXPECT_EQ(at(11000), 0) << "off at X_Off";
  EXPECT_EQ(at(10500), 0) << "back before X_Free: stays 0 down to X_Off - H";
  EXPECT_EQ(at(10000), 0);
  EXPECT_EQ(at(9999), 1);
  EXPECT_EQ(at(11000), 0);
  EXPECT_EQ(at(12000), 0) << "X_Free = X_Off + H reached";
  EXPECT_EQ(at(11500), 0) << "reversal: the negative rules";
  EXPECT_EQ(at(11000), 0);
  EXPECT_EQ(at(10999), 1) << "negative: on below X_Off";
  EXPECT_EQ(at(11500), 1) << "forward again: stays 1 up to X_Off + H";
  EXPECT_EQ(at(12000), 0);
  EXPECT_EQ(at(10500), 1);
  EXPECT_EQ(at(10000), 1);
  EXPECT_EQ(at(9999), 0) << "off below X_On";
  EXPECT_EQ(at(10500), 0) << "forward before X_Free (X_On - H): stays 0 up to X_On + H";
  EXPECT_EQ(at(11000), 1);
  EXPECT_EQ(at(8900), 0) << "back below X_On - H: X_Free";
  EXPECT_EQ(at(9500), 0) << "reversal: the positive rules again";
  EXPECT_EQ(at(10000), 1);
}

TEST_F(SfTest, CamHysteresisRangeIsChecked) {
  DataBlock t(40);
  t.set_dd(32, 10000).set_dd(34, 19500);
  dbs[56] = t;
  init_ok(Init(12, 0).source(1, 5).out(1, 1).tab(0, 56));
  auto c = command(0, 0, 1, 1);
  c.set_dw(3, 2).set_dr(6, 1).set_dd(14, 20000).set_dw(16, 105);  // 10500 >= 20000 - 9500
  const auto s = rt.command(c, image);
  EXPECT_TRUE(s.error);
  EXPECT_NE(s.text.find("must be below 10500"), std::string::npos) << s.text;
  c.set_dw(16, 104);
  EXPECT_FALSE(rt.command(c, image).error);
  // Running on in one direction, the hysteresis never shifts the edges: X_On / X_Off every revolution.
  for (int x = 100; x <= 3 * 20000; x += 100) {
    image.aw[0].position_feedback = x;
    cycles(1);
    const int p = x % 20000;
    ASSERT_EQ(image.a[1] & 1, (p >= 10000 && p < 19500) ? 1 : 0) << "x = " << x;
  }
}

// 6.3 FIPW (the sequence; its printing mark control: PrintingMark below): BA 98 with a
// coupling table DB16, working table DB17, decoupling table DB18 over Xme = 20000 from the 32-bit
// AZ message 1. E8.0 = 1 runs DB16 for one master revolution, then DB17 repeatedly; E8.0 = 0 runs
// DB18 once from the next table end, then holds.
TEST_F(SfTest, FipwClockingInAndOut) {
  auto table = [](std::initializer_list<std::int32_t> ys) {
    DataBlock t(8);
    t.set_dw(0, static_cast<int>(ys.size()) + 1);
    std::size_t a = 2;
    for (auto y : ys) t.set_dd(a, y), a += 2;
    return t;
  };
  dbs[16] = table({0, 2500, 10000});
  dbs[17] = table({0, 10000, 20000});
  dbs[18] = table({0, 7500, 10000});
  init_ok(Init(1, 0).source(0, 16).sink(129, 40).in(1, 8).tab(0, 16).tab(1, 17).tab(2, 18));
  auto c = command(0, 0, 1, 98);
  c.set_dw(3, 2).set_dw(4, 3).set_dw(5, 1).set_dd(8, 1).set_dd(10, 20000);
  start_ok(c);
  image.e[8] = 1;
  cycles(1);  // master at 0: inside the start window (0): clocked in at X = 0
  auto at = [&](std::int32_t x) {
    while (image.az[0] < x) {
      image.az[0] += 100;
      cycles(1);
    }
    return image.md(40);
  };
  EXPECT_EQ(at(10000), 2500);          // DB16 halfway
  EXPECT_EQ(at(20000), 10000);         // DB16 done: one revolution
  EXPECT_EQ(at(30000), 20000);         // DB17
  EXPECT_EQ(at(50000), 40000);         // DB17 again
  image.e[8] = 0;                      // clock out at the next table end (stop angle 0)
  EXPECT_EQ(at(55000), 45000);         // still DB17
  EXPECT_EQ(at(70000), 50000 + 7500);  // DB18 from 60000
  EXPECT_EQ(at(80000), 60000);         // DB18 done
  EXPECT_EQ(at(120000), 60000);        // rests
  image.e[8] = 1;  // clock in again: the master stands on a zero passage (120000), inside the window
  cycles(1);
  EXPECT_EQ(at(130000), 60000 + 2500);
}

TEST_F(SfTest, FipwCyclicTimeModeAndScaling) {
  DataBlock t(8);
  t.set_dw(0, 4).set_dd(4, 500).set_dd(6, 1000);  // 3 points 0, 500, 1000 over Te = 200 (100 ms)
  dbs[20] = t;
  init_ok(Init(1, 0).sink(129, 40).tab(0, 20));
  auto c = command(0, 0, 1, 4);
  c.set_dw(3, 2).set_dw(4, 1).set_dw(6, 1).set_dd(8, 3).set_dd(10, 200);  // Y x 3 / 2
  start_ok(c);
  cycles(50);  // t = 100 (0.5 ms units): Y = 500 -> 750
  EXPECT_EQ(image.md(40), 750);
  cycles(50 + 100 * 7);  // 8 whole periods: 8 x 1000 x 1.5
  EXPECT_EQ(image.md(40), 12000);
}

TEST_F(SfTest, FipwRefusesABadSyncAddressAndBadTables) {
  DataBlock t(8);
  t.set_dw(0, 3).set_dd(4, 40000);  // |dY| >= 32768
  dbs[20] = t;
  init_ok(Init(1, 0).source(0, 16).sink(129, 40).tab(0, 20));
  auto c = command(0, 5, 1, 2);
  c.set_dw(3, 2).set_dw(4, 1).set_dd(8, 1).set_dd(10, 20000).set_dr(7, 6);
  auto s = rt.command(c, image);
  EXPECT_TRUE(s.error);
  EXPECT_NE(s.text.find("DR7 MD addr. ext. sync. = 6"), std::string::npos) << s.text;
  c.set_dl(0, 0);
  s = rt.command(c, image);
  EXPECT_TRUE(s.error);
  EXPECT_NE(s.text.find("32768"), std::string::npos) << s.text;
}

// 6.3 with its printing mark control: coupling DB16, working DB17 (Y_end 20000 for the format of
// 300 mm: s = 20000 / 3000 increments per 0.1 mm), sensor distance 100 mm -> the mark is expected
// at s x 2000 = 13333 in the working table, valid within s x 200 = 1333; the correction is output
// over master [5000, 15000) of the next working table; dXM shown in MD 60 (DW26).
class PrintingMark : public SfTest {
 protected:
  PrintingMark() : SfTest(4) {}  // ID 2 = 2 ms (DW3 = 4)
  std::int32_t at(std::int32_t x) {
    while (image.az[0] < x) {
      image.az[0] += 100;
      cycles(1);
    }
    return image.md(40);
  }
  void mark(std::int32_t x) {  // the mark passes the sensor at master x (inside the next step)
    image.az[0] += 100;
    image.az_zero[0].pulse(x);
    cycles(1);
  }
};

TEST_F(PrintingMark, Vector6_3CorrectsTheWorkingTable) {
  auto table = [](std::initializer_list<std::int32_t> ys) {
    DataBlock t(8);
    t.set_dw(0, static_cast<int>(ys.size()) + 1);
    std::size_t a = 2;
    for (auto y : ys) t.set_dd(a, y), a += 2;
    return t;
  };
  dbs[16] = table({0, 2500, 10000});
  dbs[17] = table({0, 10000, 20000});
  dbs[18] = table({0, 7500, 10000});
  init_ok(Init(1, 0).source(0, 16).sink(129, 40).in(1, 8).tab(0, 16).tab(1, 17).tab(2, 18));
  auto c = command(0, 1, 1, 98);
  c.set_dw(3, 4).set_dw(4, 3).set_dw(5, 1).set_dd(8, 1).set_dd(10, 20000);
  c.set_dw(18, 3000).set_dd(20, 1000).set_dw(23, 200).set_dw(24, 5000).set_dw(25, 10000).set_dw(26, 60);
  start_ok(c);
  image.e[8] = 1;
  cycles(1);
  EXPECT_EQ(at(20000), 10000);  // the coupling table
  at(33600);
  mark(33633);  // 13633 into the working table: 300 late
  EXPECT_EQ(image.md(60), 300);
  EXPECT_EQ(at(40000), 30000) << "no correction in this period (its window had begun)";
  EXPECT_EQ(at(45000), 35000);
  EXPECT_EQ(at(50000), 40000 + 150) << "half of the window";
  EXPECT_EQ(at(55000), 45000 + 300);
  EXPECT_EQ(at(60000), 50300);
  EXPECT_EQ(at(60100), 50400);
  EXPECT_EQ(image.md(60), 0) << "no mark in the last period";
  at(75200);
  mark(75333 + 1500);  // outside the valid range (1333): ignored
  EXPECT_EQ(image.md(60), 0);
  EXPECT_EQ(at(80000), 70300);
  at(93200);
  mark(93233);  // 100 early (the earlier correction is part of the table's frame now)
  EXPECT_EQ(image.md(60), -100);
  EXPECT_EQ(at(105000), 95300) << "the -100 in the next period's window";
  EXPECT_EQ(at(110000), 100250);
  EXPECT_EQ(at(115000), 105200);
  image.e[8] = 0;  // clock out at the table end: the correction stays, the decoupling table runs
  EXPECT_EQ(at(120000), 110200);
  EXPECT_EQ(at(140000), 120200);
  EXPECT_EQ(at(150000), 120200);
}

TEST_F(SfTest, FipwExternalMasterSyncWaitsForTheZeroPulse) {
  DataBlock t(8);
  t.set_dw(0, 4).set_dd(4, 5000).set_dd(6, 10000);
  dbs[20] = t;
  init_ok(Init(1, 0).source(0, 16).sink(129, 40).tab(0, 20));
  auto c = command(0, 4, 1, 2);
  c.set_dw(3, 2).set_dw(4, 1).set_dd(8, 1).set_dd(10, 20000).set_dw(12, 1000);
  start_ok(c);
  for (int i = 0; i < 50; ++i) image.az[0] += 100, cycles(1);
  EXPECT_EQ(image.md(40), 0) << "nothing before the master's zero pulse";
  image.az[0] += 100;            // 5100
  image.az_zero[0].pulse(5050);  // X := offset 1000 at master 5050
  cycles(1);
  EXPECT_EQ(image.md(40), 0) << "the table continues from the sink, no jump";
  while (image.az[0] < 5050 + 9000) image.az[0] += 50, cycles(1);
  EXPECT_EQ(image.md(40), 5000 - 525) << "X = 10000: y 5000 - y(X at the first cycle = 1050) = 525";
}

// Printing mark control with the external-master sync: the master's zero pulse comes on a second
// input (AZ message 2, its counter 777 ahead of the first), which SF0 (DCOPY) copies into MD 40
// with its latch; SF1 (FIPW, DR7 = 40) starts the table at that pulse and corrects on the marks of
// its own input (AZ message 1).
TEST_F(SfTest, FipwPrintingMarkWithTheExternalSyncThroughMd) {
  DataBlock t(8);
  t.set_dw(0, 4).set_dd(4, 10000).set_dd(6, 20000);
  dbs[17] = t;
  init_ok(Init(0, 0).source(0, 18).sink(129, 40));
  start_ok(command(0, 1, 1, 0));
  init_ok(Init(1, 1).source(0, 16).sink(129, 60).tab(0, 17));
  auto c = command(1, 5, 1, 2);
  c.set_dw(3, 2).set_dw(4, 1).set_dd(8, 1).set_dd(10, 20000).set_dr(7, 40);
  c.set_dw(18, 3000).set_dd(20, 1000).set_dw(26, 64);  // the mark expected at 13333
  start_ok(c);
  image.az[1] = 777;
  auto step = [&] {
    image.az[0] += 50;
    image.az[1] += 50;
    cycles(1);
  };
  for (int i = 0; i < 100; ++i) step();
  EXPECT_EQ(image.md(60), 0) << "nothing before the master's zero pulse";
  image.az_zero[1].pulse(image.az[1] + 25);  // at master 5025 (counter 2: 5802)
  step();                                    // master 5050: X = 25 from the pulse
  EXPECT_EQ(image.md(60), 0) << "the table starts where the slave is";
  while (image.az[0] < 5025 + 13600) step();
  image.az_zero[0].pulse(5025 + 13633);  // the mark: 300 late
  step();
  EXPECT_EQ(image.md(64), 300);
  while (image.az[0] < 5025 + 20000) step();
  EXPECT_EQ(image.md(60), 20025 - 25 + 300) << "X = 20025 from the pulse, the slave started at X = 25";
}

// FIPZ timing: a 1 s table (Te = 2000 x 0.5 ms) at a 2 ms SF cycle takes exactly 500 cycles;
// each E1 edge (BA 16) runs Tab0 again, relative to where the last run ended.
class Fipz : public SfTest {
 protected:
  Fipz() : SfTest(4) {}  // ID 2 = 2 ms
};

TEST_F(Fipz, TimingAndRelativeRuns) {
  DataBlock t(8);
  t.set_dw(0, 4).set_dd(4, 5000).set_dd(6, 10000);
  dbs[20] = t;
  init_ok(Init(2, 1).sink(129, 40).in(1, 8).tab(0, 20));
  auto c = command(1, 0, 1, 16);
  c.set_dw(3, 4).set_dw(4, 1).set_dd(8, 1).set_dw(10, 2000);  // DW11..DW17 = 0: unused tables
  start_ok(c);
  cycles(10);
  EXPECT_EQ(image.md(40), 0);
  image.e[8] = 1;
  cycles(250);
  EXPECT_EQ(image.md(40), 5000);
  cycles(249);
  EXPECT_EQ(image.md(40), 9980);
  cycles(1);
  EXPECT_EQ(image.md(40), 10000) << "500 cycles of 2 ms";
  cycles(100);
  EXPECT_EQ(image.md(40), 10000);
  image.e[8] = 0;
  cycles(1);
  image.e[8] = 1;
  cycles(500);
  EXPECT_EQ(image.md(40), 20000);
}

TEST_F(Fipz, Ba17SelectsTheTableByE2ToE4) {
  DataBlock a(8), b(8);
  a.set_dw(0, 3).set_dd(4, 100);
  b.set_dw(0, 3).set_dd(4, -300);
  dbs[20] = a;
  dbs[21] = b;
  init_ok(Init(2, 1).sink(129, 40).in(1, 8).tab(0, 20).tab(1, 21));
  auto c = command(1, 0, 1, 17);
  c.set_dw(3, 4).set_dw(4, 2).set_dd(8, 2).set_dw(10, 40).set_dw(11, 40);  // K = 2
  start_ok(c);
  image.e[8] = 0b0011;  // E2 = 1 selects Tab1, E1 edge starts it
  cycles(10);
  EXPECT_EQ(image.md(40), -600);
  image.e[8] = 0;
  cycles(1);
  image.e[8] = 0b0001;  // Tab0
  cycles(10);
  EXPECT_EQ(image.md(40), -400);
}

}  // namespace
}  // namespace hil::controllers::amkasyn
