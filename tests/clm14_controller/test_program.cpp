// SPDX-License-Identifier: MIT
// CLM1.4 program lines: every command of §4.2 parses, bad lines give the device's error number.
#include <gtest/gtest.h>

#include <set>

#include "hil/controllers/clm14/instruction.hpp"
#include "hil/controllers/clm14/number.hpp"
#include "hil/controllers/clm14/settings.hpp"

namespace hil::controllers::clm14 {
namespace {

struct Good {
  std::string_view text;
  Op op;
};

TEST(ClmProgram, EveryCommandOfTheManualParses) {
  const std::vector<Good> good{
      {"ACC 1 999 999", Op::acc},
      {"ACC V602 V600 V601", Op::acc},
      {"AEA Q1.01.1 1", Op::aea},
      {"AEA Q1.01.0 V600", Op::aea},
      {"AEO 1    1 1 500    100", Op::aeo},
      {"AKN M2.02.3 1", Op::akn},
      {"AKP M2.02 01201201", Op::akp},
      {"APE Q1.01 01201201", Op::ape},
      {"BAC 1234 -5678 98765", Op::bac},
      {"BAC V600 -5678 V601", Op::bac},
      {"BCE 0234 I1.00.3    1", Op::bce},
      {"BIC 0234 56     M0.12.3 0 1", Op::bic},
      {"BIO 0234 M2.03 Q0.00 01201201", Op::bio},
      {"BPA 0123 M2.02      21112212", Op::bpa},
      {"CID V600 1     +12345.678", Op::cid},
      {"CID V600 1     +V601", Op::cid},
      {"CIO M2.02.3 Q1.01.1 08", Op::cio},
      {"CLC 0234", Op::clc},
      {"CON 1    1    +234", Op::con},
      {"CON V602 V600 +V601", Op::con},
      {"COU +12345 Q1.01.1 654321", Op::cou},
      {"CPJ V600>=+12345.678 1234.56 1234", Op::cpj},
      {"CPJ V604 >=+V600     V601    V603", Op::cpj},
      {"CPJ V100 < +01000.000 0000.00 1000", Op::cpj},
      {"CPL 1", Op::cpl},
      {"CPS V602<=+12345.678 1234.56 Q1.01.1", Op::cps},
      {"CST 3 0", Op::cst},
      {"CVT V600 M2.00 0 0", Op::cvt},
      {"EOS", Op::eos},
      {"FAK 1 1.234500", Op::fak},
      {"FAK 5 0.998000", Op::fak},
      {"FOL 1 1 1.000000", Op::fol},
      {"FOL 2 2 -V600", Op::fol},
      {"FUN 2222220", Op::fun},
      {"HOM 1", Op::hom},
      {"JMP 0000", Op::jmp},
      {"JSR 1000", Op::jsr},
      {"JST 0000", Op::jst},
      {"JTK 0100 1", Op::jtk},
      {"LMK 1 001000.000 000300.000", Op::lmk},
      {"LML 1 001000.000", Op::lml},
      {"LMR 1 001000.000 000300.000 +00100.000", Op::lmr},
      {"MAT V600 = V601 - +123456.987654", Op::mat},
      {"MLO 1 001000.000 Q1.00.0", Op::mlo},
      {"MLT 1 001000.000 Q1.00.0", Op::mlt},
      {"NOP", Op::nop},
      {"PBK 1", Op::pbk},
      {"POA 1 +000200.000 999", Op::poa},
      {"POI 1    +123456.789 123", Op::poi},
      {"PSA 1 +000200.000 999", Op::psa},
      {"PSI 1 -V604 V601", Op::psi},
      {"REP 0900 1 000500.000", Op::rep},
      {"RMI 1 0 I1.01.7", Op::rmi},
      {"RSV 1 0000 10000", Op::rsv},
      {"RTM 1 1", Op::rtm},
      {"RTS", Op::rts},
      {"SAC 1 0 +123456.789", Op::sac},
      {"SET V600 = +12345678.123456", Op::set},
      {"SET V701 = +V700", Op::set},
      {"SRM 1 +000200.000 +500 I1.01.0", Op::srm},
      {"SRP 1 1 0 V600 M2.02", Op::srp},
      {"TXT 0 HELLO WORLD 123", Op::txt},
      {"VCC 1 +000050.000 250 0 0", Op::vcc},
      {"VEO 1 4 1 500 0", Op::veo},
      {"WAI 00.500", Op::wai},
      {"WAI V600", Op::wai},
  };
  std::set<Op> seen;
  for (const auto& g : good) {
    auto in = parse_instruction(g.text);
    ASSERT_TRUE(in.has_value()) << g.text << ": " << in.error().message;
    EXPECT_EQ(in->op, g.op) << g.text;
    seen.insert(in->op);
  }
  EXPECT_EQ(seen.size(), static_cast<std::size_t>(op_count)) << "all 55 commands covered";
}

TEST(ClmProgram, OperandsAreReadExactly) {
  auto poi = parse_instruction("POI 1    +123456.789 123").value();
  EXPECT_EQ(poi.n[0].value, 1 * micro_one);
  EXPECT_EQ(poi.n[1].value, 123'456'789'000);
  EXPECT_EQ(poi.n[2].value, 123 * micro_one);
  auto psi = parse_instruction("PSI 1 -V604 V601").value();
  EXPECT_EQ(psi.n[1].var, 604);
  EXPECT_TRUE(psi.n[1].negate);
  auto cpj = parse_instruction("CPJ V604 >=+V600     V601    V603").value();
  EXPECT_EQ(cpj.var, 604);
  EXPECT_EQ(cpj.cmp, Cmp::ge);
  EXPECT_EQ(cpj.n[0].var, 600);
  EXPECT_EQ(cpj.n[2].var, 603);
  auto bpa = parse_instruction("BPA 0123 M2.02      21112212").value();
  EXPECT_EQ(bpa.byte, (ByteAddress{Area::marker, 2, 2}));
  EXPECT_EQ(bpa.pattern[0], 2);
  EXPECT_EQ(bpa.pattern[7], 2);
  auto mat = parse_instruction("MAT V600 = V601 - +123456.987654").value();
  EXPECT_EQ(mat.mat_op, '-');
  EXPECT_EQ(mat.n[1].value, 123'456'987'654);
  auto txt = parse_instruction("TXT 1 MOTOR HOT").value();
  EXPECT_EQ(txt.text, "MOTOR HOT       ");
  auto cou = parse_instruction("COU 000000 Q1.00.4 000010").value();
  EXPECT_TRUE(cou.counter_reset);
}

struct Bad {
  std::string_view text;
  ClmError error;
};

TEST(ClmProgram, BadLinesGiveTheDevicesErrorNumber) {
  const std::vector<Bad> bad{
      {"XYZ 1", ClmError::invalid_program_command},
      {"POI 7 +000010.000 999", ClmError::axis_number},
      {"POI 0 +000010.000 999", ClmError::axis_number},
      {"AEA Q9.00.0 1", ClmError::command_io},
      {"AEA Q1.00.8 1", ClmError::command_io},
      {"AKP M7.00 01201201", ClmError::command_io},
      {"JMP 3000", ClmError::invalid_block_number},
      {"BCE 4000 I1.00.0 1", ClmError::invalid_block_number},
      {"APE Q1.01 0120120", ClmError::invalid_program_command},
      {"APE Q1.01 01201203", ClmError::invalid_program_command},
      {"POI 1 +000010.000", ClmError::invalid_program_command},
      {"POI 1 +000010.000 999 9", ClmError::invalid_program_command},
      {"NOP 1", ClmError::invalid_program_command},
      {"SET V600 +1", ClmError::invalid_program_command},
      {"CPJ V600 => +1 0 0000", ClmError::invalid_program_command},
      {"MAT V600 = V601 % V602", ClmError::invalid_program_command},
      {"TXT 1 LOWER case", ClmError::invalid_program_command},
      {"TXT 3 X", ClmError::invalid_program_command},
      {"WAI V6000", ClmError::invalid_program_command},
      {"FAK 6 1.000000", ClmError::axis_number},
      {"FOL 5 1 1.000000", ClmError::axis_number},
      {"FUN 222", ClmError::invalid_program_command},
      {"FUN 2222223", ClmError::invalid_program_command},
      {"LMR 1 001000.000", ClmError::invalid_program_command},
      {"LMK 1 001000.000", ClmError::invalid_program_command},
      {"MLT 1 000010.000 Q9.00.0", ClmError::command_io},
  };
  for (const auto& b : bad) {
    auto in = parse_instruction(b.text);
    ASSERT_FALSE(in.has_value()) << b.text;
    EXPECT_EQ(in.error().error, b.error) << b.text << ": " << in.error().message;
    EXPECT_NE(in.error().message.find(std::string(b.text.substr(0, 3))), std::string::npos) << in.error().message;
  }
}

TEST(ClmProgram, CounterOffsetIsClearedWhenStored) {
  EXPECT_EQ(clear_counter_offset("COU +00012 Q1.00.4 000010"), "COU +00000 Q1.00.4 000010");
  EXPECT_EQ(clear_counter_offset("BAC 0000 -0003 00010"), "BAC 0000 +0000 00010");
  EXPECT_EQ(clear_counter_offset("POI 1 +000010.000 999"), "POI 1 +000010.000 999");
}

TEST(ClmNumbers, VariableFormat) {
  EXPECT_EQ(parse_micro("+12345678.123456"), 12'345'678'123'456);
  EXPECT_EQ(parse_micro("-0.5"), -500'000);
  EXPECT_EQ(parse_micro("1,5"), 1'500'000);
  EXPECT_EQ(parse_micro("00.500"), 500'000);
  EXPECT_FALSE(parse_micro("123456789"));
  EXPECT_FALSE(parse_micro("1.1234567"));
  EXPECT_FALSE(parse_micro("+"));
  EXPECT_EQ(format_variable(-87'654'321'654'321), "-87654321.654321");
  EXPECT_EQ(format_variable(100'000'000), "+00000100.000000");
  EXPECT_EQ(format_fixed(-12'345'678, 5, 3), "-00012.345");
}

TEST(ClmSettings, BadParameterIsError02NamingIt) {
  auto r = make_settings([](std::string_view n) -> std::string {
    if (n == "A106") return "abc";
    return "";
  });
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().error, ClmError::parameter_invalid);
  EXPECT_TRUE(r.error().message.starts_with("B000")) << r.error().message;  // the first unreadable one
}

}  // namespace
}  // namespace hil::controllers::clm14
