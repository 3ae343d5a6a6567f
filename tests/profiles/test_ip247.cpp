// SPDX-License-Identifier: MIT
// IP247 profile: the manual's MD DB example as a STEP 5 listing, the DB field encodings and the MD
// checks (MD errors 2, 4, 6, 7, 9, 10, 13, 14, 17, 21).
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

class Ip247 : public hil::profiles::testing::DeviceTest {
 protected:
  Ip247() : DeviceTest("ip247") {}
  std::vector<hp::Problem> problems_with(const std::string& extra, hp::Settings s = {}) {
    return problems_of(parser_->parse(read("ip247_manual_md.txt") + extra), s);
  }
  std::string value_of(const hp::ParameterSet& s, std::string_view id) {
    const auto* e = s.find(profile_->resolve(id)->id());
    return e ? e->text : "<absent>";
  }
};

}  // namespace

TEST_F(Ip247, ManualExampleDecodesAndValidates) {
  const auto r = parser_->parse(read("ip247_manual_md.txt"));
  for (const auto& p : r.problems) ADD_FAILURE() << p.describe();
  for (const auto& p : hp::validate(*profile_, r.set)) ADD_FAILURE() << p.describe();
  EXPECT_EQ(value_of(r.set, "fmax"), "5000");
  EXPECT_EQ(value_of(r.set, "fss"), "200");
  EXPECT_EQ(value_of(r.set, "frequency_increase"), "50");
  EXPECT_EQ(value_of(r.set, "gear"), "2000");
  EXPECT_EQ(value_of(r.set, "sw_limit_start"), "-400000");
  EXPECT_EQ(value_of(r.set, "DW44"), "-75000");
  EXPECT_EQ(value_of(r.set, "db_number"), "1");
  EXPECT_EQ(value_of(r.set, "reference_direction"), "32");
  // and writes back to the same 70 words
  const auto again = parser_->parse(parser_->write(r.set));
  EXPECT_TRUE(again.problems.empty());
  EXPECT_EQ(parser_->write(again.set), parser_->write(r.set));
  EXPECT_NE(parser_->write(r.set).find("29: KH = FFF9\n30: KH = E580\n"), std::string::npos);
  EXPECT_NE(parser_->write(r.set).find("2: KY = 066,001\n"), std::string::npos);
}

TEST_F(Ip247, FieldEncodings) {
  auto enc = [&](std::string_view id, std::string_view value) {
    auto ref = profile_->resolve(id);
    const auto& v = ref->spec->variants.front();
    auto val = hp::parse_value_input(v, value);
    if (!val) return val.error();
    auto img = hp::encode_value(*profile_, v, *val);
    return img ? img->text : img.error();
  };
  EXPECT_EQ(enc("fmax", "5000"), "0000 1388");
  EXPECT_EQ(enc("frequency_increase", "50"), "0000 C350");
  EXPECT_EQ(enc("DW44", "-75000"), "FFFE DB08");
  EXPECT_EQ(enc("pulse_duration", "30"), "001E");
  EXPECT_EQ(enc("module", "7"), "0700");
  EXPECT_EQ(enc("axis", "2"), "0002");
  EXPECT_NE(enc("frequency_increase", "50.0001").find("multiple"), std::string::npos);
  EXPECT_NE(enc("DW27", "3000000000").find("does not fit"), std::string::npos);
}

TEST_F(Ip247, MachineDataChecks) {
  EXPECT_TRUE(has(problems_with("11: KF = +00200\n"), "MD error 2"));  // 200 µs > ½ period at 5 kHz
  EXPECT_TRUE(has(problems_with("11: KF = +00040\n"), "range 1..31"));
  EXPECT_TRUE(has(problems_with("17: DD = 6000\n"), "MD error 4"));  // 10 kHz > fmax
  EXPECT_TRUE(has(problems_with("9: DH = 00000010\n"), "range 0.02..2599.999"));
  EXPECT_TRUE(has(problems_with("9: DD = 2000000\n"), "MD error 6"));  // τ = 2.5 ms < 5 ms
  EXPECT_TRUE(has(problems_with("29: DD = 600000\n"), "MD error 7"));
  EXPECT_TRUE(has(problems_with("15: DD = 100\n"), "MD error 9"));      // 0.5 BU/pulse
  EXPECT_TRUE(has(problems_with("13: KF = +00006\n"), "MD error 10"));  // 200 not a multiple of 6
  EXPECT_TRUE(has(problems_with("38: DD = 99999999\n"), "MD error 13"));
  EXPECT_TRUE(has(problems_with("34: DD = 99900000\n"), "MD error 14"));
  EXPECT_TRUE(has(problems_with("23: DD = 100\n"), "MD error 17"));  // 166 Hz < fss
  EXPECT_TRUE(has(problems_with("46: KH = 0080\n29: DD = 600000\n"), "MD error 21"));
  EXPECT_TRUE(has(problems_with("3: KY = 005,001\n", {{"sysid_module", 4.0L}}), "MD error 12"));
  EXPECT_TRUE(has(problems_with("12: KH = 0041\n"), "one of 0, 64"));
  EXPECT_TRUE(has(problems_with("5: DD = 30\n"), "range fmax_min_hz..100000"));
  EXPECT_FALSE(has(
      problems_with(
          "5: DD = 30\n11: KF = +00001\n7: DD = 1\n9: DH = 00000014\n17: DD = 1\n19: DD = 1\n21: DD = 1\n23: DD = 1\n",
          {{"fmax_min_hz", 12.0L}}),
      "range fmax_min_hz"));
}

TEST_F(Ip247, ListingErrorsCarryTheirLine) {
  auto r = parser_->parse("0: KF = +70000\n1: KH = 12345\n2: KY = 300,1\nfoo\n80: KF = +0\n5: XX = 1\n");
  ASSERT_EQ(r.problems.size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(r.problems[static_cast<std::size_t>(i)].line, i + 1);
  auto half = parser_->parse("5: KH = 0000\n");
  ASSERT_EQ(half.problems.size(), 1u);
  EXPECT_NE(half.problems[0].message.find("incomplete"), std::string::npos);
}

TEST_F(Ip247, Catalogues) {
  const auto* m = profile_->catalogue("module");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->find(59)->text_de, "Der Referenznocken ist defekt");
  EXPECT_EQ(m->find(7)->reaction, hp::Reaction::message);
  EXPECT_EQ(m->find(25)->reaction, hp::Reaction::stop);
  EXPECT_EQ(m->find(21), nullptr) << "free codes are not listed";
  const auto* md = profile_->catalogue("md_error");
  ASSERT_TRUE(md);
  EXPECT_EQ(md->find(23), nullptr);
  EXPECT_EQ(md->find(22)->text_de, "Falsche Start-Stopp-Frequenz");
  EXPECT_TRUE(profile_->catalogue("syntax")->find(37));
  EXPECT_EQ(profile_->catalogue("interface")->parse_code("A"), 10);
}
