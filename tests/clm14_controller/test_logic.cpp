// SPDX-License-Identifier: MIT
// CLM1.4 logic task (§6): IL truth tables, brackets, set/reset, edges, compile errors 38.
#include <gtest/gtest.h>

#include "hil/controllers/clm14/logic_task.hpp"

namespace hil::controllers::clm14 {
namespace {

BitAddress b(std::string_view s) {
  return parse_bit(s).value();
}

LogicProgram compile(std::vector<std::string> lines) {
  auto p = LogicProgram::compile(lines);
  EXPECT_TRUE(p.has_value()) << (p ? "" : p.error().message);
  return p.value_or(LogicProgram{});
}

struct Row {
  bool a, b;
  bool and_, andn, or_, orn, xor_, xorn;
};

TEST(ClmLogic, TruthTablesOfTheManual) {
  const std::vector<Row> rows{{true, true, true, false, true, true, false, true},
                              {false, true, false, false, true, false, true, false},
                              {true, false, false, true, true, true, true, false},
                              {false, false, false, false, false, true, false, true}};
  const std::vector<std::string> ops{"AND", "ANDN", "OR", "ORN", "XOR", "XORN"};
  for (std::size_t o = 0; o < ops.size(); ++o) {
    auto p = compile({"LD I1.00.0", ops[o] + " I1.00.1", "ST Q1.00.0", "END"});
    for (const auto& r : rows) {
      Image im;
      im.set_bit(b("I1.00.0"), r.a);
      im.set_bit(b("I1.00.1"), r.b);
      p.run(im);
      const bool want = std::array<bool, 6>{r.and_, r.andn, r.or_, r.orn, r.xor_, r.xorn}[o];
      EXPECT_EQ(im.bit(b("Q1.00.0")), want) << ops[o] << " " << r.a << r.b;
    }
  }
}

TEST(ClmLogic, StoreFamilyOverAccumulatorAndOldBit) {
  // new bit for (acc, old) = (0,0) (0,1) (1,0) (1,1); the accumulator passes through unchanged
  const std::vector<std::pair<std::string, std::array<bool, 4>>> stores{
      {"ST", {false, false, true, true}},   {"STN", {true, true, false, false}},
      {"SET", {true, true, true, true}},    {"RES", {false, false, false, false}},
      {"SETC", {false, true, true, true}},  {"RESC", {false, true, false, false}},
      {"SETCN", {true, true, false, true}}, {"RESCN", {false, false, false, true}}};
  for (const auto& [op, want] : stores) {
    // LDN loads the inverted input; the second store shows the accumulator survived the first.
    auto p = compile({"LDN I1.00.0", op + " M6.20.3", "ST M6.20.6", "END"});
    for (unsigned i = 0; i < 4; ++i) {
      const bool acc = (i & 2U) != 0;
      const bool old = (i & 1U) != 0;
      Image im;
      im.set_byte({Area::marker, 6, 20}, static_cast<std::uint8_t>(old ? 0xBF : 0xB7));
      im.set_bit(b("I1.00.0"), !acc);
      p.run(im);
      EXPECT_EQ(im.bit(b("M6.20.3")), want[i]) << op << " acc " << acc << " old " << old;
      EXPECT_EQ(im.bit(b("M6.20.6")), acc) << op;
      EXPECT_EQ(im.byte({Area::marker, 6, 20}) & 0xB7, 0xB7) << op << ": other bits of the byte kept";
    }
  }
}

TEST(ClmLogic, BracketsSetResetAndNegatedStore) {
  // Q1.00.0 = I0 AND (I1 OR I2); Q1.00.1 = NOT that; M6.20.0 set by I3, reset by I4
  auto p = compile({"LD I1.00.0", "AND(", "LD I1.00.1", "OR I1.00.2", ")", "ST Q1.00.0", "STN Q1.00.1", "LD I1.00.3",
                    "SETC M6.20.0", "LD I1.00.4", "RESC M6.20.0", "NOP", "END"});
  Image im;
  im.set_bit(b("I1.00.0"), true);
  im.set_bit(b("I1.00.2"), true);
  im.set_bit(b("I1.00.3"), true);
  p.run(im);
  EXPECT_TRUE(im.bit(b("Q1.00.0")));
  EXPECT_FALSE(im.bit(b("Q1.00.1")));
  EXPECT_TRUE(im.bit(b("M6.20.0")));
  im.set_bit(b("I1.00.2"), false);
  im.set_bit(b("I1.00.3"), false);
  p.run(im);
  EXPECT_FALSE(im.bit(b("Q1.00.0")));
  EXPECT_TRUE(im.bit(b("M6.20.0"))) << "SETC latches";
  im.set_bit(b("I1.00.4"), true);
  p.run(im);
  EXPECT_FALSE(im.bit(b("M6.20.0")));
  EXPECT_EQ(p.owned_mask({Area::output, 1, 0}), 0x03) << "the LT owns Q1.00.0 and Q1.00.1, nothing else";
  EXPECT_EQ(p.owned_mask({Area::marker, 6, 20}), 0) << "markers are not owned outputs";
}

TEST(ClmLogic, RisingEdgeExampleOfTheManual) {
  auto p = compile({"LD M6.20.0", "ANDN M6.20.4", "ST M6.20.1", "LD M6.20.0", "ST M6.20.4", "END"});
  Image im;
  p.run(im);
  EXPECT_FALSE(im.bit(b("M6.20.1")));
  im.set_bit(b("M6.20.0"), true);
  p.run(im);
  EXPECT_TRUE(im.bit(b("M6.20.1"))) << "one pass after the rise";
  p.run(im);
  EXPECT_FALSE(im.bit(b("M6.20.1")));
}

TEST(ClmLogic, EndAtLineZeroDisablesTheTask) {
  auto p = compile({"END", "ST Q1.00.0"});
  EXPECT_TRUE(p.empty());
}

TEST(ClmLogic, CompileErrorsAre38WithTheLine) {
  const std::vector<std::pair<std::vector<std::string>, int>> bad{
      {{"LD I1.00.0", "FOO Q1.00.0", "END"}, 1},
      {{"LD I1.00.0", "ST I1.00.1", "END"}, 1},          // inputs cannot be stored
      {{"LD I1.00.0", "ST Q2.00.0", "END"}, 1},          // Q2.00/01 are not LT targets
      {{"LD M2.00.0", "END"}, 0},                        // NC markers M2 are not LT operands
      {{"LD I1.00.0", "AND(", "LD I1.00.1", "END"}, 3},  // unbalanced
      {{"LD I1.00.0", ")", "END"}, 1},
      {{"LD I1.00.0", "ST Q1.00.0"}, 1},  // no END
  };
  for (const auto& [lines, line] : bad) {
    auto p = LogicProgram::compile(lines);
    ASSERT_FALSE(p.has_value()) << lines[static_cast<std::size_t>(line)];
    EXPECT_EQ(p.error().error, ClmError::logic_program);
    EXPECT_EQ(p.error().line, line) << p.error().message;
  }
}

}  // namespace
}  // namespace hil::controllers::clm14
