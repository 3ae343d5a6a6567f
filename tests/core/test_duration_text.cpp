// SPDX-License-Identifier: MIT
// The one duration grammar of scenario files and the CLI (hil/core/duration_text.hpp).
#include <gtest/gtest.h>

#include "hil/core/duration_text.hpp"

using namespace std::chrono_literals;
using hil::is_bare_number;
using hil::parse_duration_text;

TEST(DurationText, UnitsAsScenarioFilesWriteThem) {
  EXPECT_EQ(parse_duration_text("250ms"), 250ms);
  EXPECT_EQ(parse_duration_text("2s"), 2s);
  EXPECT_EQ(parse_duration_text(" 2 s "), 2s);
  EXPECT_EQ(parse_duration_text("30us"), 30us);
  EXPECT_EQ(parse_duration_text("1min"), 60s);
  EXPECT_EQ(parse_duration_text("1.5s"), 1500ms);
  EXPECT_EQ(parse_duration_text("0.1ms"), 100us);
  EXPECT_EQ(parse_duration_text("100us"), 100000ns);  // rounded, not 99999ns
  EXPECT_EQ(parse_duration_text("0s"), 0ns);
  EXPECT_EQ(parse_duration_text("200ns"), 200ns);
  EXPECT_EQ(parse_duration_text("5000 ns"), 5us);
  EXPECT_EQ(parse_duration_text("0.2us"), 200ns);
}

TEST(DurationText, BareNumberIsReadInTheGivenUnit) {
  EXPECT_EQ(parse_duration_text("1.5"), 1500ms);  // scenario files: seconds
  EXPECT_EQ(parse_duration_text("500", "ms"), 500ms);
  EXPECT_EQ(parse_duration_text("30", "us"), 30us);
  EXPECT_EQ(parse_duration_text("200", "ns"), 200ns);
  EXPECT_EQ(parse_duration_text("2s", "ms"), 2s);  // a unit always wins over the bare unit
  // Ten days is the limit in the bare unit too: 1e6 ms is fine, 1e6 s is not.
  EXPECT_EQ(parse_duration_text("1000000", "ms"), 1000s);
  EXPECT_FALSE(parse_duration_text("1000000", "s"));
}

TEST(DurationText, RefusesWhatIsNotADuration) {
  for (const char* bad : {"", "ms", "fast", "-1", "-1ms", "1h", "1 m", "1e300", "inf", "nan", "1ms2", "0x10ms"})
    EXPECT_FALSE(parse_duration_text(bad)) << bad;
  EXPECT_FALSE(parse_duration_text("5", "parsecs"));
}

TEST(DurationText, BareNumber) {
  EXPECT_TRUE(is_bare_number("500"));
  EXPECT_TRUE(is_bare_number(" 0.5 "));
  EXPECT_FALSE(is_bare_number("500ms"));
  EXPECT_FALSE(is_bare_number("fast"));
  EXPECT_FALSE(is_bare_number(""));
}
