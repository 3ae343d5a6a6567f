// SPDX-License-Identifier: MIT
// The setting-up formulas of 13.3 and 7.2 against the manual's worked figures.
#include <gtest/gtest.h>

#include "hil/controllers/elg/calculator.hpp"

namespace elg = hil::controllers::elg;

TEST(ElgCalculator, ResolutionAndPulsesPerRevolution) {
  EXPECT_DOUBLE_EQ(elg::ms_unit_deg(180000), 0.0005);              // MS = 0.0005 deg
  EXPECT_DOUBLE_EQ(elg::input_unit_deg(180000), 0.001);            // 1 unit = 2 MS
  EXPECT_DOUBLE_EQ(elg::pulses_for_resolution(0.0005), 180000.0);  // 13.3 example: 90 * 2000
  EXPECT_DOUBLE_EQ(elg::resolution_deg(18000.0, 10.0), 0.0005);
}

TEST(ElgCalculator, IncStepOfTheManual) {
  EXPECT_DOUBLE_EQ(elg::inc_step_deg(1000, 0.0005), 1.0);  // 7.2: 1000 increments at MS 0.0005 -> 1 deg
  EXPECT_DOUBLE_EQ(elg::inc_step_deg(1000, 0.005), 10.0);
}

TEST(ElgCalculator, EncoderFrequencyLimit) {
  // n_axis,max = 60 f_max / MD 396*: 500 kHz at 180 000 pulses -> 166.67 rpm.
  EXPECT_NEAR(elg::max_axis_speed_rpm(500e3, 180000), 166.6667, 1e-4);
  EXPECT_NEAR(elg::encoder_frequency_hz(166.6667, 180000), 500e3, 1.0);
}
