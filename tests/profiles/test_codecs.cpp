// SPDX-License-Identifier: MIT
// Value codecs: public vectors (shared/vectors/wf725-726.md §7.1, ip247.md #19), round trips
// over the whole range, rejection of out-of-range values and invalid BCD digits.
#include <gtest/gtest.h>

#include <random>

#include "hil/profiles/bcd.hpp"
#include "hil/profiles/bit_field.hpp"
#include "hil/profiles/db_integer_text.hpp"
#include "hil/profiles/decimal_text.hpp"
#include "hil/profiles/fixed_point.hpp"
#include "hil/profiles/twos_complement.hpp"

namespace hp = hil::profiles;

namespace {

hp::Decimal dec(std::string_view s) {
  return *hp::parse_decimal(s);
}
hp::DecimalTextFormat fmt(std::string_view s) {
  return *hp::DecimalTextFormat::parse(s);
}

}  // namespace

TEST(Decimal, ParsesAndCompares) {
  EXPECT_EQ(dec("0010.00000"), dec("10"));
  EXPECT_EQ(dec("-24537").units, -24537);
  EXPECT_EQ(dec("1,5"), dec("1.5"));
  EXPECT_EQ(dec("0x1F").units, 31);
  EXPECT_LT(dec("-0.001"), dec("0"));
  EXPECT_EQ(dec("0.2340").to_string(), "0.234");
  EXPECT_TRUE(dec("2.5").is_multiple_of(dec("0.5")));
  EXPECT_FALSE(dec("2.55").is_multiple_of(dec("0.1")));
  EXPECT_FALSE(hp::parse_decimal("1.2.3"));
  EXPECT_FALSE(hp::parse_decimal("12a"));
  EXPECT_FALSE(hp::parse_decimal(""));
  EXPECT_FALSE(hp::parse_decimal("99999999999999999999"));
}

TEST(DecimalText, ClmTemplates) {
  // §2.5 strings of the CLM manual: value → exact field text
  struct V {
    const char* format;
    const char* value;
    const char* text;
  };
  for (const V& v :
       {V{"+6.3", "123456.789", "+123456.789"}, V{"+6.3", "-111111.111", "-111111.111"}, V{"4.5", "10", "0010.00000"},
        V{"5", "3000", "03000"}, V{"2.1", "10", "10.0"}, V{"1.3", "0.234", "0.234"}, V{"+5.3", "0", "+00000.000"},
        V{"+3", "-100", "-100"}, V{"2.2", "1", "01.00"}, V{"6", "10", "000010"}, V{"1.1", "0", "0.0"}}) {
    auto t = hp::make_decimal_text(dec(v.value), fmt(v.format));
    ASSERT_TRUE(t) << v.format << " " << v.value << ": " << t.error().message;
    EXPECT_EQ(*t, v.text);
    auto back = hp::parse_decimal_text(*t, fmt(v.format));
    ASSERT_TRUE(back);
    EXPECT_EQ(*back, dec(v.value));
  }
}

// The CLM1.4 keeps the sign of a zero in a signed field: the manual's Ax25 default is
// "# K A125 -00000.000$7B" (digest clm14.md §2.5), and it must be written back that way.
TEST(DecimalText, SignedZeroKeepsItsSign) {
  auto d = hp::parse_decimal_text("-00000.000", fmt("+5.3"));
  ASSERT_TRUE(d);
  EXPECT_EQ(*d, dec("0")) << "still zero in comparisons";
  EXPECT_EQ(hp::make_decimal_text(*d, fmt("+5.3")).value(), "-00000.000");
  EXPECT_EQ(hp::make_decimal_text(*d, fmt("+6.3")).value(), "-000000.000") << "kept across a rescale";
  EXPECT_EQ(hp::make_decimal_text(*hp::parse_decimal_text("+00000.000", fmt("+5.3")), fmt("+5.3")).value(),
            "+00000.000");
  EXPECT_EQ(hp::make_decimal_text(*hp::parse_decimal("-0"), fmt("+5.3")).value(), "-00000.000");
  EXPECT_EQ(hp::make_decimal_text(*hp::parse_decimal("-0"), fmt("4.1")).value(), "0000.0") << "unsigned: no sign";
}

