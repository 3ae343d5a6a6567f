// SPDX-License-Identifier: MIT
// CLM1.4 commands, group by group, on simulated drives: the manual's worked vectors
// (vectors/clm14.md #19-#35) and the rules of §4.2 (counters, stack, variables, MAT, VCC, ...).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "rig.hpp"

namespace hil::controllers::clm14 {
namespace {

using testing::bit;
using testing::byte;
using testing::Rig;
using namespace std::chrono_literals;

/// Run `lines` in Automatic until task 1 reaches `stop_line` (or times out).
[[maybe_unused]] bool run_to(Rig& r, int stop_line, Duration limit = 30s) {
  r.start_auto();
  return r.run_until([&] { return r.clm.task(1).pc == stop_line || r.clm.error() != 0; }, limit);
}

// ---- jumps on bits and bytes ------------------------------------------------------------------

struct JumpCase {
  std::string name;
  std::vector<std::pair<std::string, std::uint8_t>> bytes;  // preset marker bytes
  std::string line;
  int expect_pc;  // line reached after the jump (or 0001 when none)
};

TEST(ClmCommands, ComputedAndPatternJumps) {
  const std::vector<JumpCase> cases{
      // vector #19: binary 10110 = 22 -> 0500 + 22 x 11 = 0742
      {"BIC binary", {{"M2.03", 0b00000011}, {"M2.02", 0b01101011}}, "BIC 0500 11 M2.02.4 5 0", 742},
      // vector #21: BCD 10 + 4 + 2 = 16 -> 0676
      {"BIC BCD", {{"M2.03", 0b00000101}, {"M2.02", 0b01100111}}, "BIC 0500 11 M2.02.4 5 1", 676},
      // vector #27: pattern 11110000, bytes 11100010 / 11000010 -> no jump
      {"BIO no jump", {{"M2.03", 0b11100010}, {"M2.04", 0b11000010}}, "BIO 0900 M2.03 M2.04 11110000", 1},
      // both bytes match 1111x0x0 (bit 7 .. bit 0; 2 = either)
      {"BIO jump", {{"M2.03", 0b11110000}, {"M2.04", 0b11111010}}, "BIO 0900 M2.03 M2.04 11112020", 900},
      // bits 6, 5, 4, 1 must be 1 (pattern 21112212, bit 7 .. bit 0)
      {"BPA jump", {{"M2.02", 0b01110010}}, "BPA 0800 M2.02 21112212", 800},
      {"BPA no jump", {{"M2.02", 0b10100010}}, "BPA 0800 M2.02 21112212", 1},
      {"BCE jump", {{"M2.05", 0b00001000}}, "BCE 0700 M2.05.3 1", 700},
      {"BCE no jump", {{"M2.05", 0b00001000}}, "BCE 0700 M2.05.3 0", 1},
  };
  for (const auto& c : cases) {
    Rig r;
    r.program({{0, c.line}, {1, "JMP 0001"}, {c.expect_pc, "JMP " + fmt::format("{:04d}", c.expect_pc)}});
    r.enter_auto();  // M2 is cleared at power-up and on leaving Automatic: preset it in Automatic
    for (const auto& [b, v] : c.bytes) r.clm.image().set_byte(byte(b), v);
    r.pulse(sys::start);
    r.run_until([&] { return r.clm.task(1).pc == c.expect_pc && r.clm.cycles() > 20; }, 1s);
    EXPECT_EQ(r.clm.task(1).pc, c.expect_pc) << c.name << " error " << r.clm.error_message();
    EXPECT_EQ(r.clm.error(), 0) << c.name << ": " << r.clm.error_message();
  }
}

TEST(ClmCommands, BicErrors) {
  {
    Rig r;  // a BCD nibble above 9 is error 0D
    r.program({{0, "BIC 0500 11 M2.02.0 4 1"}});
    r.enter_auto();
    r.clm.image().set_byte(byte("M2.02"), 0x0C);
    r.pulse(sys::start);
    EXPECT_EQ(r.clm.error(), 0x0D);
    EXPECT_EQ(r.clm.error_item(1), "0000");
  }
  {
    Rig r;  // 2999 + 1 x 1 -> 0E
    r.program({{0, "BIC 2999 1 M2.02.0 1 0"}});
    r.enter_auto();
    r.clm.image().set_byte(byte("M2.02"), 0x01);
    r.pulse(sys::start);
    EXPECT_EQ(r.clm.error(), 0x0E);
  }
}

TEST(ClmCommands, AkpWaitsForTheWholePattern) {
  // vector #25: AKP M0.02 21001220 proceeds iff b0 = b4 = b5 = 0 and b3 = b6 = 1
  Rig r;
  r.program({{0, "AKP M2.02 21001220"}, {1, "JMP 0001"}});
  r.enter_auto();
  r.clm.image().set_byte(byte("M2.02"), 0b01001001);  // b0 = 1: waits
  r.pulse(sys::start);
  r.run_for(20ms);
  EXPECT_EQ(r.clm.task(1).pc, 0);
  r.clm.image().set_byte(byte("M2.02"), 0b11001110);  // b0 = b4 = b5 = 0, b3 = b6 = 1, others anything
  r.run_for(10ms);
  EXPECT_EQ(r.clm.task(1).pc, 1);
}

TEST(ClmCommands, ApeAeaCioWriteBitsAndBytes) {
  Rig r;
  r.program({{0, "APE Q1.01 21002210"},  // manual example a): bits 0,4,5 -> 0; 1,6 -> 1; 2,3,7 unchanged
             {1, "AEA Q1.00.6 1"},
             {2, "CIO Q1.01.0 M2.03.6 5"},  // 5 bits across the byte boundary
             {3, "JMP 0003"}});
  r.enter_auto();
  r.clm.image().set_byte(byte("Q1.01"), 0b10111101);
  r.pulse(sys::start);
  r.run_for(20ms);
  EXPECT_EQ(r.clm.image().byte(byte("Q1.01")), 0b11001110);
  EXPECT_TRUE(r.get(bit("Q1.00.6")));
  // Q1.01 bits 0..4 = 0,1,1,1,0 -> M2.03.6, M2.03.7, M2.04.0, M2.04.1, M2.04.2
  EXPECT_FALSE(r.get(bit("M2.03.6")));
  EXPECT_TRUE(r.get(bit("M2.03.7")));
  EXPECT_TRUE(r.get(bit("M2.04.0")));
  EXPECT_TRUE(r.get(bit("M2.04.1")));
  EXPECT_FALSE(r.get(bit("M2.04.2")));
}

TEST(ClmCommands, CioMoreThan32BitsIs3D) {
  Rig r;
  r.program({{0, "CIO I1.00.0 M2.00.0 33"}});
  r.start_auto();
  EXPECT_EQ(r.clm.error(), 0x3D);
}

// ---- variables, CVT, MAT, comparisons -------------------------------------------------------

TEST(ClmCommands, CvtBcdBothWays) {
  // vector #23: V600 = -87654321.654321 -> M2.00..07 = 21 43 65 21 43 65 87 FF
  Rig r;
  r.program({{0, "CVT V600 M2.00 0 0"},
             {1, "CVT V601 M2.00 0 1"},
             {2, "CVT V600 M2.10 1 0"},
             {3, "CVT V602 M2.10 1 1"},
             {4, "JMP 0004"}});
  ASSERT_TRUE(r.clm.set_variable(600, -87'654'321'654'321));
  r.start_auto();
  r.run_for(20ms);
  const std::array<std::uint8_t, 8> want{0x21, 0x43, 0x65, 0x21, 0x43, 0x65, 0x87, 0xFF};
  for (std::uint8_t i = 0; i < 8; ++i) EXPECT_EQ(r.clm.image().byte({Area::marker, 2, i}), want[i]) << int(i);
  EXPECT_EQ(r.clm.variable(601), -87'654'321'654'321);
  EXPECT_EQ(r.clm.variable(602), -87'654'321'654'321) << "binary layout round trip";
}

TEST(ClmCommands, SetMatAndVariableRules) {
  Rig r;
  r.program({{0, "SET V600 = +00001000.500000"},
             {1, "SET V601 = -V600"},
             {2, "MAT V602 = V600 * +2.5"},
             {3, "MAT V603 = V602 / V601"},
             {4, "MAT V604 = V600 - +123456.987654"},
             {5, "CID V604 1 +1.000000"},
             {6, "JMP 0006"}});
  r.start_auto();
  r.run_for(40ms);
  EXPECT_EQ(r.clm.variable(600), 1'000'500'000);
  EXPECT_EQ(r.clm.variable(601), -1'000'500'000);
  EXPECT_EQ(r.clm.variable(602), 2'501'250'000);
  EXPECT_EQ(r.clm.variable(603), -2'500'000);
  EXPECT_EQ(r.clm.variable(604), 1'000'500'000 - 123'456'987'654 + 1'000'000);
  EXPECT_EQ(r.clm.error(), 0);
}

TEST(ClmCommands, MatTakesCyclesAndSharesOneUnit) {
  Options o;
  o.mat_cycles_add = 1;
  o.mat_cycles_mul = 3;
  Rig r({{"B011", "0100 0000 0"}}, 1, o);
  r.program({{0, "MAT V600 = V600 * +1"}, {1, "JMP 0001"}, {100, "MAT V601 = V601 + +1"}, {101, "JMP 0101"}});
  r.start_auto();  // the start cycle and the next one: 2 of the 3 cycles of the multiplication
  EXPECT_EQ(r.clm.task(1).pc, 0) << "multiplication still running";
  EXPECT_EQ(r.clm.task(2).pc, 100) << "task 2 waits for the shared unit";
  r.cycle();
  EXPECT_EQ(r.clm.task(1).pc, 1) << "3 cycles for the multiplication";
  EXPECT_EQ(r.clm.task(2).pc, 101) << "the unit is free again later in the same cycle (task order 1..5)";
}

TEST(ClmCommands, VariableErrors) {
  const std::vector<std::tuple<std::string, std::string, int>> cases{
      {"MAT V600 = V601 / +0", "division by zero", 0x07},
      {"SET V100 = +1", "Vx00 may be set while the axis is not homed", 0},
      {"SET V500 = +1", "system variable", 0x31},
      {"POI 1 V602 999", "feed too large", 0x32},
      {"POI 1 +000001.000 V603", "negative velocity", 0x32},
      {"MAT V600 = V605 * V605", "overflow", 0x32},
  };
  for (const auto& [line, what, code] : cases) {
    Rig r;
    r.program({{0, line}, {1, "JMP 0001"}});
    ASSERT_TRUE(r.clm.set_variable(602, 1'234'567'123'456));
    ASSERT_TRUE(r.clm.set_variable(603, -999'999'990));
    ASSERT_TRUE(r.clm.set_variable(605, 99'999'999'000'000));
    r.start_auto();
    r.run_for(20ms);
    EXPECT_EQ(r.clm.error(), code) << line << " (" << what << "): " << r.clm.error_message();
  }
}

TEST(ClmCommands, VariablesInCommandFields) {
  // §5.6: V600 = +00123456.123456 -> feed +123456.123; V601 = +999.9999 -> velocity 999;
  // -V604 with V604 = -1234.123456 -> +1234.123
  Rig r({{"A104", "+200000.000"}, {"A106", "050000.000"}, {"A108", "999999"}});
  r.program({{0, "POI 1 -V604 V601"}, {1, "JMP 0001"}});
  ASSERT_TRUE(r.clm.set_variable(601, 999'999'900));
  ASSERT_TRUE(r.clm.set_variable(604, -1'234'123'456));
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return std::abs(r.pos() - 1234.123) < 0.002 && !r.clm.velocity(1); }, 10s));
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
}

TEST(ClmCommands, CompareAndJump) {
  Rig r;
  r.program({{0, "CPJ V600 = +00010.000 0000.50 0100"},
             {1, "JMP 0001"},
             {100, "CPS V600 > +00010.000 0000.00 M2.01.0"},
             {101, "CPJ V600 <>+V601 0000.00 0200"},
             {102, "JMP 0102"},
             {200, "JMP 0200"}});
  ASSERT_TRUE(r.clm.set_variable(600, 10'400'000));  // 10.4: equal within 0.5
  ASSERT_TRUE(r.clm.set_variable(601, 10'400'000));
  r.start_auto();
  r.run_for(20ms);
  EXPECT_EQ(r.clm.task(1).pc, 102) << "= within tolerance jumps; <> of equal values does not";
  EXPECT_TRUE(r.get(bit("M2.01.0")));
}

// ---- subroutines and counters -----------------------------------------------------------------

TEST(ClmCommands, SubroutineStackIs127Levels) {
  {
    Rig r;  // a JSR to itself nests until level 128 -> 0B
    r.program({{0, "JSR 0000"}});
    r.start_auto();
    r.run_for(400ms);
    EXPECT_EQ(r.clm.error(), 0x0B);
  }
  {
    Rig r;  // 127 levels are fine, then 127 returns
    r.program({{0, "SET V600 = +0"},
               {1, "JSR 0010"},
               {2, "JMP 0002"},
               {10, "MAT V600 = V600 + +1"},
               {11, "CPJ V600 < +127 0.00 0013"},
               {12, "RTS"},
               {13, "JSR 0010"},
               {14, "RTS"}});
    r.start_auto();
    r.run_until([&] { return r.clm.task(1).pc == 2 || r.clm.error() != 0; }, 10s);
    EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
    EXPECT_EQ(r.clm.variable(600), 127 * micro_one);
  }
  {
    Rig r;  // RTS without JSR -> 0C; CST 1 0 empties the stack first
    r.program({{0, "JSR 0005"}, {5, "CST 1 0"}, {6, "RTS"}});
    r.start_auto();
    r.run_for(20ms);
    EXPECT_EQ(r.clm.error(), 0x0C);
  }
}

TEST(ClmCommands, CountersPersistAndTakeTheirOffsetWhenStored) {
  Rig r;
  r.program({{0, "COU +00000 Q1.00.4 000003"}, {1, "JMP 0000"}});
  ASSERT_TRUE(r.clm.store_line(0, "COU +00001 Q1.00.4 000003"));  // offset +1 applied once
  EXPECT_EQ(r.clm.line_text(0), "COU +00000 Q1.00.4 000003");
  EXPECT_EQ(r.clm.counter(0)->count, 1);
  r.start_auto();  // counts 2 in the start cycle
  EXPECT_EQ(r.clm.counter(0)->count, 2);
  r.cycle();
  r.cycle();
  EXPECT_EQ(r.clm.counter(0)->count, 0);
  EXPECT_TRUE(r.get(bit("Q1.00.4")));
  ASSERT_TRUE(r.clm.store_line(0, "COU 000000 Q1.00.4 000003"));
  EXPECT_EQ(r.clm.counter(0)->count, 0);
  EXPECT_EQ(r.clm.counter(0)->preset, 3);
  EXPECT_FALSE(r.clm.counter(1).has_value());
}

TEST(ClmCommands, CounterWithVariablePresetWritesTheCountToTheNextVariable) {
  Rig r;
  r.program({{0, "BAC 0000 +0000 V610"}, {1, "JMP 0001"}});
  ASSERT_TRUE(r.clm.set_variable(610, 5 * micro_one));
  r.start_auto();  // two cycles: two counts
  EXPECT_EQ(r.clm.variable(611), 2 * micro_one);
  r.run_for(20ms);
  EXPECT_EQ(r.clm.task(1).pc, 1);
  EXPECT_EQ(r.clm.variable(611), 0);
}

// ---- motion -------------------------------------------------------------------------------------

TEST(ClmCommands, PoaNeedsHomingAndMovesAbsolute) {
  // vector #29: from -100, POA +200 moves +300; from +400, -200.
  Rig r({{"A124", "M2.01.0 +100 1"}});
  r.program({{0, "POA 1 +000200.000 999"}});
  r.start_auto();
  EXPECT_EQ(r.clm.error(), 0x48) << "not homed";
  Rig h({{"A124", "M2.01.0 +100 1"}, {"A125", "-00100.000"}});
  h.program(
      {{0, "HOM 1"}, {1, "AKN M2.01.0 1"}, {2, "PSA 1 +000200.000 999"}, {3, "SET V600 = V100"}, {4, "JMP 0004"}});
  h.start_auto();
  ASSERT_TRUE(h.run_until([&] { return h.clm.task(1).pc == 4 || h.clm.error() != 0; }, 20s)) << h.clm.error_message();
  EXPECT_NEAR(h.pos(), 200.0, 0.011);
  EXPECT_TRUE(h.clm.homed(1));
}

TEST(ClmCommands, TravelLimitsOnTargets) {
  Rig r({{"A124", "M2.01.0 +100 1"}, {"A103", "-000010.000"}, {"A104", "+000050.000"}});
  r.program({{0, "HOM 1"}, {1, "AKN M2.01.0 1"}, {2, "POA 1 +000060.000 999"}});
  r.start_auto();
  r.run_until([&] { return r.clm.error() != 0; }, 5s);
  EXPECT_EQ(r.clm.error(), 0x51);
  Rig s({{"A124", "M2.01.0 +100 1"}, {"A203", "-000010.000"}, {"A204", "+000050.000"}}, 2);
  s.program({{0, "HOM 2"}, {1, "AKN M2.01.0 0"}, {2, "WAI 00.200"}, {3, "POA 2 -000020.000 999"}});
  s.start_auto();
  s.run_until([&] { return s.clm.error() != 0; }, 5s);
  EXPECT_EQ(s.clm.error(), 0x80) << "axis 2 code = 0x50 + 0x30: " << s.clm.error_message();
}

TEST(ClmCommands, PsiWaitsForTheWindowPoiDoesNot) {
  // vector #31 rule: PSx continues once inside ±Ax27 of the target
  Rig r({{"A127", "M2.00.0 0000.200"}});
  r.program({{0, "PSI 1 +000100.000 999"}, {1, "SET V600 = V100"}, {2, "JMP 0002"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 2; }, 10s));
  const double at = to_double(r.clm.variable(600));
  EXPECT_GE(at, 99.8);
  EXPECT_LE(at, 100.2);
  Rig p;
  p.program({{0, "POI 1 +000100.000 999"}, {1, "SET V600 = V100"}, {2, "JMP 0002"}});
  p.start_auto();
  p.cycle();
  EXPECT_EQ(p.clm.task(1).pc, 2) << "POI proceeds at once";
  EXPECT_LT(to_double(p.clm.variable(600)), 1.0);
}

TEST(ClmCommands, PoiAddsToTheRemainingDistanceAndFakScales) {
  Rig r;
  r.program({{0, "POI 1 +000010.000 500"},
             {1, "POI 1 +000010.000 500"},
             {2, "FAK 1 1.500000"},
             {3, "PSI 1 +000010.000 999"},
             {4, "JMP 0004"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 4; }, 10s));
  r.run_for(100ms);
  EXPECT_NEAR(r.pos(), 35.0, 0.011);
}

TEST(ClmCommands, PbkDiscardsTheRemainingDistance) {
  Rig r;
  r.program({{0, "POI 1 +001000.000 999"},
             {1, "WAI 00.500"},
             {2, "PBK 1"},
             {3, "AKN M2.00.0 1"},
             {4, "POI 1 +000050.000 100"},
             {5, "AKN M2.00.0 1"},
             {6, "JMP 0006"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 4; }, 10s));
  const double stopped = r.pos();
  EXPECT_LT(stopped, 100.0);
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 6; }, 10s));
  EXPECT_NEAR(r.pos(), stopped + 50.0, 0.02);
}

TEST(ClmCommands, PbkThenPoiAddsToTheBrakingEndWithoutAStop) {
  // vector #33: CON 1 1 +999, WAI 02.000, PBK 1, POI 1 +000050.000 100: the axis travels the
  // braking distance (99.9 IU/s at 1000 IU/s²: 4.99 IU) + 50 IU from the PBK point, and never stops
  // in between (a continuous transition 99.9 % -> 10 %).
  Rig r;
  r.program({{0, "CON 1 1 +999"}, {1, "WAI 02.000"}, {2, "PBK 1"}, {3, "POI 1 +000050.000 100"}, {4, "JMP 0004"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 2; }, 5s));
  const double at_pbk = r.motion_axes[0]->status().command_position;  // PBK reads it in the next cycle
  const double end = at_pbk + 99.9 * 99.9 / 2000.0 + 50.0;
  double slowest = 1e9;
  ASSERT_TRUE(r.run_until(
      [&] {
        const auto& st = r.motion_axes[0]->status();
        // before the feed's own final braking (10 IU/s: 0.05 IU)
        if (st.busy && st.command_position < end - 0.1) slowest = std::min(slowest, std::abs(st.command_velocity));
        return !st.busy;
      },
      20s));
  EXPECT_NEAR(r.pos(), end, 0.05);
  EXPECT_GT(slowest, 9.9) << "no stop between the braking and the 10 % feed";
}

TEST(ClmCommands, ConRunsUntilStopped) {
  Rig r;
  r.program({{0, "CON 1 1 +500"}, {1, "WAI 01.000"}, {2, "CON 1 0 +000"}, {3, "JMP 0003"}});
  r.start_auto();
  r.run_for(600ms);
  EXPECT_NEAR(r.clm.velocity(1), 50.0, 1.0);
  r.run_for(1s);
  EXPECT_NEAR(r.clm.velocity(1), 0.0, 0.01);
  EXPECT_GT(r.pos(), 40.0);
}

TEST(ClmCommands, VccChangesVelocityInsideAMove) {
  // §4.4 VCC example: 100 IU at 99.9 %, then 25 % after 50, 50 % after 75, 10 % after 90
  Rig r({{"A108", "009999"}});
  r.program({{0, "POI 1 +000100.000 999"},
             {1, "VCC 1 +000050.000 250 0 0"},
             {2, "VCC 1 +000075.000 500 0 0"},
             {3, "VCC 1 +000090.000 100 0 0"},
             {4, "AKN M2.00.0 1"},
             {5, "JST 0000"}});
  r.start_auto();
  std::vector<std::pair<double, double>> samples;  // position, velocity
  r.run_until(
      [&] {
        samples.emplace_back(r.pos(), r.clm.velocity(1));
        return r.clm.run_state() == RunState::stopped;
      },
      20s);
  const auto v_at = [&](double p) {
    for (const auto& s : samples)
      if (s.first >= p) return s.second;
    return 0.0;
  };
  EXPECT_NEAR(v_at(40), 99.9, 1.0);
  EXPECT_NEAR(v_at(65), 25.0, 1.0);
  EXPECT_NEAR(v_at(85), 50.0, 1.0);
  EXPECT_NEAR(v_at(95), 10.0, 1.0);
  EXPECT_NEAR(r.pos(), 100.0, 0.011);
}

TEST(ClmCommands, VeoOverridesLaterMoves) {
  Rig r;
  r.program({{0, "VEO 1 4 1 500 0"},
             {1, "POI 1 +000100.000 999"},
             {2, "WAI 00.500"},
             {3, "SET V600 = V104"},
             {4, "VEO 1 4 1 300 1"},
             {5, "POI 1 +000100.000 999"},
             {6, "WAI 00.800"},
             {7, "SET V601 = V104"},
             {8, "JMP 0008"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 8; }, 10s));
  EXPECT_NEAR(to_double(r.clm.variable(600)), 49.95, 0.5) << "as factor: 999 ‰ x 0.5";
  EXPECT_NEAR(to_double(r.clm.variable(601)), 30.0, 0.5) << "as limit: 30 % of Vmax";
}

TEST(ClmCommands, SrmLatchesTheMarkAndMovesTheOffset) {
  Rig r;
  r.program({{0, "SRM 1 +000020.000 +500 I1.01.0"}, {1, "AKN M2.00.0 1"}, {2, "JMP 0002"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.pos() > 30.0; }, 5s));
  r.set(bit("I1.01.0"), true);
  r.cycle();
  const double mark = r.clm.latched_position(1);
  EXPECT_NEAR(mark, 30.0, 0.5);
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 2; }, 5s));
  EXPECT_NEAR(r.pos(), mark + 20.0, 0.011);
}

