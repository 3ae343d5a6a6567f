// SPDX-License-Identifier: MIT
// The device address codecs: CLM1.4 Ix.yy.z / Qx.yy.z / Mx.yy.z and S5 E/A/M/EB/D/DL/DR,
// table-driven both ways, with the errors for malformed text.
#include <gtest/gtest.h>

#include <array>

#include "hil/controllers/io_address_clm.hpp"
#include "hil/controllers/io_address_s5.hpp"

namespace hil::controllers {
namespace {

struct ClmCase {
  const char* text;
  ClmAddress address;
  BitAddress bit;
};

TEST(ClmAddress, ParsesFormatsAndMapsOntoTheImage) {
  const std::array cases{
      ClmCase{"I0.00.1", {'I', 0, 0, 1}, {IoArea::input, 0, 1}},      // Automatic/Manual
      ClmCase{"I0.00.7", {'I', 0, 0, 7}, {IoArea::input, 0, 7}},      // External Clear
      ClmCase{"I1.10.7", {'I', 1, 10, 7}, {IoArea::input, 74, 7}},    // last user input X22/16
      ClmCase{"Q1.00.3", {'Q', 1, 0, 3}, {IoArea::output, 64, 3}},    // AEA Q1.00.3 (§9.2 example)
      ClmCase{"Q2.01.7", {'Q', 2, 1, 7}, {IoArea::output, 129, 7}},   // fieldbus image
      ClmCase{"M2.03.4", {'M', 2, 3, 4}, {IoArea::marker, 131, 4}},   // NC marker
      ClmCase{"M6.39.0", {'M', 6, 39, 0}, {IoArea::marker, 423, 0}},  // last LT marker
  };
  for (const auto& c : cases) {
    const auto a = parse_clm_address(c.text);
    ASSERT_TRUE(a) << c.text << ": " << a.error();
    EXPECT_EQ(*a, c.address) << c.text;
    EXPECT_EQ(format_clm_address(*a), c.text);
    EXPECT_EQ(to_bit_address(*a), c.bit) << c.text;
    EXPECT_EQ(to_clm_address(c.bit), c.address) << c.text;
  }
  EXPECT_EQ(parse_clm_address("q1.02.7")->type, 'Q') << "lower case letter accepted";
}

TEST(ClmAddress, RejectsMalformedText) {
  for (const char* bad : {"", "X0.00.1", "I0.0.1", "I0.00.8", "I0.64.0", "I0.00", "IA.00.1", "I0-00-1", "I0.00.1 "}) {
    const auto a = parse_clm_address(bad);
    EXPECT_FALSE(a) << bad;
    if (!a) {
      EXPECT_NE(a.error().find("CLM address"), std::string::npos) << a.error();
    }
  }
  EXPECT_NE(parse_clm_address("I0.0.1").error().find("two digits"), std::string::npos);
  EXPECT_TRUE(is_clm_unused("00.00.0"));
  EXPECT_FALSE(is_clm_unused("I0.00.0"));
  EXPECT_FALSE(parse_clm_address("00.00.0"));
  EXPECT_FALSE(to_clm_address(BitAddress{IoArea::data, 0, 0}));
  EXPECT_FALSE(to_clm_address(BitAddress{IoArea::input, 10 * clm_group_stride, 0}));
}

TEST(ClmAddress, LayoutHoldsTheGroups) {
  const auto l = clm_io_layout(3, 3, 7);
  EXPECT_EQ(l.size(IoArea::input), 192U);
  EXPECT_EQ(l.size(IoArea::marker), 448U);
  IoImage io(l);
  EXPECT_TRUE(io.contains(to_bit_address(*parse_clm_address("M6.39.7"))));
  EXPECT_FALSE(io.contains(to_bit_address(*parse_clm_address("M7.00.0"))));
}

struct S5Case {
  const char* text;
  S5Address address;
  const char* formatted;
};

TEST(S5Address, ParsesAndFormats) {
  const std::array cases{
      S5Case{"E 4.1", {S5Operand::input_bit, 0, 4, 1}, "E 4.1"},
      S5Case{"e5.0", {S5Operand::input_bit, 0, 5, 0}, "E 5.0"},  // IP247 STAR (DW3 example)
      S5Case{"A 5.0", {S5Operand::output_bit, 0, 5, 0}, "A 5.0"},
      S5Case{"M 10.3", {S5Operand::marker_bit, 0, 10, 3}, "M 10.3"},
      S5Case{"MB 251", {S5Operand::marker_byte, 0, 251, 0}, "MB 251"},  // IP247 module error byte
      S5Case{"EB 4", {S5Operand::input_byte, 0, 4, 0}, "EB 4"},
      S5Case{"AB 5", {S5Operand::output_byte, 0, 5, 0}, "AB 5"},
      S5Case{"DB10 D 2.0", {S5Operand::data_bit, 10, 2, 0}, "DB10 D 2.0"},  // WF drive enable
      S5Case{"db 10.d 3.15", {S5Operand::data_bit, 10, 3, 15}, "DB10 D 3.15"},
      S5Case{"DB10 DL 4", {S5Operand::data_left_byte, 10, 4, 0}, "DB10 DL 4"},
      S5Case{"DB7 DR 12", {S5Operand::data_right_byte, 7, 12, 0}, "DB7 DR 12"},
  };
  for (const auto& c : cases) {
    const auto a = parse_s5_address(c.text);
    ASSERT_TRUE(a) << c.text << ": " << a.error();
    EXPECT_EQ(*a, c.address) << c.text;
    EXPECT_EQ(format_s5_address(*a), c.formatted);
    EXPECT_EQ(parse_s5_address(format_s5_address(*a)), a) << "round trip " << c.text;
  }
  const auto d = parse_s5_address("D 2.0", std::uint16_t{12});
  ASSERT_TRUE(d) << d.error();
  EXPECT_EQ(d->db, 12) << "default DB";
}

TEST(S5Address, RejectsMalformedText) {
  for (const char* bad : {"", "X 1.0", "E 4", "E 4.8", "E 256.0", "D 2.0", "DB0 D 2.0", "DB10 E 4.1", "D 2.16",
                          "MB 10.1", "E 4.1x", "DB300 D 1.0"}) {
    const auto a = parse_s5_address(bad);
    EXPECT_FALSE(a) << bad;
    if (!a) {
      EXPECT_NE(a.error().find("S5 operand"), std::string::npos) << a.error();
    }
  }
  EXPECT_NE(parse_s5_address("D 2.0").error().find("without DB"), std::string::npos);
}

TEST(S5Address, MapsOntoTheImageWithBigEndianWords) {
  const std::array blocks{S5DataBlock{10, 0, 32}, S5DataBlock{12, 64, 8}};
  EXPECT_EQ(to_bit_address(*parse_s5_address("E 4.1")), (BitAddress{IoArea::input, 4, 1}));
  EXPECT_EQ(to_bit_address(*parse_s5_address("A 5.0")), (BitAddress{IoArea::output, 5, 0}));
  EXPECT_EQ(to_bit_address(*parse_s5_address("M 10.3")), (BitAddress{IoArea::marker, 10, 3}));
  // DW 2 of DB10: DL at byte 4 (bits 15..8), DR at byte 5 (bits 7..0).
  EXPECT_EQ(to_bit_address(*parse_s5_address("DB10 D 2.0"), blocks), (BitAddress{IoArea::data, 5, 0}));
  EXPECT_EQ(to_bit_address(*parse_s5_address("DB10 D 2.9"), blocks), (BitAddress{IoArea::data, 4, 1}));
  EXPECT_EQ(to_bit_address(*parse_s5_address("DB12 D 1.15"), blocks), (BitAddress{IoArea::data, 66, 7}));
  EXPECT_EQ(to_byte_address(*parse_s5_address("DB12 DL 1"), blocks), (ByteAddress{IoArea::data, 66}));
  EXPECT_EQ(to_byte_address(*parse_s5_address("DB12 DR 1"), blocks), (ByteAddress{IoArea::data, 67}));
  EXPECT_EQ(to_byte_address(*parse_s5_address("MB 251")), (ByteAddress{IoArea::marker, 251}));
  const auto unknown = to_bit_address(*parse_s5_address("DB11 D 0.0"), blocks);
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().find("DB11"), std::string::npos) << unknown.error();
  EXPECT_FALSE(to_bit_address(*parse_s5_address("DB12 D 8.0"), blocks)) << "beyond the block's words";
  EXPECT_FALSE(to_bit_address(*parse_s5_address("EB 4"))) << "a byte is not a bit";
  EXPECT_FALSE(to_byte_address(*parse_s5_address("E 4.0"))) << "a bit is not a byte";
  // The D bit and the DL/DR byte agree.
  IoImage io(IoLayout{{0, 0, 0, 80}});
  io.set(*to_byte_address(*parse_s5_address("DB10 DL 2"), blocks), 0x02);
  EXPECT_TRUE(io.get(*to_bit_address(*parse_s5_address("DB10 D 2.9"), blocks)));
}

}  // namespace
}  // namespace hil::controllers
