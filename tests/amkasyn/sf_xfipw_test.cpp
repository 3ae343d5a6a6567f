// SPDX-License-Identifier: MIT
// SF XFIPW (type 9): XY tables, READ VALUE and setting on, working table cycles, retriggering with
// A_Akt, table set switch-over with A_SUK, a signed master offset, and the START checks.
#include <gtest/gtest.h>

#include "sf_fixture.hpp"

namespace hil::controllers::amkasyn {
namespace {

using testing::command;
using testing::Init;
using testing::SfTest;

DataBlock y_table(std::initializer_list<std::int32_t> ys) {
  DataBlock t(8);
  t.set_dw(0, static_cast<int>(ys.size()) + 1);
  std::size_t a = 2;
  for (auto y : ys) t.set_dd(a, y), a += 2;
  return t;
}

DataBlock xy_table(std::initializer_list<std::pair<std::int32_t, std::int32_t>> pts) {
  DataBlock t(8);
  t.set_dw(0, static_cast<int>(pts.size()) + 1).set_dw(1, 1);
  std::size_t i = 1;
  for (auto [x, y] : pts) t.set_dd(4 * i - 2, x).set_dd(4 * i, y), ++i;
  return t;
}

class Xfipw : public SfTest {
 protected:
  DataBlock cmd(int fct, int ba, int m = 1) {
    auto c = command(0, fct, 1, ba);
    c.set_dw(3, 2).set_dw(4, m).set_dd(8, 1).set_dd(10, 20000);
    return c;
  }
  // Moves the 32-bit master (AZ message 1) in steps of 100 up to x; returns MD40.
  std::int32_t at(std::int32_t x) {
    while (image.az[0] < x) {
      image.az[0] += 100;
      cycles(1);
    }
    return image.md(40);
  }
};

TEST_F(Xfipw, XyTableInterpolatesBetweenItsPairs) {
  dbs[16] = xy_table({{0, 0}, {5000, 1000}, {20000, 10000}});
  init_ok(Init(9, 0).source(0, 16).sink(129, 40).tab(0, 16));
  start_ok(cmd(0, 2));
  EXPECT_EQ(at(5000), 1000);
  EXPECT_EQ(at(12500), 5500);
  EXPECT_EQ(at(20000), 10000);
  EXPECT_EQ(at(45000), 20000 + 1000) << "periodic over the last X with cumulative continuation";
}

TEST_F(Xfipw, XyAndYTablesAgree) {
  dbs[16] = xy_table({{0, 0}, {10000, 2500}, {20000, 10000}});
  dbs[17] = y_table({0, 2500, 10000});
  init_ok(Init(9, 0).source(0, 16).sink(129, 40).tab(0, 16));
  init_ok(Init(9, 1).source(0, 16).sink(129, 44).tab(0, 17));
  start_ok(cmd(0, 2));
  auto c1 = cmd(0, 2);
  c1.set_dr(0, 1);
  start_ok(c1);
  for (int x = 0; x < 60000; x += 700) {
    at(x);
    ASSERT_EQ(image.md(40), image.md(44)) << "x = " << x;
  }
}

TEST_F(Xfipw, ReadValueAndSettingOn) {
  dbs[16] = xy_table({{0, 0}, {5000, 1000}, {20000, 10000}});
  init_ok(Init(9, 0).source(0, 16).sink(129, 40).tab(0, 16));
  auto c = cmd(8, 2);
  c.set_dw(12, 12500).set_dr(1, 6);
  auto s = rt.command(c, image);  // READ VALUE in RESET: the table at X = 12500, into DD32
  ASSERT_FALSE(s.error) << s.text;
  EXPECT_EQ(c.dd(32), 5500);
  c.set_dw(12, -5000);  // a lag: one period back, y(15000) - 10000
  ASSERT_FALSE(rt.command(c, image).error);
  EXPECT_EQ(c.dd(32), -3000);
  c.set_dw(12, 12500).set_dr(1, 1);
  image.set_md(40, 777);
  start_ok(c);  // setting on: the output is the table's own position, y(12500) = 5500
  cycles(1);
  EXPECT_EQ(image.md(40), 5500);
  EXPECT_EQ(at(2500), 7000) << "X = 15000";
  c.set_dr(1, 6);
  s = rt.command(c, image);
  EXPECT_EQ(s.code, SfError::xfipw_not_reset);
  EXPECT_EQ(image.m[233], 4);
  auto vn = c;
  ASSERT_FALSE(rt.command(command(0, 0, 0, 0), image).error);
  vn.set_dr(1, 5);
  EXPECT_EQ(rt.command(vn, image).code, SfError::xfipw_not_started);
  // Without setting on the output continues from the sink (X = offset, no jump).
  c.set_dl(0, 0).set_dr(1, 1);
  image.set_md(40, 777);
  start_ok(c);
  cycles(1);
  EXPECT_EQ(image.md(40), 777);
  EXPECT_EQ(at(image.az[0] + 2500), 777 + 1500);
}

TEST_F(Xfipw, FipwHasNoReadValue) {
  dbs[16] = y_table({0, 2500, 10000});
  init_ok(Init(1, 0).source(0, 16).sink(129, 40).tab(0, 16));
  auto c = cmd(0, 2);
  c.set_dr(1, 6);
  const auto s = rt.command(c, image);
  EXPECT_TRUE(s.error);
  EXPECT_NE(s.text.find("only XFIPW"), std::string::npos) << s.text;
}

TEST_F(Xfipw, WorkingTableCyclesAndRetriggering) {
  dbs[16] = y_table({0, 500, 1000});
  init_ok(Init(9, 0).source(0, 16).sink(129, 40).in(1, 8).out(1, 8).tab(0, 16));
  auto c = cmd(0, 26);
  c.set_dd(10, 1000).set_dl(7, 3);  // the working table 3 times per start
  start_ok(c);
  cycles(1);
  EXPECT_EQ(image.a[8] & 1, 1) << "A_Akt = 1: no movement";
  image.e[8] = 1;
  cycles(1);  // the edge at master 0: X = 0
  EXPECT_EQ(at(100), 100);
  EXPECT_EQ(image.a[8] & 1, 0);
  EXPECT_EQ(at(3000), 3000);
  EXPECT_EQ(at(5000), 3000) << "stopped after 3 runs";
  EXPECT_EQ(image.a[8] & 1, 1);
  // Without fct bit4 an edge during the movement is ignored.
  image.e[8] = 0;
  cycles(1);
  image.e[8] = 1;
  cycles(1);  // the edge at master 5000
  EXPECT_EQ(at(5500), 3500);
  image.e[8] = 0;
  cycles(1);
  image.e[8] = 1;
  cycles(1);
  EXPECT_EQ(at(10000), 6000);
  ASSERT_FALSE(rt.command(command(0, 0, 0, 0), image).error);
  // With fct bit4 it is stored: the next movement starts at the end of this one (E1 still 1).
  start_ok(cmd(16, 26).set_dd(10, 1000));
  const std::int32_t y0 = image.md(40);
  image.e[8] = 0;
  cycles(1);
  image.e[8] = 1;
  cycles(1);  // the edge at master 10000
  at(10500);
  image.e[8] = 0;
  cycles(1);
  image.e[8] = 1;
  cycles(1);  // an edge during the movement: stored
  EXPECT_EQ(at(11500) - y0, 1500) << "the second run follows the first seamlessly";
  EXPECT_EQ(image.a[8] & 1, 0) << "A_Akt stays 0";
  EXPECT_EQ(at(13000) - y0, 2000);
  EXPECT_EQ(image.a[8] & 1, 1);
}

TEST_F(Xfipw, TableSetSwitchOverInTheCyclicMode) {
  dbs[16] = y_table({0, 5000, 10000});  // set 0
  dbs[17] = y_table({0, 0, 20000});     // set 1
  init_ok(Init(9, 0).source(0, 16).sink(129, 40).in(1, 8).out(1, 8).tab(0, 16).tab(1, 17));
  start_ok(cmd(0, 3));  // BA 2 + 1: E1 = E_SUEn, E2 = E_SU0, A1 = A_SUK
  EXPECT_EQ(at(10000), 5000);
  EXPECT_EQ(image.a[8] & 1, 0);
  image.e[8] = 0b11;  // enable, select set 1: switched at the next zero passage
  EXPECT_EQ(at(15000), 7500);
  EXPECT_EQ(image.a[8] & 1, 0);
  EXPECT_EQ(at(20100), 10000);
  EXPECT_EQ(image.a[8] & 1, 1) << "switch done";
  EXPECT_EQ(at(30000), 10000);
  EXPECT_EQ(at(40000), 30000);
  image.e[8] = 0b10;  // enable off: no switch, A_SUK = 0
  EXPECT_EQ(at(40100), 30000);
  EXPECT_EQ(image.a[8] & 1, 0);
  EXPECT_EQ(at(60000), 50000) << "still set 1";
}

// XFIPW printing mark control in BA 2: A1 = A_Dmr (a valid mark in the last working-table period);
// SK = LK = 0: the window [3/4, 7/8] x Xme of the same period when the mark comes before it;
// VALUE NEW takes over the weighting (32: F = 0, dXM still shown).
TEST_F(Xfipw, PrintingMarkWithADmrAndValueNew) {
  dbs[16] = y_table({0, 10000, 20000});
  init_ok(Init(9, 0).source(0, 16).sink(129, 40).out(1, 8).tab(0, 16));
  auto c = cmd(1, 2);
  c.set_dw(18, 3000).set_dd(20, 1000).set_dw(26, 60);  // the mark expected at 13333
  start_ok(c);
  at(13400);
  image.az[0] += 100;
  image.az_zero[0].pulse(13433);  // 100 late
  cycles(1);
  EXPECT_EQ(image.md(60), 100);
  EXPECT_EQ(at(15000), 15000);
  EXPECT_EQ(at(16300), 16300 + 52);
  EXPECT_EQ(at(17500), 17600);
  EXPECT_EQ(image.a[8] & 1, 0) << "A_Dmr at the end of the working table";
  EXPECT_EQ(at(20100), 20200);
  EXPECT_EQ(image.a[8] & 1, 1);
  auto vn = c;
  vn.set_dr(1, 5).set_dr(27, 32);  // F = 0
  ASSERT_FALSE(rt.command(vn, image).error);
  at(33400);
  image.az[0] += 100;
  image.az_zero[0].pulse(33333 + 200);
  cycles(1);
  EXPECT_EQ(image.md(60), 200) << "this mark 200 late";
  EXPECT_EQ(at(40100), 40200) << "no correction with F = 0";
  EXPECT_EQ(image.a[8] & 1, 1);
  EXPECT_EQ(at(60100), 60200);
  EXPECT_EQ(image.a[8] & 1, 0) << "no mark in the last period";
  EXPECT_EQ(image.md(60), 0);
}

TEST_F(Xfipw, StartChecks) {
  dbs[16] = y_table({0, 100, 200});
  dbs[17] = y_table({0, 100, 200});
  dbs[18] = y_table({0, 100, 200});
  init_ok(Init(9, 0).source(0, 16).sink(129, 40).in(1, 8).tab(0, 16).tab(1, 17).tab(2, 18));
  auto s = rt.command(cmd(0, 83, 2), image);
  EXPECT_NE(s.text.find("multiple of the total table number"), std::string::npos) << s.text;
  s = rt.command(cmd(1, 2), image);
  EXPECT_NE(s.text.find("printing mark"), std::string::npos) << s.text;
  auto c = cmd(0, 2);
  c.set_dw(12, -20000);
  EXPECT_NE(rt.command(c, image).text.find("DW12 master offset angle = -20000"), std::string::npos);
  dbs[16] = xy_table({{0, 0}, {5000, 100}, {5000, 200}});
  s = rt.command(cmd(0, 2), image);
  EXPECT_NE(s.text.find("increase strictly"), std::string::npos) << s.text;
  dbs[16] = xy_table({{0, 0}, {40, 100}});
  s = rt.command(cmd(0, 2), image);
  EXPECT_NE(s.text.find("50 <= Xme"), std::string::npos) << s.text;
  DataBlock big(4100);  // 2000 points: XFIPW only
  big.set_dw(0, 2001);
  dbs[16] = big;
  start_ok(cmd(0, 2));
  init_ok(Init(1, 1).source(0, 16).sink(129, 44).tab(0, 16));
  auto f = cmd(0, 2);
  f.set_dr(0, 1);
  s = rt.command(f, image);
  EXPECT_NE(s.text.find("3..128"), std::string::npos) << s.text;
}

}  // namespace
}  // namespace hil::controllers::amkasyn