TEST(ClmCommands, RepLimitsTheSearchAndJumps) {
  Rig r;
  r.program({{0, "SRM 1 +000001.000 +500 I1.01.0"},
             {1, "REP 0900 1 000040.000"},
             {2, "SRM 1 +000001.000 +500 I1.01.0"},
             {3, "JMP 0003"},
             {900, "JMP 0900"}});
  r.start_auto();
  r.run_for(200ms);
  r.pulse(bit("I1.01.0"));
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 900 || r.clm.error() != 0; }, 10s)) << r.clm.error_message();
  EXPECT_EQ(r.clm.task(1).pc, 900) << r.clm.error_message();
}

TEST(ClmCommands, RepAfterSrmOfAnotherAxisIs1A) {
  Rig r({}, 2);
  r.program({{0, "SRM 1 +000001.000 +500 I1.01.0"}, {1, "REP 0900 2 000040.000"}});
  r.start_auto();
  r.run_for(100ms);
  r.pulse(bit("I1.01.0"));
  r.run_until([&] { return r.clm.error() != 0; }, 5s);
  EXPECT_EQ(r.clm.error(), 0x1A) << r.clm.error_message();
}

TEST(ClmCommands, SacSetsAndOffsetsCoordinates) {
  // rotary axis (type 0), not homed: SAC 1 0 sets the actual position and homes the axis
  Rig r({{"A100", "0 0 0 0 0"}});
  r.program({{0, "SAC 1 0 +000500.000"}, {1, "PSI 1 +000010.000 999"}, {2, "SAC 1 0 +000100.000"}, {3, "JMP 0003"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 3; }, 5s));
  EXPECT_TRUE(r.clm.homed(1));
  EXPECT_NEAR(r.pos(), 610.0, 0.011);
  Rig l;  // linear, not homed: SAC 0/1 -> "Axis not homed"
  l.program({{0, "SAC 1 1 +000500.000"}});
  l.start_auto();
  EXPECT_EQ(l.clm.error(), 0x48);
  Rig c({{"A120", "3 0 00 1"}});  // controlled axis -> 1B
  c.program({{0, "SAC 1 1 +000500.000"}});
  c.start_auto();
  EXPECT_EQ(c.clm.error(), 0x1B);
}