TEST(DecimalText, RejectsWhatDoesNotFit) {
  using K = hp::CodecError::Kind;
  EXPECT_EQ(hp::make_decimal_text(dec("1234567"), fmt("+6.3")).error().kind, K::out_of_range);
  EXPECT_EQ(hp::make_decimal_text(dec("1.2345"), fmt("+6.3")).error().kind, K::precision);
  EXPECT_EQ(hp::make_decimal_text(dec("-1"), fmt("4.5")).error().kind, K::out_of_range);
  EXPECT_EQ(hp::parse_decimal_text("-0001.00000", fmt("4.5")).error().kind, K::out_of_range);
  EXPECT_EQ(hp::parse_decimal_text("12x4", fmt("5")).error().kind, K::syntax);
  EXPECT_EQ(hp::parse_decimal_text("1.5", fmt("5")).error().kind, K::precision);
  EXPECT_EQ(hp::parse_decimal_text("1.1.1", fmt("4.5")).error().kind, K::syntax);
  EXPECT_EQ(hp::parse_decimal_text("", fmt("4.5")).error().kind, K::syntax);
  EXPECT_EQ(hp::parse_decimal_text("123456", fmt("4.5")).error().kind, K::out_of_range);
  // lenient where the devices are: ',' as decimal point, short integer part, missing '+'
  EXPECT_EQ(*hp::parse_decimal_text("10,5", fmt("4.5")), dec("10.5"));
  EXPECT_EQ(*hp::parse_decimal_text("200", fmt("+6.3")), dec("200"));
  EXPECT_FALSE(hp::DecimalTextFormat::parse("x.3"));
  EXPECT_FALSE(hp::DecimalTextFormat::parse("10.10"));
}

TEST(DecimalText, RoundTripRandom) {
  std::mt19937_64 rng(0x50524f46);
  for (const char* f : {"+6.3", "4.5", "5", "+5.3", "2.2", "1.3"}) {
    const auto df = fmt(f);
    const auto max = df.max_magnitude().units;
    std::uniform_int_distribution<std::int64_t> dist(df.sign == hp::DecimalTextFormat::Sign::always ? -max : 0, max);
    for (int i = 0; i < 2000; ++i) {
      const hp::Decimal d{dist(rng), df.frac_digits};
      auto t = hp::make_decimal_text(d, df);
      ASSERT_TRUE(t);
      EXPECT_EQ(t->size(), df.width());
      EXPECT_EQ(*hp::parse_decimal_text(*t, df), d);
    }
  }
}

// shared/vectors/wf725-726.md §7.1: value → BCD (bit-31 sign) / binary (two's complement)
TEST(Bcd, Wf725Vectors) {
  struct V {
    std::int64_t value;
    std::uint32_t bcd;
    std::uint32_t bin;
  };
  const hp::BcdFormat wf{8, hp::BcdSign::bit31};
  for (const V& v : {V{360000, 0x00360000, 0x00057E40},   V{1200, 0x00001200, 0x000004B0},
                     V{852100, 0x00852100, 0x000D0084},   V{32768, 0x00032768, 0x00008000},
                     V{76, 0x00000076, 0x0000004C},       V{-24537, 0x80024537, 0xFFFFA027},
                     V{-42728, 0x80042728, 0xFFFF5918},   V{96417, 0x00096417, 0x000178A1},
                     V{137428, 0x00137428, 0x000218D4},   V{-824967, 0x80824967, 0xFFF36979},
                     V{-25, 0x80000025, 0xFFFFFFE7},      V{1246, 0x00001246, 0x000004DE},
                     V{31830980, 0x31830980, 0x01E5B3C4}, V{112, 0x00000112, 0x00000070},
                     V{8000, 0x00008000, 0x00001F40},     V{36700, 0x00036700, 0x00008F5C},
                     V{1427366, 0x01427366, 0x0015C7A6},  V{32775, 0x00032775, 0x00008007},
                     V{65538, 0x00065538, 0x00010002},    V{50000, 0x00050000, 0x0000C350},
                     V{25000, 0x00025000, 0x000061A8},    V{0, 0, 0}}) {
    auto b = hp::make_bcd(v.value, wf);
    ASSERT_TRUE(b) << v.value;
    EXPECT_EQ(*b, v.bcd) << v.value;
    EXPECT_EQ(*hp::parse_bcd(v.bcd, wf), v.value);
    auto t = hp::make_twos_complement(v.value, {32, true});
    ASSERT_TRUE(t);
    EXPECT_EQ(*t, v.bin) << v.value;
    EXPECT_EQ(*hp::parse_twos_complement(v.bin, {32, true}), v.value);
  }
}

