// SPDX-License-Identifier: MIT
// AMKASYN SF profile: the manual's FIPW and REGL command blocks (shared/vectors/amkasyn-sf.md),
// type-dependent meanings of the commanding-DB addresses, fixed-point values and the START checks.
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

class Amk : public hil::profiles::testing::DeviceTest {
 protected:
  Amk() : DeviceTest("amkasyn-sf") {}
  std::vector<hp::Problem> check(const std::string& text, hp::Settings s = {{"id2_ms", 2.0L}}) {
    return problems_of(parser_->parse(text), s);
  }
  std::string value(const hp::ParameterSet& s, std::string_view id) {
    const auto* e = s.find(id);
    return e ? hp::to_string(e->value.at(0)) : "<absent>";
  }
};

}  // namespace

TEST_F(Amk, FipwPrintingMarkExampleIsValid) {
  const auto text = read("amk_fipw_printing_mark.txt");
  for (const auto& p : check(text)) ADD_FAILURE() << p.describe();
  const auto r = parser_->parse(text);
  EXPECT_EQ(value(r.set, "DW3"), "2") << "4 × 0.5 ms";
  EXPECT_EQ(value(r.set, "DD10"), "20000");
  EXPECT_EQ(value(r.set, "INIT_DR0"), "1");
  // writes back the stored (raw) values
  const auto out = parser_->write(r.set);
  EXPECT_NE(out.find("DW3 = 4\n"), std::string::npos);
  EXPECT_NE(out.find("INIT DR0 = 1\n"), std::string::npos);
  EXPECT_EQ(parser_->write(parser_->parse(out).set), out);
}

TEST_F(Amk, ReglExampleFixedPointGains) {
  const auto text = read("amk_regl_force.txt");
  for (const auto& p : check(text, {{"id2_ms", 1.0L}})) ADD_FAILURE() << p.describe();
  const auto r = parser_->parse(text);
  EXPECT_EQ(value(r.set, "DW6"), "2");
  EXPECT_EQ(value(r.set, "DW7"), "0.5");
  EXPECT_EQ(value(r.set, "DW8"), "0.25");
  // the same addresses mean something else for another SF type
  auto dfkt = parser_->parse("INIT DR0 = 4\nDW6 = 512\nDW8 = 64\n");
  EXPECT_EQ(value(dfkt.set, "DW6"), "512") << "DFKT DW6 = division factor, no fixed point";
}

TEST_F(Amk, EncodeWordsLowWordFirst) {
  auto enc = [&](std::string_view id, std::string_view v, std::string type) {
    auto r = parser_->parse("INIT DR0 = " + type + "\n");
    const hp::Scope scope(*profile_, &r.set, {});
    auto ref = profile_->resolve(id);
    const auto* var = hp::select_variant(*ref, scope);
    if (!var) return std::string("n/a");
    auto val = hp::parse_value_input(*var, v);
    if (!val) return val.error();
    auto img = hp::encode_value(*profile_, *var, *val);
    return img ? img->text : img.error();
  };
  EXPECT_EQ(enc("DD10", "20000", "1"), "4E20 0000");
  EXPECT_EQ(enc("DD20", "-1", "6"), "FFFF FFFF");
  EXPECT_EQ(enc("DD8", "70000", "1").find("out of range") == std::string::npos, true);
  EXPECT_EQ(enc("DW6", "2", "6"), "0200");
  EXPECT_EQ(enc("DW4", "-1", "3"), "D8F0") << "VARSYNC m1 = -1.0 = -10000 (DL0 defaults to fct 1 for STDFKT)";
  EXPECT_NE(enc("DW6", "128", "6").find("does not fit"), std::string::npos) << "Kp 128 = raw 32768";
}