TEST(ClmCommands, RotaryTableTakesTheShortestPathWithRtm) {
  Rig r({{"A100", "2 0 0 0 0"}, {"A105", "000360.000 0"}, {"A124", "M2.01.0 +100 1"}, {"A106", "001000.000"}});
  r.program({{0, "HOM 1"},
             {1, "AKN M2.01.0 1"},
             {2, "RTM 1 1"},
             {3, "PSA 1 +000350.000 999"},
             {4, "SET V600 = V100"},
             {5, "RTM 1 2"},
             {6, "PSA 1 +000010.000 999"},
             {7, "SET V601 = V100"},
             {8, "JMP 0008"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 8 || r.clm.error(); }, 20s)) << r.clm.error_message();
  EXPECT_NEAR(to_double(r.clm.variable(600)), -10.0, 0.011) << "350 is 10 back the short way";
  EXPECT_NEAR(to_double(r.clm.variable(601)), 10.0, 0.011) << "programmed direction: +20 forward";
}

TEST(ClmCommands, WaiWaitsItsTime) {
  Rig r;
  r.program({{0, "WAI 00.100"}, {1, "JMP 0001"}});
  r.start_auto();
  const TimePoint started = r.now;
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 1; }, 1s));
  EXPECT_NEAR(std::chrono::duration<double>(r.now - started).count(), 0.1, 0.0025);
}

