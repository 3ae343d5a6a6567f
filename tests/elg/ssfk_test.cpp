// SPDX-License-Identifier: MIT
// SSFK, the compensation table of C (MD 6000-6249, MD 316*-328*, MD 5016 bits 1-2; ssfk.hpp): the
// point coding, the pointers, direction dependence and the revolution.
#include <gtest/gtest.h>

#include "hil/controllers/elg/ssfk.hpp"

namespace elg = hil::controllers::elg;

namespace {
elg::SsfkData table() {
  elg::SsfkData d;
  d.active = true;
  d.distance = 100;
  d.step = 5;
  d.revolution = 1000;
  // Byte 6000 = points 4, 3, 2, 1 in bit pairs 7/6, 5/4, 3/2, 1/0 (sign, no):
  // point 1 "+ yes" (10), point 2 "no" (11), point 3 "- yes" (00), point 4 "+ yes" (10).
  d.flags[0] = 0b10'00'11'10;
  d.flags[1] = 0b10'10'10'00;  // points 5 "-", 6..8 "+"
  return d;
}
}  // namespace

TEST(ElgSsfk, PointsAreSignAndNoBitPairsFourToAByte) {
  const elg::Ssfk s(table());
  EXPECT_EQ(s.point(1), 1);
  EXPECT_EQ(s.point(2), 0);
  EXPECT_EQ(s.point(3), -1);
  EXPECT_EQ(s.point(4), 1);
  EXPECT_EQ(s.point(5), -1);
  EXPECT_EQ(s.point(9), 0);  // the default 01: "no"
  EXPECT_EQ(s.point(1001), 0);
}

TEST(ElgSsfk, CompensationSumsThePointsPassedTimesMd328) {
  const elg::Ssfk s(table());
  EXPECT_EQ(s.compensation(0, 1), 0);
  EXPECT_EQ(s.compensation(99, 1), 0);
  EXPECT_EQ(s.compensation(100, 1), 5);   // point 1 passed
  EXPECT_EQ(s.compensation(250, 1), 5);   // + point 2 ("no")
  EXPECT_EQ(s.compensation(300, 1), 0);   // + point 3 (-)
  EXPECT_EQ(s.compensation(400, 1), 5);   // + point 4
  EXPECT_EQ(s.compensation(500, 1), 0);   // + point 5 (-)
  EXPECT_EQ(s.compensation(800, 1), 15);  // + points 6..8
  EXPECT_EQ(s.compensation(1100, 1), 5);  // modulo one revolution of C
  EXPECT_EQ(s.compensation(-900, 1), 5);
}

TEST(ElgSsfk, PointersAndDirectionDependence) {
  auto d = table();
  d.pointer_plus = 3;  // the + table starts at point 3
  elg::Ssfk from3(d);
  EXPECT_EQ(from3.compensation(100, 1), -5);
  EXPECT_EQ(from3.compensation(100, -1), -5);  // not direction dependent: the + table both ways
  d.pointer_plus = 6001;                       // an MD byte: its first point, 5
  EXPECT_EQ(elg::Ssfk(d).compensation(100, 1), -5);
  EXPECT_EQ(elg::Ssfk(d).compensation(200, 1), 0);
  d.direction_dependent = true;
  d.pointer_minus = 1;
  const elg::Ssfk both(d);
  EXPECT_EQ(both.compensation(100, 1), -5);
  EXPECT_EQ(both.compensation(100, -1), 5);
  d.pointer_plus = 2000;  // neither a point nor an MD byte: no table for +
  EXPECT_EQ(elg::Ssfk(d).compensation(500, 1), 0);
}

TEST(ElgSsfk, OffWithoutMd5016Bit1OrADistance) {
  auto d = table();
  d.active = false;
  EXPECT_EQ(elg::Ssfk(d).compensation(400, 1), 0);
  d.active = true;
  d.distance = 0;
  EXPECT_FALSE(elg::Ssfk(d).active());
  EXPECT_EQ(elg::Ssfk(d).compensation(400, 1), 0);
}