TEST_F(Amk, StartChecks) {
  const auto base = read("amk_fipw_printing_mark.txt");
  EXPECT_TRUE(has(check(base + "DW5 = 3\n"), "q must be at most m - 1"));
  EXPECT_TRUE(has(check(base + "DW3 = 2\n"), "must equal drive parameter ID 2"));
  EXPECT_TRUE(has(check(base + "DL1 = 82\n"), "Printing mark control only in BA 2 or 98"));
  EXPECT_TRUE(has(check(base + "INIT DR2 = 1\n"), "32-bit AZ message source"));
  EXPECT_TRUE(has(check(base + "DW23 = 2000\n"), "valid range <= format length / 2"));
  EXPECT_TRUE(has(check(base + "DR7 = 6\n"), "multiples of 4"));
  EXPECT_TRUE(has(check(base + "DR0 = 3\n"), "must be the slot initialised"));
  EXPECT_TRUE(has(check(base + "DD10 = 40\n"), "range 50..32767"));
  EXPECT_TRUE(has(check(base + "DW12 = 30000\n"), "below Xme"));
  EXPECT_TRUE(has(check(base + "INIT DR4 = 3\n"), "exactly one bit"));
  EXPECT_TRUE(has(check(base + "INIT DR0 = 9\n", {{"id2_ms", 2.0L}, {"module", std::string("AZ-PS3")}}), "AZ-PS4"));
  EXPECT_TRUE(has(check(base + "INIT DL0 = 12\n", {{"id2_ms", 2.0L}, {"firmware", 2.08L}}), "INIT_DL0"));
  EXPECT_TRUE(has(check(base + "DW30 = 5\n"), "reserved"));
  EXPECT_TRUE(has(check("INIT DR0 = 12\nDR6 = 30\nDL6 = 30\n"), "at most 56 cams"));
  EXPECT_TRUE(has(check("INIT DR0 = 11\nDD8 = 5000\nDD10 = 1000\n"), "at least the acceleration"));
  EXPECT_TRUE(has(check("INIT DR0 = 6\nDW12 = 0\n"), "output gain"));
}

TEST_F(Amk, ParserErrors) {
  auto r = parser_->parse("INIT DR0 = 1\nXX4 = 1\nDW40 = 1\nDW4 = abc\nDD2 = 1\nDW4 = 70000\nINIT DW12 = 1\n");
  ASSERT_EQ(r.problems.size(), 6u);
  EXPECT_EQ(r.problems[0].line, 2);
  EXPECT_NE(r.problems[1].message.find("outside"), std::string::npos);
  EXPECT_NE(r.problems[2].message.find("not an integer"), std::string::npos);
  EXPECT_NE(r.problems[3].message.find("not used by SF type 1"), std::string::npos);
  EXPECT_NE(r.problems[4].message.find("does not fit"), std::string::npos);
}

TEST_F(Amk, Catalogues) {
  const auto* s = profile_->catalogue("sf_status");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->find(6)->reaction, hp::Reaction::stop);
  const auto* d = profile_->catalogue("dfkt_status");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->parse_code("bit2"), 4);
  EXPECT_EQ(d->find(4)->text, "Upper output maximum speed exceeded");
}

// The profile accepts every example block the manual prints (issue 16): FIPZ with unused table
// cycle times 0, XFIPW with DD18 = 0, EPOS with DD14 = 0 - and still refuses what they would hide.
TEST_F(Amk, ManualExamplesWithZeroedUnusedFieldsAreValid) {
  for (const char* f :
       {"amk_fipz_unused_tables.txt", "amk_xfipw_dd18_zero.txt", "amk_epos_dd14_zero.txt", "amk_apsf_speed.txt"})
    for (const auto& p : check(read(f))) ADD_FAILURE() << f << ": " << p.describe();
  // A table in use without a cycle time is still an error.
  auto fipz = read("amk_fipz_unused_tables.txt");
  fipz.replace(fipz.find("DW11 = 400"), 10, "DW11 = 0  ");
  EXPECT_FALSE(check(fipz).empty());
  // EPOS with external velocity needs the external resolution.
  auto epos = read("amk_epos_dd14_zero.txt");
  epos.replace(epos.find("DL1 = 0 "), 8, "DL1 = 1 ");
  EXPECT_FALSE(check(epos).empty());
}