TEST(ClmCommands, TxtTextsForStatus53And63) {
  Rig r;
  r.program({{0, "TXT 0 LINE ONE"}, {1, "TXT 0 LINE TWO"}, {2, "TXT 1 MOTOR HOT"}, {3, "JMP 0003"}});
  r.start_auto();  // cycle 1: both TXT 0 lines; cycle 2: TXT 1
  EXPECT_EQ(r.clm.task(1).pc, 3) << "two TXT 0 lines in one cycle";
  EXPECT_EQ(r.clm.text_lines()[0], "LINE ONE        ");
  EXPECT_EQ(r.clm.text_lines()[1], "LINE TWO        ");
  EXPECT_EQ(r.clm.status_text(), "MOTOR HOT       ");
  r.set(sys::automatic, false);
  r.cycle();
  EXPECT_EQ(r.clm.status_text(), "") << "cleared on Auto -> Manual";
}

TEST(ClmCommands, MasterEncoderCommandsWithoutTheEncoderStopWith0A) {
  // No master encoder attached: the commands that need it stop the program with 0A and say so.
  for (const std::string line : {"LML 1 001000.000", "VEO 1 5 1 500 0", "MLT 1 000010.000 Q1.00.0", "FUN 2222022"}) {
    Rig r({{"C002", "0020.00000"}, {"A100", "1 5 0 0 0"}});
    r.program({{0, "NOP"}, {1, line}});
    r.start_auto();
    r.run_for(std::chrono::milliseconds(10));
    EXPECT_EQ(r.clm.error(), 0x0A) << line;
    EXPECT_NE(r.clm.error_message().find("master encoder 1"), std::string::npos) << r.clm.error_message();
  }
}

}  // namespace
}  // namespace hil::controllers::clm14