TEST(Bcd, Wf725LimitIs79999999) {
  const hp::BcdFormat wf{8, hp::BcdSign::bit31};
  EXPECT_EQ(*hp::make_bcd(79999999, wf), 0x79999999u);
  EXPECT_EQ(*hp::make_bcd(-79999999, wf), 0xF9999999u);
  EXPECT_EQ(hp::make_bcd(80000000, wf).error().kind, hp::CodecError::Kind::out_of_range);
  EXPECT_EQ(hp::make_bcd(-80000000, wf).error().kind, hp::CodecError::Kind::out_of_range);
  EXPECT_EQ(*hp::parse_bcd(0xF9999999u, wf), -79999999);
}

TEST(Bcd, RejectsInvalidDigits) {
  const hp::BcdFormat wf{8, hp::BcdSign::bit31};
  for (std::uint32_t w : {0x0000000Au, 0x000B0000u, 0x00F00000u, 0x1234567Fu, 0x8000C000u}) {
    auto r = hp::parse_bcd(w, wf);
    ASSERT_FALSE(r) << std::hex << w;
    EXPECT_EQ(r.error().kind, hp::CodecError::Kind::invalid_digit);
  }
  const hp::BcdFormat plain{8, hp::BcdSign::none};
  EXPECT_EQ(hp::parse_bcd(0xA0000000u, plain).error().kind, hp::CodecError::Kind::invalid_digit);
  EXPECT_EQ(hp::make_bcd(-1, plain).error().kind, hp::CodecError::Kind::out_of_range);
  const hp::BcdFormat four{4, hp::BcdSign::none};
  EXPECT_EQ(*hp::make_bcd(1000, four), 0x1000u);
  EXPECT_EQ(hp::make_bcd(10000, four).error().kind, hp::CodecError::Kind::out_of_range);
  EXPECT_EQ(hp::parse_bcd(0x10000u, four).error().kind, hp::CodecError::Kind::syntax);
}

// shared/vectors/ip247.md #19: +120000 → BCD 00120000h, −120000 → F0120000h (AG values, sign nibble)
TEST(Bcd, Ip247SignNibble) {
  const hp::BcdFormat ag{8, hp::BcdSign::nibble};
  EXPECT_EQ(*hp::make_bcd(120000, ag), 0x00120000u);
  EXPECT_EQ(*hp::make_bcd(-120000, ag), 0xF0120000u);
  EXPECT_EQ(*hp::parse_bcd(0xF0120000u, ag), -120000);
  EXPECT_EQ(*hp::make_bcd(9999999, ag), 0x09999999u);
  EXPECT_EQ(hp::make_bcd(10000000, ag).error().kind, hp::CodecError::Kind::out_of_range);
  EXPECT_EQ(hp::parse_bcd(0x80120000u, ag).error().kind, hp::CodecError::Kind::invalid_digit);
  // the binary forms of the same vector
  EXPECT_EQ(*hp::make_twos_complement(120000, {32, true}), 0x0001D4C0u);
  EXPECT_EQ(*hp::make_twos_complement(-120000, {32, true}), 0xFFFE2B40u);
}

