// SPDX-License-Identifier: MIT
// SF EPOS (type 11): the discrete trapezoid landing exactly, stop and continue, retrigger, velocity
// and acceleration override, modulo positioning with A2, external velocity, substitutional
// positioning on the drive's reference latch (with and without reversal), VALUE NEW, START checks.
#include <gtest/gtest.h>

#include <algorithm>

#include "sf_fixture.hpp"

namespace hil::controllers::amkasyn {
namespace {

using testing::command;
using testing::Init;
using testing::SfTest;

// ID 2 = 1 ms, DD12 = 10000 incr/rev: DD6 = 600000 (60 rpm) = 10 increments per cycle, DD8 =
// 100000 (100 rev/s^2) = 1 increment per cycle^2, DD10 = 200000 = 2.
class Epos : public SfTest {
 protected:
  DataBlock cmd(int ba, std::int32_t travel = 1000) {
    auto c = command(0, 0, 1, ba);
    c.set_dw(3, 2).set_dd(4, travel).set_dd(6, 600000).set_dd(8, 100000).set_dd(10, 200000).set_dd(12, 10000);
    return c;
  }
  void start(int ba, std::int32_t travel = 1000) {
    init_ok(Init(11, 0).source(0, 1).sink(1, 16).in(1, 12).out(1, 12));
    start_ok(cmd(ba, travel));
  }
  void edge(int bit) {
    image.e[12] = static_cast<std::uint8_t>(image.e[12] & ~bit);
    cycles(1);
    image.e[12] = static_cast<std::uint8_t>(image.e[12] | bit);
  }
  std::int32_t pos() const { return image.aw[0].swq2; }
  int a() const { return image.a[12] & 3; }
};

TEST_F(Epos, RelativeTrapezoidLandsExactly) {
  start(0);
  cycles(3);
  EXPECT_EQ(a() & 1, 1) << "A1 = 1 at standstill";
  edge(1);
  cycles(10);  // 1 + 2 + ... + 10
  EXPECT_EQ(pos(), 55);
  EXPECT_EQ(a() & 1, 0);
  cycles(98);  // cruise 10 per cycle, then 10, 9, ..., 2
  EXPECT_EQ(pos(), 999);
  EXPECT_EQ(a() & 1, 0);
  cycles(1);
  EXPECT_EQ(pos(), 1000);
  EXPECT_EQ(a() & 1, 1);
  cycles(5);
  EXPECT_EQ(pos(), 1000);
  edge(1);  // the next start moves DD4 further
  cycles(109);
  EXPECT_EQ(pos(), 2000);
}

TEST_F(Epos, StopDeceleratesAndANewEdgeContinues) {
  start(0);
  edge(1);
  cycles(20);
  EXPECT_EQ(pos(), 155);
  edge(2);    // stop with DD10: 8, 6, 4, 2, 0 (the edge cycle moved 10)
  cycles(5);  // 165 + 20
  EXPECT_EQ(pos(), 185);
  EXPECT_EQ(a() & 1, 1);
  cycles(5);
  EXPECT_EQ(pos(), 185);
  edge(1);  // continue the interrupted positioning
  cycles(200);
  EXPECT_EQ(pos(), 1000);
}

TEST_F(Epos, RetriggerAddsToTheResidualDistance) {
  start(8);
  edge(1);
  cycles(20);
  edge(1);  // the travel is added
  cycles(300);
  EXPECT_EQ(pos(), 2000);
  ASSERT_FALSE(rt.command(command(0, 0, 0, 0), image).error);
  start(0);  // without bit3 an edge while moving is ignored
  edge(1);
  cycles(20);
  edge(1);
  cycles(300);
  EXPECT_EQ(pos(), 3000);
}

TEST_F(Epos, VelocityAndAccelerationOverride) {
  init_ok(Init(11, 0).sink(1, 16).in(1, 12).out(1, 12));
  auto c = cmd(0);
  c.set_dw(16, 21).set_dw(17, 30);  // odd: MW 20
  start_ok(c);
  image.set_mw(20, 512);  // 50 %: 5 per cycle
  image.set_mw(30, 50);   // below 10 %: 102/1024 (sampled at the edge)
  edge(1);
  cycles(1);  // the edge samples the acceleration override
  image.set_mw(30, 1024);
  EXPECT_EQ(pos(), 0) << "0.0996 per cycle^2";
  cycles(99);
  EXPECT_GT(pos(), 0);
  const auto p = pos();
  image.set_mw(20, 0);  // override 0: no output
  cycles(5);
  EXPECT_EQ(pos(), p);
  image.set_mw(20, 512);
  cycles(2000);
  EXPECT_EQ(pos(), 1000);
}

TEST_F(Epos, ModuloRunsOnWhileE1IsHeld) {
  start(16);
  edge(1);  // E1 stays 1
  cycles(100);
  EXPECT_EQ(pos(), 955);
  cycles(55);
  EXPECT_EQ(pos(), 1505) << "no ramp-down at 1000: another DD4";
  EXPECT_EQ(a(), 2) << "A2 = constant speed";
  image.e[12] = 0;  // stops at the next modulo value
  cycles(200);
  EXPECT_EQ(pos(), 2000);
  EXPECT_EQ(a(), 1);
}

TEST_F(Epos, ExternalVelocityFromTheSource) {
  init_ok(Init(11, 0).source(0, 1).sink(1, 16).in(1, 12).out(1, 12));
  auto c = cmd(1);
  c.set_dd(14, 20000);  // master 20000 incr/rev, drive 10000: half the master's increments
  start_ok(c);
  edge(1);
  for (int i = 0; i < 10; ++i) {
    image.az[0] += 10 << 16;  // 10 master increments per cycle -> 5
    cycles(1);
  }
  EXPECT_EQ(pos(), 1 + 2 + 3 + 4 + 5 + 5 * 5);
}

TEST_F(Epos, SubstitutionalPositionsRelativeToTheReference) {
  for (const int ba : {2, 6}) {
    for (const std::int32_t travel : {-300, -20}) {
      image = ProcessImage{};
      init_ok(Init(11, 0).sink(1, 4).in(1, 12).out(1, 12));
      auto c = cmd(ba, travel);
      c.set_dd(6, -600000);  // approach in the negative direction
      start_ok(c);
      edge(1);
      int guard = 0;
      while (image.aw[0].swq1 > -200 && ++guard < 1000) cycles(1);
      image.aw[0].reference_position = -200;  // the reference latched at -200
      ++image.aw[0].reference_count;
      std::int16_t lowest = 0;
      for (int i = 0; i < 300; ++i) {
        cycles(1);
        lowest = std::min(lowest, image.aw[0].swq1);
      }
      EXPECT_EQ(image.aw[0].swq1, -200 + travel) << "BA " << ba << " DD4 " << travel;
      EXPECT_EQ(a() & 1, 1);
      if (ba == 6 && travel == -20)
        EXPECT_LT(lowest, -220) << "with reversal: overshoot and back";
      else
        EXPECT_EQ(lowest, -200 + travel) << "BA " << ba << " DD4 " << travel;
      ASSERT_FALSE(rt.command(command(0, 0, 0, 0), image).error);
    }
  }
}

TEST_F(Epos, ValueNewAndStartChecks) {
  start(0);
  auto vn = cmd(0, 500);
  vn.set_dr(1, 5);
  ASSERT_FALSE(rt.command(vn, image).error);
  edge(1);
  cycles(300);
  EXPECT_EQ(pos(), 500) << "the travel from the next start edge";
  ASSERT_FALSE(rt.command(command(0, 0, 0, 0), image).error);
  auto bad = cmd(0);
  bad.set_dd(10, 1000);
  auto s = rt.command(bad, image);
  EXPECT_NE(s.text.find("at least the acceleration"), std::string::npos) << s.text;
  EXPECT_NE(rt.command(cmd(1), image).text.find("DD14"), std::string::npos) << "external velocity needs DD14";
  EXPECT_FALSE(rt.command(cmd(0), image).error) << "DD14 = 0 without external velocity (the manual's example)";
  ASSERT_FALSE(rt.command(command(0, 0, 0, 0), image).error);
  s = rt.command(cmd(2), image);
  EXPECT_NE(s.text.find("SWQ1"), std::string::npos) << s.text;
  init_ok(Init(11, 0).sink(1, 4).in(1, 12).out(1, 12));
  s = rt.command(cmd(2, 0), image);
  EXPECT_NE(s.text.find("must not be 0"), std::string::npos) << s.text;
  s = rt.command(cmd(18), image);
  EXPECT_NE(s.text.find("relative positioning only"), std::string::npos) << s.text;
}

}  // namespace
}  // namespace hil::controllers::amkasyn
