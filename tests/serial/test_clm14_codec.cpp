// SPDX-License-Identifier: MIT
// CLM1.4 telegram codec: checksum golden vectors (every example of the manual/digest), station
// characters, make/parse round trips, the status-01 error telegram and the line splitter.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "hil/serial/clm14/serial_error.hpp"
#include "hil/serial/clm14/telegram.hpp"

using namespace hil::serial::clm14;

TEST(Clm14Checksum, ManualExampleFig912) {
  // Sum 0x636 -> 06 + 36 = 3C -> two's complement C4.
  EXPECT_EQ(checksum("# N0000 POI 1    +123456.789 123 "), 0xC4);
}

TEST(Clm14Checksum, EveryGoldenVector) {
  std::ifstream in("tests/serial/data/clm14_checksums.txt");
  ASSERT_TRUE(in) << "run from the source root (ctest sets WORKING_DIRECTORY)";
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line.starts_with("//")) continue;
    const auto bar = line.rfind('|');
    ASSERT_NE(bar, std::string::npos) << line;
    const std::string text = line.substr(0, bar);
    const auto expect = static_cast<std::uint8_t>(std::stoi(line.substr(bar + 1), nullptr, 16));
    EXPECT_EQ(checksum(text), expect) << "'" << text << "'";
    // And the full telegram built by make_telegram carries it and parses back.
    const std::string wire = make_telegram(text[0], text[1], text.substr(2));
    EXPECT_EQ(wire.substr(wire.size() - 5, 3), "$" + line.substr(bar + 1)) << wire;
    auto t = parse_telegram(wire.substr(0, wire.size() - 2), true);
    ASSERT_TRUE(t) << t.error().message;
    EXPECT_EQ(t->body, text.substr(2));
    ++n;
  }
  EXPECT_GE(n, 80);
}

TEST(Clm14Station, Characters) {
  EXPECT_EQ(station_char(0), ' ');
  EXPECT_EQ(station_char(1), '1');
  EXPECT_EQ(station_char(9), '9');
  EXPECT_EQ(station_char(10), 'A');
  EXPECT_EQ(station_char(32), 'W');
  EXPECT_FALSE(station_char(33));
  EXPECT_FALSE(station_char(-1));
  for (int s = 0; s <= 32; ++s) EXPECT_EQ(parse_station(*station_char(s)), s);
  EXPECT_FALSE(parse_station('X'));
  EXPECT_FALSE(parse_station('0'));
}

TEST(Clm14Telegram, Rs485ExampleRoundTrip) {
  // §9.2: request "?AN0000 CR LF" to station 10.
  EXPECT_EQ(make_telegram('?', 'A', "N0000", false), "?AN0000\r\n");
  const std::string with = make_telegram('?', 'A', "N0000");
  auto t = parse_telegram(std::string_view(with).substr(0, with.size() - 2), true);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->lead, '?');
  EXPECT_EQ(t->station, 'A');
  EXPECT_EQ(t->body, "N0000");
}

TEST(Clm14Telegram, ChecksumErrorsAreReported) {
  auto t = parse_telegram("# N0101 AEA Q1.00.3 1 $C1", true);
  ASSERT_FALSE(t);
  EXPECT_EQ(t.error().code, SyntaxError::checksum);
  EXPECT_NE(t.error().message.find("computed $C0"), std::string::npos) << t.error().message;
  auto bad_hex = parse_telegram("# N0101 AEA Q1.00.3 1 $G0", true);
  ASSERT_FALSE(bad_hex);
  EXPECT_EQ(bad_hex.error().code, SyntaxError::checksum);
}

TEST(Clm14Telegram, MissingChecksumDependsOnPolicy) {
  EXPECT_FALSE(parse_telegram("# N0101 AEA Q1.00.3 1 ", true));
  auto t = parse_telegram("# N0101 AEA Q1.00.3 1 ", false);
  ASSERT_TRUE(t);
  EXPECT_FALSE(t->checksum);
  EXPECT_EQ(t->body, "N0101 AEA Q1.00.3 1 ");
}

TEST(Clm14Telegram, FormatErrors) {
  EXPECT_EQ(parse_telegram("Z N0000", false).error().code, SyntaxError::format);
  EXPECT_EQ(parse_telegram("#", false).error().code, SyntaxError::format);
  EXPECT_EQ(parse_telegram(std::string(200, '#'), false).error().code, SyntaxError::format);
  EXPECT_EQ(parse_telegram("# N00\x01"
                           "0",
                           false)
                .error()
                .code,
            SyntaxError::format);
  EXPECT_TRUE(parse_telegram("Y", true)->is_confirmation());
  EXPECT_EQ(make_telegram(Telegram{'Y', ' ', {}, {}}), "Y\r\n");
}

TEST(Clm14ErrorTelegram, Status01BodyHasTwentyCharacterText) {
  const std::string body = make_error_body(4, "RS Checksum Error");
  EXPECT_EQ(body, "01 04 RS Checksum Error    ");
  EXPECT_EQ(body.size(), 6U + 20U + 1U);
  auto r = parse_error_body(body);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->code, 4);
  EXPECT_EQ(r->text, "RS Checksum Error");
  // The digest's plain-text readback "X 01 12 Block # too large".
  auto p = parse_telegram("X 01 12 Block # too large", false);
  ASSERT_TRUE(p);
  auto r12 = parse_error_body(p->body);
  ASSERT_TRUE(r12);
  EXPECT_EQ(r12->code, 12);
  EXPECT_EQ(r12->text, "Block # too large");
  EXPECT_FALSE(parse_error_body("53 00 no error"));
  EXPECT_EQ(std::error_code(SerialError::checksum_error).value(), 4);
}

TEST(Clm14Splitter, SplitsOnLfDropsCrAndReportsOverflow) {
  LineSplitter s;
  std::vector<std::string> lines;
  for (char c : std::string("Y\r\n#5N0123 NOP  $45\r\n\n")) {
    if (s.feed(c) == LineSplitter::Event::line) lines.push_back(s.take_line());
  }
  ASSERT_EQ(lines.size(), 3U);
  EXPECT_EQ(lines[0], "Y");
  EXPECT_EQ(lines[1], "#5N0123 NOP  $45");
  EXPECT_EQ(lines[2], "");
  int overflows = 0;
  int got = 0;
  for (int i = 0; i < 300; ++i) overflows += s.feed('x') == LineSplitter::Event::overflow ? 1 : 0;
  got += s.feed('\n') == LineSplitter::Event::line ? 1 : 0;
  EXPECT_EQ(overflows, 1);
  EXPECT_EQ(got, 0);  // the over-long line is dropped, not delivered
  for (char c : std::string("Y\r\n")) got += s.feed(c) == LineSplitter::Event::line ? 1 : 0;
  EXPECT_EQ(got, 1);
}