TEST(Bcd, RoundTripRandom) {
  std::mt19937_64 rng(0x424344);
  for (auto sign : {hp::BcdSign::none, hp::BcdSign::bit31, hp::BcdSign::nibble}) {
    const hp::BcdFormat f{8, sign};
    const auto max = hp::bcd_max_magnitude(f);
    std::uniform_int_distribution<std::int64_t> dist(sign == hp::BcdSign::none ? 0 : -max, max);
    for (int i = 0; i < 5000; ++i) {
      const auto v = dist(rng);
      auto w = hp::make_bcd(v, f);
      ASSERT_TRUE(w) << v;
      EXPECT_EQ(*hp::parse_bcd(*w, f), v);
    }
  }
}

TEST(TwosComplement, LimitsAndWidth) {
  EXPECT_EQ(*hp::make_twos_complement(-1, {16, true}), 0xFFFFu);
  EXPECT_EQ(*hp::make_twos_complement(32767, {16, true}), 0x7FFFu);
  EXPECT_EQ(hp::make_twos_complement(32768, {16, true}).error().kind, hp::CodecError::Kind::out_of_range);
  EXPECT_EQ(hp::make_twos_complement(-32769, {16, true}).error().kind, hp::CodecError::Kind::out_of_range);
  EXPECT_EQ(*hp::make_twos_complement(65535, {16, false}), 0xFFFFu);
  EXPECT_EQ(hp::make_twos_complement(-1, {16, false}).error().kind, hp::CodecError::Kind::out_of_range);
  EXPECT_EQ(*hp::parse_twos_complement(0x8000, {16, true}), -32768);
  EXPECT_EQ(hp::parse_twos_complement(0x10000, {16, true}).error().kind, hp::CodecError::Kind::syntax);
  EXPECT_EQ(*hp::make_twos_complement(INT32_MIN, {32, true}), 0x80000000u);
  EXPECT_EQ(hp::make_twos_complement(std::int64_t{1} << 31, {32, true}).error().kind,
            hp::CodecError::Kind::out_of_range);
  std::mt19937_64 rng(7);
  for (int bits : {8, 16, 32}) {
    std::uniform_int_distribution<std::int64_t> d(-(std::int64_t{1} << (bits - 1)),
                                                  (std::int64_t{1} << (bits - 1)) - 1);
    for (int i = 0; i < 3000; ++i) {
      const auto v = d(rng);
      EXPECT_EQ(*hp::parse_twos_complement(*hp::make_twos_complement(v, {bits, true}), {bits, true}), v);
    }
  }
}

// WF 725/726 MD 41 check mask: K = 1, S = 2, U = 4, J = 65536, N = 131072; S + J = 65538
TEST(BitField, Wf725CheckMask) {
  hp::BitFieldFormat f{
      32, {{"K", 0, 1, ""}, {"S", 1, 1, ""}, {"U", 2, 1, ""}, {"J", 16, 1, ""}, {"N", 17, 1, ""}}, false};
  auto names = hp::parse_bit_field_text("S|J", f);
  ASSERT_TRUE(names);
  EXPECT_EQ(*hp::make_bit_field(*names, f), 65538u);
  auto back = hp::parse_bit_field(65538, f);
  ASSERT_TRUE(back);
  EXPECT_EQ(hp::bit_field_text(*back, f), "S|J");
  EXPECT_EQ(hp::parse_bit_field(8, f).error().kind, hp::CodecError::Kind::out_of_range);  // bit 3 undefined
  EXPECT_FALSE(hp::parse_bit_field_text("X", f));
  EXPECT_EQ(hp::bit_field_text(*hp::parse_bit_field(0, f), f), "0");
}

