// SPDX-License-Identifier: MIT
// The SF scheduler and commanding state machine: FB 207 checks, START / VALUE NEW / RESET rules
// with their error numbers in MB 232/233, slot order with SF links (a producer's sink read by a
// higher SF in the same cycle), cycle factors, DCOPY absolute/incremental, DIGDREH, and a START
// that fails on its tables leaving the SF in RESET with an error naming the type.
#include <gtest/gtest.h>

#include "sf_fixture.hpp"

namespace hil::controllers::amkasyn {
namespace {

using testing::command;
using testing::Init;
using testing::SfTest;

TEST_F(SfTest, InitDbChecks) {
  EXPECT_TRUE(rt.init(Init(13, 0).db, image).error);
  EXPECT_TRUE(rt.init(Init(0, 16).db, image).error);
  EXPECT_TRUE(rt.init(Init(0, 0).source(1, 4).db, image).error) << "offset 4 is a sink, not a source";
  EXPECT_TRUE(rt.init(Init(0, 0).sink(1, 5).db, image).error) << "offset 5 is a source, not a sink";
  EXPECT_TRUE(rt.init(Init(0, 0).in(3, 8).db, image).error) << "two bits in the input mask";
  const auto s = rt.init(Init(0, 2).source(255, 5).db, image);
  EXPECT_TRUE(s.error) << "SF link from a higher SF number";
  EXPECT_NE(s.text.find("smaller SF number"), std::string::npos) << s.text;
  EXPECT_EQ(image.m[232] & 1, 1);
  EXPECT_FALSE(rt.init(Init(0, 0).source(129, 40).sink(129, 44).db, image).error);
  EXPECT_EQ(image.m[232] & 1, 0);
}

TEST_F(SfTest, CommandStateMachineAndErrorNumbers) {
  init_ok(Init(0, 1).source(129, 40).sink(129, 44));
  auto vn = command(1, 1, 5, 0);
  auto s = rt.command(vn, image);
  EXPECT_EQ(s.code, SfError::value_new_not_active);
  EXPECT_EQ(image.m[233], 3);
  start_ok(command(1, 1, 1, 0));
  EXPECT_EQ(rt.state(1), SfState::active);
  s = rt.command(command(1, 1, 1, 0), image);
  EXPECT_EQ(s.code, SfError::start_while_active);
  EXPECT_EQ(image.m[233], 2);
  s = rt.command(command(1, 1, 5, 0), image);
  EXPECT_EQ(s.code, SfError::value_new_not_active) << "DCOPY has no VALUE NEW";
  EXPECT_FALSE(rt.command(command(1, 1, 0, 0), image).error);
  EXPECT_EQ(rt.state(1), SfState::reset);
  s = rt.command(command(1, 1, 7, 0), image);
  EXPECT_TRUE(s.error);
  s = rt.command(command(4, 1, 1, 0), image);
  EXPECT_TRUE(s.error) << "slot 4 not initialised";
}

TEST_F(SfTest, StartWithoutTablesIsRefused) {
  init_ok(Init(1, 0).source(0, 16).sink(1, 4));
  const auto s = rt.command(command(0, 0, 1, 2), image);
  EXPECT_TRUE(s.error);
  EXPECT_EQ(s.code, SfError::start_invalid);
  EXPECT_NE(s.text.find("FIPW"), std::string::npos) << s.text;
  EXPECT_EQ(rt.state(0), SfState::reset);
}

TEST_F(SfTest, SlotOrderLinksAndCycleFactor) {
  // SF0 DCOPY MD40 -> internal sink; SF1 DCOPY link(SF0) -> MD44 sees SF0's value of the same
  // cycle; SF2 (factor 2) DCOPY MD40 -> MD48 runs every second cycle.
  init_ok(Init(0, 0).source(129, 40).sink(255, 0));
  init_ok(Init(0, 1).source(255, 0).sink(129, 44));
  init_ok(Init(0, 2).factor(2).source(129, 40).sink(129, 48));
  for (int n = 0; n < 3; ++n) start_ok(command(n, 1, 1, 0));
  image.set_md(40, 111);
  cycles(1);
  EXPECT_EQ(image.md(44), 111);
  EXPECT_EQ(image.md(48), 111);
  image.set_md(40, 222);
  cycles(1);
  EXPECT_EQ(image.md(44), 222) << "the link is read in the same cycle";
  EXPECT_EQ(image.md(48), 111) << "factor 2: not this cycle";
  cycles(1);
  EXPECT_EQ(image.md(48), 222);
}

TEST_F(SfTest, SnapshotIsTakenOncePerCycle) {
  // SF0 writes MD44 from MD40; SF1 reads MD44 as its source: it sees the cycle's snapshot
  // (last cycle's MD44), not SF0's write of this cycle (only SF links are live).
  init_ok(Init(0, 0).source(129, 40).sink(129, 44));
  init_ok(Init(0, 1).source(129, 44).sink(129, 48));
  start_ok(command(0, 1, 1, 0));
  start_ok(command(1, 1, 1, 0));
  image.set_md(40, 5);
  cycles(1);
  EXPECT_EQ(image.md(48), 0);
  cycles(1);
  EXPECT_EQ(image.md(48), 5);
}

TEST_F(SfTest, DcopyIncrementalSumsLowWordDeltasFromTheSinkAtStart) {
  init_ok(Init(0, 0).source(2, 5).sink(129, 60));
  image.set_md(60, 1000000);
  image.aw[1].position_feedback = 65530;
  start_ok(command(0, 1, 1, 1));
  image.aw[1].position_feedback = 65540;  // low word wraps: +10
  cycles(1);
  EXPECT_EQ(image.md(60), 1000010);
  image.aw[1].position_feedback = 65500;
  cycles(1);
  EXPECT_EQ(image.md(60), 999970);
}

TEST_F(SfTest, DigdrehSwitchesSpeed) {
  init_ok(Init(3, 0).sink(1, 16).in(1, 10).out(1, 10));
  auto c = command(0, 2, 1, 0);
  c.set_dd(2, 100000);  // 10 rpm
  start_ok(c);
  cycles(1);
  EXPECT_EQ(image.aw[0].swq2, 0);
  EXPECT_EQ(image.a[10] & 1, 1);
  image.e[10] = 0b011;  // enable + start edge
  cycles(1);
  EXPECT_EQ(image.aw[0].swq2, 100000);
  EXPECT_EQ(image.a[10] & 1, 0);
  image.e[10] = 0b101;  // stop
  cycles(1);
  EXPECT_EQ(image.aw[0].swq2, 0);
  image.e[10] = 0b001;
  cycles(1);
  EXPECT_EQ(image.aw[0].swq2, 0) << "restart needs a new E2 edge";
}

TEST_F(SfTest, OutputBytesOwnedBySfsAreReported) {
  init_ok(Init(0, 0).mode(2).source(129, 40).sink(129, 44).out(4, 20));
  EXPECT_TRUE(rt.owns_output_byte(20, true));
  EXPECT_FALSE(rt.owns_output_byte(20, false));
}

}  // namespace
}  // namespace hil::controllers::amkasyn
