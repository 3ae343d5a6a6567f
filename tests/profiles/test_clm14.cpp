// SPDX-License-Identifier: MIT
// CLM1.4 profile: the manual's 72 parameter telegrams, the constraint rules, the catalogues.
#include <gtest/gtest.h>

#include "device_test.hpp"

#include <fstream>
#include <sstream>

#include "hil/profiles/loader.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/validation.hpp"
#include "hil/profiles/wire.hpp"

namespace hp = hil::profiles;

namespace {

using hil::profiles::testing::read;

class Clm14 : public hil::profiles::testing::DeviceTest {
 protected:
  Clm14() : DeviceTest("clm14") {}
  /// Problems of the manual's set with `line` appended (later lines win).
  std::vector<hp::Problem> problems_with(const std::string& extra, const hp::Settings& s = {}) {
    return problems_of(parser_->parse(read("clm14_manual_defaults.txt") + extra), s);
  }
  static bool has(const std::vector<hp::Problem>& v, std::string_view param, std::string_view rule_part) {
    for (const auto& p : v)
      if (p.param.find(param) != std::string::npos && (p.rule + " " + p.message).find(rule_part) != std::string::npos)
        return true;
    return false;
  }
};

}  // namespace

TEST_F(Clm14, ManualTelegramsParseValidateAndRewriteByteExact) {
  const auto text = read("clm14_manual_defaults.txt");
  const auto r = parser_->parse(text);
  for (const auto& p : r.problems) ADD_FAILURE() << p.describe();
  EXPECT_EQ(r.set.entries.size(), 72u);
  for (const auto& p : hp::validate(*profile_, r.set)) ADD_FAILURE() << p.describe();
  // writing the set reproduces every telegram of the manual, checksum included
  std::string expected;
  for (std::string_view t = text; !t.empty();) {
    const auto nl = t.find('\n');
    const auto line = t.substr(0, nl);
    if (!line.starts_with(";")) expected += std::string(line) + "\n";
    t = nl == std::string_view::npos ? std::string_view{} : t.substr(nl + 1);
  }
  EXPECT_EQ(parser_->write(r.set), expected);
}

TEST_F(Clm14, ChecksumVectors) {
  EXPECT_EQ(hp::clm_checksum("# N0000 POI 1    +123456.789 123 "), 0xC4);
  EXPECT_EQ(hp::clm_checksum("#5N0123 NOP  "), 0x45);
  EXPECT_EQ(hp::clm_checksum("# N0101 AEA Q1.00.3 1 "), 0xC0);
  EXPECT_EQ(hp::clm_checksum("! START "), 0x10);
  EXPECT_EQ(hp::clm_checksum("# V600 +00000100.000000 "), 0x93);
}

TEST_F(Clm14, EncodeDecodeTelegramFields) {
  auto ref = profile_->resolve("A112");
  ASSERT_TRUE(ref);
  const auto& v = ref->spec->variants.front();
  auto value = hp::parse_value_input(v, "3000 10");
  ASSERT_TRUE(value) << value.error();
  auto img = hp::encode_value(*profile_, v, *value);
  ASSERT_TRUE(img);
  EXPECT_EQ(img->text, "03000 10.0");
  auto io = profile_->resolve("a124");
  ASSERT_TRUE(io);
  auto back = hp::decode_wire(*profile_, io->spec->variants.front(), "Q1.00.0 -100 0");
  ASSERT_TRUE(back) << back.error();
  EXPECT_EQ(hp::to_string((*back)[0]), "Q1.00.0");
  EXPECT_EQ(hp::to_string((*back)[1]), "-100");
  EXPECT_FALSE(hp::decode_wire(*profile_, io->spec->variants.front(), "X1.00.0 -100 0"));
  EXPECT_FALSE(hp::decode_wire(*profile_, v, "03000"));                                  // field missing
  EXPECT_FALSE(hp::decode_wire(*profile_, v, "03000 10.0 1"));                           // field too many
  EXPECT_FALSE(hp::encode_value(*profile_, v, *hp::parse_value_input(v, "123456 10")));  // rpm field is 5 wide
  EXPECT_FALSE(profile_->resolve("A233")) << "Ax33-Ax42 exist for axis 1 only";
  EXPECT_TRUE(profile_->resolve("A433") == std::nullopt);
  EXPECT_TRUE(profile_->resolve("A442") == std::nullopt);
  EXPECT_TRUE(profile_->resolve("A142"));
}

TEST_F(Clm14, RangeStepAndTypeViolations) {
  auto v = problems_with("A106 060000.000\n");
  EXPECT_TRUE(has(v, "A106", "range 0.1..50000")) << v.size();
  v = problems_with("A110 1.100\n");
  EXPECT_TRUE(has(v, "A110", "range 0..1.024"));
  v = problems_with("B010 2.2\n");
  EXPECT_TRUE(has(v, "B010", "one of"));
  v = problems_with("A124 I1.00.0 -100 0\n");
  EXPECT_TRUE(has(v, "A124", "I/O type Q/M"));
  v = problems_with("A120 0 0 00 7\n");
  EXPECT_TRUE(has(v, "A120", "one of 0, 1"));
}