// SINUMERIK MD 5002: bits 6-4 input system unit, bits 2-0 measuring system unit; 22H released
TEST(BitField, Groups) {
  hp::BitFieldFormat f{8, {{"measuring_unit", 0, 3, ""}, {"input_unit", 4, 3, ""}}, false};
  auto w = hp::make_bit_field({{"measuring_unit", 2}, {"input_unit", 2}}, f);
  ASSERT_TRUE(w);
  EXPECT_EQ(*w, 0x22u);
  EXPECT_EQ(hp::make_bit_field({{"input_unit", 8}}, f).error().kind, hp::CodecError::Kind::out_of_range);
  EXPECT_EQ(hp::parse_bit_field(0x100, f).error().kind, hp::CodecError::Kind::out_of_range);
  EXPECT_EQ(hp::bit_field_text(*hp::parse_bit_field(0x22, f), f), "measuring_unit=2|input_unit=2");
}

// AMKASYN REGL: Kp 512 = 2.0, Ki 128 = 0.5, Kd 64 = 0.25 (lsb 1/256); ratios 10000 = 1.0
TEST(FixedPoint, AmkasynFormats) {
  auto q8 = *hp::FixedPointFormat::parse_lsb("1/256", {16, true});
  EXPECT_EQ(*hp::make_fixed_point(dec("2"), q8), 512);
  EXPECT_EQ(*hp::make_fixed_point(dec("0.5"), q8), 128);
  EXPECT_EQ(*hp::parse_fixed_point(64, q8), dec("0.25"));
  EXPECT_EQ(*hp::parse_fixed_point(1, q8), dec("0.00390625"));
  EXPECT_EQ(hp::make_fixed_point(dec("128"), q8).error().kind, hp::CodecError::Kind::out_of_range);
  auto ratio = *hp::FixedPointFormat::parse_lsb("0.0001", {16, true});
  EXPECT_EQ(*hp::make_fixed_point(dec("-1"), ratio), -10000);
  EXPECT_EQ(*hp::parse_fixed_point(20000, ratio), dec("2"));
  // rounding half away from zero
  EXPECT_EQ(*hp::make_fixed_point(dec("0.3"), q8), 77);
  EXPECT_EQ(*hp::make_fixed_point(dec("-0.3"), q8), -77);
  EXPECT_FALSE(hp::FixedPointFormat::parse_lsb("0", {16, true}));
  EXPECT_FALSE(hp::FixedPointFormat::parse_lsb("1/x", {16, true}));
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<std::int64_t> d(-32768, 32767);
  for (int i = 0; i < 3000; ++i) {
    const auto raw = d(rng);
    EXPECT_EQ(*hp::make_fixed_point(*hp::parse_fixed_point(raw, q8), q8), raw);
  }
}

TEST(DbIntegerText, DecimalAndBothHexSpellings) {
  using hil::profiles::parse_db_integer;
  EXPECT_EQ(parse_db_integer("120"), 120);
  EXPECT_EQ(parse_db_integer("+120"), 120);
  EXPECT_EQ(parse_db_integer("-32768"), -32768);
  EXPECT_EQ(parse_db_integer("0x1F"), 31);
  EXPECT_EQ(parse_db_integer("0X1f"), 31);
  EXPECT_EQ(parse_db_integer("1Fh"), 31);
  EXPECT_EQ(parse_db_integer("-0x10"), -16);
  EXPECT_EQ(parse_db_integer("FFFFFFFFh"), 0xFFFFFFFFLL);
}

TEST(DbIntegerText, RefusesEverythingElse) {
  using hil::profiles::parse_db_integer;
  for (const char* bad : {"", "+", "-", "h", "0x", "--5", "+-5", "0x-5", "1F", "12a", " 12", "12 ", "1.5",
                          "99999999999999999999", "0x10000000000000000"})
    EXPECT_FALSE(parse_db_integer(bad).has_value()) << "'" << bad << "'";
}
