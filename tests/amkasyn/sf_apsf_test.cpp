// SPDX-License-Identifier: MIT
// SF APSF (type 10) and its AWL subset: vector 6.13 (the speed of a non-AMK drive from the X32
// encoder commands AW1 in 0.0001 rpm) with exact values, the SF-PAE/PAA overlay, EB 217, RESET
// running the FB once more, forbidden commands, running time errors, DB access, bit logic, and
// the parser's errors.
#include <gtest/gtest.h>

#include "hil/controllers/amkasyn/awl.hpp"
#include "sf_fixture.hpp"

namespace hil::controllers::amkasyn {
namespace {

using testing::command;
using testing::Init;
using testing::SfTest;

// FB10 of 6.13 in the subset (the printed listing is partly garbled; the logic as the digest
// reconstructs it): on START MD24 := ED212 and the speed 0; on RESET or E216.0 = 0 the speed 0;
// else n = WWD(ED212 - MD24) x 30000 / 2 (incr per 2 ms -> 0.0001 rpm at 20000 incr/rev),
// MD24 := ED212. A216.0 echoes the input bit.
constexpr const char* fb10 = R"(FB10
NAME:APSF
      U    E 216.0        ; the SF's input bit
      =    A 216.0        ; A8.0: running
      L    EB 217         ; commanding code: 1 START, 0 RESET, 255 running
      L    KB 1
      !=F
      SPB  =STRT
      L    EB 217
      L    KB 0
      !=F
      SPB  =NULL
      UN   E 216.0
      SPB  =NULL
      L    ED 212         ; source: AZ message 1 high word (X32)
      L    MD 24
      -D
      WWD                 ; the 16-bit difference, sign-extended
      L    KD 30000
      xD
      L    KF 2
      :D
      T    AD 212         ; sink: SWQ2 of AW1
      L    ED 212
      T    MD 24
      BEA
STRT: L    ED 212
      T    MD 24
NULL: L    KD 0
      T    AD 212
      BE
)";

class Apsf : public SfTest {
 protected:
  Apsf() : SfTest(4) {}  // ID 2 = 2 ms
  void start_6_13() {
    ASSERT_TRUE(rt.load_fb(10, fb10)) << rt.load_fb(10, fb10).error();
    dbs[20] = DataBlock(8);
    init_ok(Init(10, 0).source(0, 1).sink(1, 16).in(1, 8).out(1, 8));
    auto c = command(0, 0, 1, 0);
    c.set_dw(3, 0).set_dw(4, 10).set_dw(5, 20).set_dw(6, 1);
    start_ok(c);
  }
  void master(int incr_per_cycle, int n) {
    for (int i = 0; i < n; ++i) {
      image.az[0] = static_cast<std::int32_t>(static_cast<std::uint32_t>(image.az[0]) +
                                              (static_cast<std::uint32_t>(incr_per_cycle) << 16));
      cycles(1);
    }
  }
  std::int32_t speed() const { return image.aw[0].swq2; }
};

TEST_F(Apsf, Vector6_13EncoderSpeedToSwq2) {
  image.az[0] = 32700 << 16;  // near the 16-bit wrap of the high word
  start_6_13();
  master(10, 1);  // EB 217 = 1: MD24 := ED212, speed 0
  EXPECT_EQ(speed(), 0);
  EXPECT_EQ(image.md(24), 32710);
  master(10, 1);
  EXPECT_EQ(speed(), 0) << "E8.0 = 0: no speed";
  image.e[8] = 1;
  master(10, 1);  // MD24 still from START: 2 cycles of increments
  EXPECT_EQ(speed(), 20 * 30000 / 2);
  EXPECT_EQ(image.a[8] & 1, 1);
  master(10, 10);  // across the 16-bit wrap: 10 increments per 2 ms = 15 rpm = 150000
  EXPECT_EQ(speed(), 150000);
  master(-7, 3);
  EXPECT_EQ(speed(), -105000);
  EXPECT_EQ(image.e[212], 0) << "the SF-PAE bytes are the SF's own, not the PLC's";
  ASSERT_FALSE(rt.command(command(0, 0, 0, 0), image).error);  // RESET: the FB runs once with EB 217 = 0
  EXPECT_EQ(speed(), 0);
  master(10, 5);
  EXPECT_EQ(speed(), 0) << "reset: the SF no longer runs";
}

TEST_F(Apsf, ForbiddenCommandsRefuseStart) {
  ASSERT_TRUE(rt.load_fb(3, "L KB 1\nSI T 4\nSPA FB 7\nE DB 9\nL MW 2\nSTP\nBE\n"));
  init_ok(Init(10, 0).sink(129, 40));
  auto c = command(0, 0, 1, 0);
  c.set_dw(4, 3);
  const auto s = rt.command(c, image);
  EXPECT_EQ(s.code, SfError::apsf_runtime);
  EXPECT_EQ(image.m[233], 6);
  for (const char* f : {"line 2: SI T 4", "line 3: SPA FB 7", "line 4: E DB 9", "line 6: STP"})
    EXPECT_NE(s.text.find(f), std::string::npos) << f << " in " << s.text;
  EXPECT_EQ(rt.state(0), SfState::reset);
  c.set_dw(4, 4);
  EXPECT_NE(rt.command(c, image).text.find("not loaded"), std::string::npos);
}

TEST_F(Apsf, EndlessLoopIsARunningTimeErrorThatStopsTheSf) {
  ASSERT_TRUE(rt.load_fb(3, "L MW 10\nT MW 12\nU M 20.0\nSPB =LOOP\nBE\nLOOP: SPA =LOOP\n"));
  init_ok(Init(10, 0).sink(129, 40));
  auto c = command(0, 0, 1, 0);
  c.set_dw(4, 3);
  start_ok(c);
  image.set_mw(10, 42);
  cycles(1);
  EXPECT_EQ(image.mw(12), 42);
  EXPECT_EQ(rt.state(0), SfState::active);
  image.m[20] = 1;
  cycles(1);
  EXPECT_EQ(rt.state(0), SfState::reset) << "stopped";
  EXPECT_EQ(image.m[232] & 1, 1);
  EXPECT_EQ(image.m[233], 6);
  EXPECT_NE(rt.status().text.find("more than 10000 statements"), std::string::npos) << rt.status().text;
}

TEST_F(Apsf, DataBlockAccessBitLogicAndCompares) {
  DataBlock d(8);
  d.set_dw(1, 7).set_dd(2, 100000);
  dbs[21] = d;
  ASSERT_TRUE(rt.load_fb(5, R"(
      L    DW 1
      L    DD 2
      +D
      T    DD 4          ; 100007 into the opened DB
      T    AD 212        ; and the sink
      L    KF -3
      L    KF 5
      <F                  ; -3 < 5
      U    M 30.1
      O    M 30.2
      =    M 31.0
      L    KH 00FF
      T    MB 32
      L    KM 0000 0000 1111 0000
      T    MW 34
      L    MW 34
      L    KH 0F0F
      UW                  ; 0x0000
      L    KH 00F0
      OW                  ; 0x00F0
      SLW  4              ; 0x0F00
      L    KH FFFF
      XOW                 ; 0xF0FF
      T    MW 36
      L    KD 1
      SLD  31
      SRD  30             ; 2
      KEW                 ; 0xFFFD
      T    MD 44
      BE
)"));
  init_ok(Init(10, 0).sink(129, 40));
  auto c = command(0, 0, 1, 0);
  c.set_dw(4, 5).set_dw(5, 21);
  start_ok(c);
  image.m[30] = 0b100;
  cycles(1);
  EXPECT_EQ(image.md(40), 100007);
  EXPECT_EQ(dbs[21].dd(4), 100007);
  EXPECT_EQ(image.m[31] & 1, 1) << "(-3 < 5) and M30.1 = 0 -> 0, or M30.2 = 1 -> 1";
  image.m[30] = 0;
  cycles(1);
  EXPECT_EQ(image.m[31] & 1, 0);
  EXPECT_EQ(image.m[32], 0xFF);
  EXPECT_EQ(image.mw(34), 0xF0);
  EXPECT_EQ(static_cast<std::uint16_t>(image.mw(36)), 0xF0FF);
  EXPECT_EQ(image.md(44), 0xFFFD);
}

TEST(Awl, ParserErrorsNameTheLine) {
  auto p = parse_awl("L MW 2\nXYZ 5\n");
  ASSERT_FALSE(p);
  EXPECT_NE(p.error().find("line 2"), std::string::npos) << p.error();
  p = parse_awl("L KF 40000\n");
  EXPECT_NE(p.error().find("outside"), std::string::npos) << p.error();
  p = parse_awl("SPA =NOPE\n");
  EXPECT_NE(p.error().find("not defined"), std::string::npos) << p.error();
  p = parse_awl("T KF 1\n");
  EXPECT_FALSE(p);
  p = parse_awl("= E 1.0\n");
  EXPECT_FALSE(p) << "inputs are not written";
  p = parse_awl("L MW 255\n");
  EXPECT_FALSE(p) << "the word would leave the area";
  p = parse_awl("A: L MW 2\nA: BE\n");
  EXPECT_NE(p.error().find("twice"), std::string::npos);
  ASSERT_TRUE(parse_awl("FB 1\nNAME: TEST\nM001: L MW 2 // comment\n:F\nBE\n"));
}

}  // namespace
}  // namespace hil::controllers::amkasyn