TEST_F(Clm14, CrossParameterRules) {
  auto v = problems_with("A107 000200.000\n");
  EXPECT_TRUE(has(v, "A107", "Ax07 <= Ax06"));
  v = problems_with("A112 00020 10.0\n");  // 20 rpm × 10 IU / 60 = 3.33 IU/s < Ax06 = 100
  EXPECT_TRUE(has(v, "A106", "possible Vmax"));
  v = problems_with("A103 +200000.000\n");
  EXPECT_TRUE(has(v, "A103", "Ax03 < Ax04"));
  v = problems_with("A100 2 0 0 0 0\nA120 2 0 24 1\nA119 01024 0300\n");  // rotary table, multi-turn, ratio 300
  EXPECT_TRUE(has(v, "A119", "power of 2"));
  v = problems_with("A100 2 0 0 0 0\nA120 2 0 24 1\nA119 01024 0256\nA125 +04000.000\n");  // IUT = 10 × 256 = 2560
  EXPECT_TRUE(has(v, "A125", "IU per table revolution"));
  v = problems_with("B000 0 1 0\n", {{"hardware_axes", 2.0L}});
  EXPECT_TRUE(has(v, "B000", "error 17"));
  EXPECT_TRUE(has(v, "A300", "missing")) << "axis 3 enabled: its block is required";
  v = problems_with("B004 009600 0 1 8 1\n");
  EXPECT_TRUE(has(v, "B002", "Only one of X6"));
  v = problems_with("A100 1 5 0 0 0\nA109 500 000\n");
  EXPECT_TRUE(has(v, "A109", "A109 = 000 000"));
  v = problems_with("A100 1 5 0 0 0\n");
  EXPECT_FALSE(has(v, "A109", "A109 = 000 000"));
}

TEST_F(Clm14, FlyingCutoffOnlyOnAxis1) {
  auto v = problems_with("B000 1 0 0\nA200 1 5 0 0 0\n");
  EXPECT_TRUE(has(v, "A200", "flying cutoff on axis 1 only"));
}

TEST_F(Clm14, TelegramErrorsUseSerialErrorNumbers) {
  auto r = parser_->parse("# K A106 000100.000$00\n# K X106 1\n# K A1X6 1\n# K A199 1\n#?K A106\nA106 abc\n");
  ASSERT_EQ(r.problems.size(), 6u);
  EXPECT_NE(r.problems[0].message.find("serial error 04"), std::string::npos);
  EXPECT_NE(r.problems[1].message.find("serial error 11"), std::string::npos);
  EXPECT_NE(r.problems[2].message.find("serial error 06"), std::string::npos);
  EXPECT_NE(r.problems[3].message.find("serial error 07"), std::string::npos);
  EXPECT_NE(r.problems[4].message.find("serial error 02"), std::string::npos);
  EXPECT_EQ(r.problems[5].line, 6);
}

TEST_F(Clm14, DiagnosticCatalogue) {
  const auto* diag = profile_->catalogue("diagnostic");
  ASSERT_TRUE(diag);
  // B018 vector: "position lag, axis 2" on Q1.02 = 0111 0011 = 0x73
  const auto* lag2 = diag->find(0x73);
  ASSERT_TRUE(lag2);
  EXPECT_EQ(lag2->text, "Excess Pos Lag 2");
  EXPECT_EQ(lag2->reaction, hp::Reaction::drive_off);
  EXPECT_EQ(diag->find(0x04)->reaction, hp::Reaction::message);
  EXPECT_EQ(diag->find(0x19)->reaction, hp::Reaction::needs_reset);
  EXPECT_EQ(diag->parse_code("E2"), 0xE2);
  EXPECT_EQ(diag->find(0xE2)->text, "HOM Command A4");
  EXPECT_EQ(diag->find(0xAC), nullptr) << "4C/7C exist for axes 1-2 only";
  const auto fault = diag->make_fault(0x73, "axis 2");
  EXPECT_EQ(fault.code.value(), 0x73);
  EXPECT_STREQ(fault.code.category().name(), "clm14.diagnostic");
  const auto* serial = profile_->catalogue("serial");
  ASSERT_TRUE(serial);
  EXPECT_EQ(serial->find(12)->text, "Block # too large");
  for (const auto& e : serial->entries()) EXPECT_LE(e.text.size(), 20u) << "status 01 text is 20 characters";
  const auto* sdc = profile_->catalogue("sdc");
  ASSERT_TRUE(sdc);
  EXPECT_NE(sdc->find(0x010C)->text.find("Block # too large"), std::string::npos);
}
