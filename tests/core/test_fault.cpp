// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include "hil/core/config_error.hpp"
#include "hil/core/drive.hpp"
#include "hil/core/fault.hpp"

TEST(Fault, EmptyMeansNoFault) {
  hil::Fault f;
  EXPECT_FALSE(f);
  EXPECT_EQ(f.describe(), "no fault");
}

TEST(Fault, DescribeNamesDomainAndCode) {
  hil::Fault f{hil::MotionFault::following_error, "axis x: 12.5 mm > 10 mm"};
  EXPECT_TRUE(f);
  EXPECT_EQ(f.describe(), "motion:1 axis x: 12.5 mm > 10 mm");
  hil::Fault g{hil::PlantFault::encoder, ""};
  EXPECT_EQ(g.describe(), "plant:1 encoder fault");
}

TEST(ConfigError, NamesFileLineAndKey) {
  hil::ConfigError e{"demo.yaml", 12, 5, "axes[2].drive.node", "expected an integer 1..127, got 'five'"};
  EXPECT_EQ(e.describe(), "demo.yaml:12:5: axes[2].drive.node: expected an integer 1..127, got 'five'");
}

TEST(DriveState, Names) {
  EXPECT_EQ(hil::to_string(hil::DriveState::operation_enabled), "operation_enabled");
  EXPECT_EQ(hil::to_string(hil::DriveRequest::fault_reset), "fault_reset");
}

TEST(Fault, LargeCodesPrintInHexAsTheSpecsWriteThem) {
  hil::Fault f{std::error_code(0x2310, hil::plant_category()), "over-current"};
  EXPECT_EQ(f.describe(), "plant:0x2310 over-current");
  hil::Fault g{std::error_code(0x06020000, hil::plant_category()), "no object"};
  EXPECT_EQ(g.describe(), "plant:0x06020000 no object");
  hil::Fault h{std::error_code(255, hil::plant_category()), "x"};
  EXPECT_EQ(h.describe(), "plant:255 x");
}
