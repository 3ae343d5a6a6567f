// SPDX-License-Identifier: MIT
// Punched-tape codec: ISO even parity (digest table), EIA odd parity table, leader skip, block
// limits, even-count check, end conditions, ELG %TEA1/%SEA tapes read and written.
#include <gtest/gtest.h>

#include "hil/serial/tape/elg_tape.hpp"
#include "hil/serial/tape/tape_code.hpp"
#include "hil/serial/tape/tape_reader.hpp"

using namespace hil::serial::tape;

namespace {
std::vector<std::uint8_t> iso(std::string_view s, std::size_t leader = 0) {
  std::vector<std::uint8_t> v(leader, 0x00);
  for (char c : s) v.push_back(make_iso(c));
  return v;
}
}  // namespace

TEST(IsoCode, DigestTableOfEvenParityBytes) {
  // sinumerik-elg.md §7.9
  const std::pair<char, std::uint8_t> table[] = {
      {'\0', 0x00},   {'\x03', 0x03}, {'\n', 0x0A}, {'\r', 0x8D},   {'\x11', 0x11}, {'\x12', 0x12},
      {'\x13', 0x93}, {'\x14', 0x14}, {' ', 0xA0},  {'\x7F', 0xFF}, {'%', 0xA5},    {'(', 0x28},
      {')', 0xA9},    {'+', 0x2B},    {'-', 0x2D},  {'.', 0x2E},    {'/', 0xAF},    {'=', 0xBD},
      {'0', 0x30},    {'1', 0xB1},    {'2', 0xB2},  {'3', 0x33},    {'4', 0xB4},    {'5', 0x35},
      {'6', 0x36},    {'7', 0xB7},    {'8', 0xB8},  {'9', 0x39},    {'A', 0x41},    {'E', 0xC5},
      {'M', 0x4D},    {'N', 0x4E},    {'P', 0x50},  {'R', 0xD2},    {'S', 0x53},    {'T', 0xD4}};
  for (auto [c, b] : table) {
    EXPECT_EQ(make_iso(c), b) << static_cast<int>(c);
    EXPECT_EQ(parse_iso(b), c);
  }
  EXPECT_EQ(iso("%TEA1\n"), (std::vector<std::uint8_t>{0xA5, 0xD4, 0xC5, 0x41, 0xB1, 0x0A}));
  EXPECT_EQ(iso("%SEA\n"), (std::vector<std::uint8_t>{0xA5, 0x53, 0xC5, 0x41, 0x0A}));
  EXPECT_EQ(iso("M02\n"), (std::vector<std::uint8_t>{0x4D, 0x30, 0xB2, 0x0A}));
  EXPECT_EQ(iso("M30\n"), (std::vector<std::uint8_t>{0x4D, 0x33, 0x30, 0x0A}));
  EXPECT_FALSE(parse_iso(0x25));  // '%' without its parity bit
}

TEST(EiaCode, EveryCodeHasOddParityAndRoundTrips) {
  const std::string chars = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ +-./,()%\n";
  for (char c : chars) {
    auto b = make_eia(c);
    ASSERT_TRUE(b) << c;
    if (*b != eia_eob) {
      EXPECT_EQ(__builtin_popcount(*b) % 2, 1) << c;
    }
    const auto d = parse_eia(*b);
    EXPECT_TRUE(d.parity_ok);
    EXPECT_EQ(d.c, c);
  }
  EXPECT_EQ(make_eia('('), 0x1A);  // tracks 2-4-5 (control out)
  EXPECT_EQ(make_eia(')'), 0x4A);  // tracks 2-4-7 (control in)
  EXPECT_EQ(make_eia('\n'), 0x80);
  EXPECT_FALSE(make_eia('='));  // '=' does not exist in EIA
  EXPECT_FALSE(parse_eia(0x03).parity_ok);
  EXPECT_TRUE(parse_eia(0x0D).parity_ok);  // good parity ...
  EXPECT_FALSE(parse_eia(0x0D).c);         // ... but no meaning: alarm 24
}

TEST(TapeReader, SkipsLeaderEndsAtM02AndIgnoresTrailer) {
  auto bytes = iso("garbage before the first percent is leader\n", 0);
  auto body = iso("%TEA1\nN396=180000\nN5002=00100010\nM02\n", 10);
  bytes.insert(bytes.end(), body.begin(), body.end());
  bytes.insert(bytes.end(), 10, 0x00);
  bytes.push_back(make_iso('X'));  // after the end: ignored
  auto r = read_tape(bytes, TapeReaderOptions{});
  ASSERT_FALSE(r.error) << r.error->message;
  EXPECT_TRUE(r.ended);
  EXPECT_EQ(r.code, Code::iso);
  EXPECT_EQ(r.blocks, (std::vector<std::string>{"%TEA1", "N396=180000", "N5002=00100010", "M02"}));
}

TEST(TapeReader, CharacterParityErrorIsAlarm23) {
  auto bytes = iso("%TEA1\nN396=180000\nM02\n");
  bytes[8] ^= 0x80;
  auto r = read_tape(bytes, TapeReaderOptions{});
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->error, TapeError::character_parity);
  EXPECT_EQ(r.error->error.value(), 23);
}

TEST(TapeReader, BlockLongerThan254IsAlarm29) {
  std::string tape = "%TEA1\nN1=" + std::string(255, '1') + "\nM02\n";
  auto r = read_tape(iso(tape), TapeReaderOptions{});
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->error.value(), 29);
  // Exactly 254 characters including LF is fine.
  std::string ok = "%TEA1\nN1=" + std::string(254 - 4, '1') + "\nM02\n";
  EXPECT_FALSE(read_tape(iso(ok), TapeReaderOptions{}).error);
}

TEST(TapeReader, EvenCharacterCountCheckWithHeaderExemptOrNot) {
  TapeReaderOptions o;
  o.even_block_check = true;
  // "%SEA\n" has 5 characters: odd (digest §7.9). Exempt by default.
  auto r = read_tape(iso("%SEA\nN5=10\nM02\n"), o);  // "N5=10\n" = 6, "M02\n" = 4
  EXPECT_FALSE(r.error) << r.error->message;
}

TEST(TapeReader, EvenCountViolationReported) {
  TapeReaderOptions o;
  o.even_block_check = true;
  auto r = read_tape(iso("%TEA1\nN396=18000\nM02\n"), o);  // "N396=18000\n" = 11 characters
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->error.value(), 23);
  o.even_check_header = true;
  auto h = read_tape(iso("%SEA\nN5=10\nM02\n"), o);
  ASSERT_TRUE(h.error);
}

TEST(TapeReader, EndCharacterEtxAllowsMdAndSdInOneTransfer) {
  TapeReaderOptions o;
  o.end_at_m02_m30 = false;
  o.end_character = '\x03';
  auto r = read_tape(iso("%TEA1\nN396=180000\nM02\n%SEA\nN5011=11000010\nM30\n\x03", 3), o);
  ASSERT_FALSE(r.error) << r.error->message;
  EXPECT_TRUE(r.ended);
  auto s = parse_elg_blocks(r.blocks);
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->size(), 2U);
  EXPECT_EQ((*s)[1].kind, ElgSectionKind::setting_data);
  EXPECT_EQ((*s)[1].entries[0], (ElgEntry{5011, "11000010"}));
}

TEST(TapeReader, EiaTapeDetectedOrRejected) {
  std::vector<std::uint8_t> eia{0x00, 0x00, eia_eor, eia_eob};
  for (char c : std::string("N10X100\n")) eia.push_back(*make_eia(c));
  for (char c : std::string("M02\n")) eia.push_back(*make_eia(c));
  auto r = read_tape(eia, TapeReaderOptions{});
  ASSERT_FALSE(r.error) << r.error->message;
  EXPECT_EQ(r.code, Code::eia);
  EXPECT_EQ(r.blocks, (std::vector<std::string>{"%", "N10X100", "M02"}));
  TapeReaderOptions iso_only;
  iso_only.accept_eia = false;
  auto rej = read_tape(eia, iso_only);
  ASSERT_TRUE(rej.error);
  EXPECT_EQ(rej.error->error.value(), 24);
}

TEST(TapeWriter, ElgRoundTripBothBlockEnds) {
  ElgSection md{ElgSectionKind::machine_data, {{396, "180000"}, {11, "-24537"}, {5002, "00100010"}}};
  for (auto end :
       {TapeWriterOptions::BlockEnd::lf, TapeWriterOptions::BlockEnd::cr_lf, TapeWriterOptions::BlockEnd::lf_cr_cr}) {
    TapeWriterOptions w;
    w.block_end = end;
    auto tape = make_tape(make_elg_blocks(md), w);
    ASSERT_TRUE(tape);
    EXPECT_EQ((*tape)[0], 0x00);  // leader
    auto r = read_tape(*tape, TapeReaderOptions{});
    ASSERT_FALSE(r.error) << r.error->message;
    auto s = parse_elg_blocks(r.blocks);
    ASSERT_TRUE(s);
    ASSERT_EQ(s->size(), 1U);
    EXPECT_EQ((*s)[0], md);
  }
  TapeWriterOptions eia;
  eia.code = Code::eia;
  EXPECT_FALSE(make_tape(make_elg_blocks(md), eia)) << "'=' cannot be punched in EIA";
}

TEST(TapeWriter, PadEvenBlocksSatisfiesTheCheck) {
  TapeWriterOptions w;
  w.pad_even_blocks = true;
  auto tape = make_tape({"%TEA1", "N396=18000", "M02"}, w);
  ASSERT_TRUE(tape);
  TapeReaderOptions o;
  o.even_block_check = true;
  o.even_check_header = true;
  auto r = read_tape(*tape, o);
  EXPECT_FALSE(r.error) << r.error->message;
}

TEST(ElgText, ParseAndErrors) {
  auto s = parse_elg_text("; file comment\n%TEA1\nN396=+180000 (resolution)\nM02\n");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ((*s)[0].entries[0], (ElgEntry{396, "180000"}));
  EXPECT_EQ(parse_elg_text(make_elg_text(*s)).value(), *s);
  EXPECT_EQ(parse_elg_text("%TEA1\nN396=1234567890\nM02\n").error().code.value(), 32);  // 10 digits
  EXPECT_EQ(parse_elg_text("%TEA1\nX396=1\nM02\n").error().code.value(), 32);
  EXPECT_EQ(parse_elg_text("%XYZ\nM02\n").error().code.value(), 32);
  EXPECT_FALSE(parse_elg_text("%TEA1\nN1=1\n"));  // no M02
  EXPECT_FALSE(parse_elg_text("N1=1\nM02\n"));    // no header
}
