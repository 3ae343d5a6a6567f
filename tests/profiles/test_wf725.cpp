// SPDX-License-Identifier: MIT
// WF 725/726 profile: the manual's MD encoding vectors (shared/vectors/wf725-726.md §7.1), the
// variant-dependent meanings and the mode-change checks (19, 1A, 1B, 1C, 10).
#include <gtest/gtest.h>

#include "hil/profiles/loader.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/validation.hpp"
#include "hil/profiles/wire.hpp"

namespace hp = hil::profiles;

namespace {

class Wf725 : public ::testing::Test {
 protected:
  void SetUp() override {
    auto p = hp::find_profile("wf725-726");
    ASSERT_TRUE(p) << p.error().describe();
    profile_ = *p;
    parser_ = hp::make_parameter_set_parser(profile_);
  }
  /// Encodes MD `md` = `value` for a set with `md4` and `module`; returns "BCD / HEX" or the error.
  std::string encode(int md, std::string_view value, int md4 = 1, std::string module = "WF726A",
                     std::string extra = "") {
    auto parsed = parser_->parse(fmt("MD 4 = {}\n{}", md4, extra));
    hp::Settings s{{"module", module}};
    const hp::Scope scope(*profile_, &parsed.set, s);
    auto ref = profile_->resolve("MD" + std::to_string(md));
    if (!ref) return "no such MD";
    const auto* v = hp::select_variant(*ref, scope);
    if (!v) return "not applicable";
    auto val = hp::parse_value_input(*v, value);
    if (!val) return val.error();
    auto img = hp::encode_value(*profile_, *v, *val);
    if (!img) return img.error();
    char buf[64];
    std::snprintf(buf, sizeof buf, "%04X %04X / %04X %04X", *img->bcd >> 16, *img->bcd & 0xFFFF, *img->binary >> 16,
                  *img->binary & 0xFFFF);
    return buf;
  }
  template <typename... A>
  static std::string fmt(std::string_view f, A... a) {
    std::string out(f);
    std::vector<std::string> args{to_s(a)...};
    for (const auto& x : args) out.replace(out.find("{}"), 2, x);
    return out;
  }
  static std::string to_s(int v) { return std::to_string(v); }
  static std::string to_s(std::string v) { return v; }
  static std::string to_s(const char* v) { return v; }

  std::vector<hp::Problem> check(std::string_view text, hp::Settings s = {{"module", std::string("WF726A")}}) {
    auto r = parser_->parse(text);
    auto v = hp::validate(*profile_, r.set, s);
    v.insert(v.begin(), r.problems.begin(), r.problems.end());
    return v;
  }
  static bool has(const std::vector<hp::Problem>& v, std::string_view text) {
    for (const auto& p : v)
      if ((p.param + " " + p.rule + " " + p.message).find(text) != std::string::npos) return true;
    return false;
  }
  std::shared_ptr<const hp::Profile> profile_;
  std::unique_ptr<hp::ParameterSetParser> parser_;
};

}  // namespace

TEST_F(Wf725, ManualEncodingVectors) {
  EXPECT_EQ(encode(1, "1200"), "0000 1200 / 0000 04B0");
  EXPECT_EQ(encode(2, "500"), "0000 0500 / 0000 01F4");
  EXPECT_EQ(encode(3, "8521"), "0085 2100 / 000D 0084");
  EXPECT_EQ(encode(4, "4"), "0000 0004 / 0000 0004");
  EXPECT_EQ(encode(5, "32768", 2, "WF726B"), "0003 2768 / 0000 8000");
  EXPECT_EQ(encode(6, "2"), "0000 0002 / 0000 0002");
  EXPECT_EQ(encode(7, "2"), "0000 0002 / 0000 0002");
  EXPECT_EQ(encode(7, "76", 2, "WF726B"), "0000 0076 / 0000 004C");
  EXPECT_EQ(encode(7, "32", 2, "WF726C"), "0000 0032 / 0000 0020");
  EXPECT_EQ(encode(8, "1200"), "0000 1200 / 0000 04B0");
  EXPECT_EQ(encode(9, "1"), "0000 0001 / 0000 0001");
  EXPECT_EQ(encode(10, "21"), "0000 0021 / 0000 0015");
  EXPECT_EQ(encode(15, "47"), "0000 0047 / 0000 002F");
  EXPECT_EQ(encode(11, "-24537"), "8002 4537 / FFFF A027");
  EXPECT_EQ(encode(12, "-42728"), "8004 2728 / FFFF 5918");
  EXPECT_EQ(encode(13, "96417"), "0009 6417 / 0001 78A1");
  EXPECT_EQ(encode(14, "137428"), "0013 7428 / 0002 18D4");
  EXPECT_EQ(encode(16, "-824967"), "8082 4967 / FFF3 6979");
  EXPECT_EQ(encode(17, "-25"), "8000 0025 / FFFF FFE7");
  EXPECT_EQ(encode(17, "1246", 2, "WF726B"), "0000 1246 / 0000 04DE");
  EXPECT_EQ(encode(18, "200"), "0000 0200 / 0000 00C8");
  EXPECT_EQ(encode(19, "0"), "0000 0000 / 0000 0000");
  EXPECT_EQ(encode(20, "31830980"), "3183 0980 / 01E5 B3C4");
  EXPECT_EQ(encode(22, "1.12"), "0000 0112 / 0000 0070");
  EXPECT_EQ(encode(23, "8000"), "0000 8000 / 0000 1F40");
  EXPECT_EQ(encode(24, "36700"), "0003 6700 / 0000 8F5C");
  EXPECT_EQ(encode(25, "12"), "0000 0012 / 0000 000C");
  EXPECT_EQ(encode(26, "4315"), "0000 4315 / 0000 10DB");
  EXPECT_EQ(encode(27, "3"), "0000 0003 / 0000 0003");
  EXPECT_EQ(encode(28, "1427366"), "0142 7366 / 0015 C7A6");
  EXPECT_EQ(encode(29, "32"), "0000 0032 / 0000 0020");
  EXPECT_EQ(encode(30, "150"), "0000 0150 / 0000 0096");
  EXPECT_EQ(encode(31, "41"), "0000 0041 / 0000 0029");
  EXPECT_EQ(encode(32, "42"), "0000 0042 / 0000 002A");
  EXPECT_EQ(encode(33, "11"), "0000 0011 / 0000 000B");
  EXPECT_EQ(encode(34, "10000"), "0001 0000 / 0000 2710");
  EXPECT_EQ(encode(34, "1000", 2, "WF726B"), "0000 1000 / 0000 03E8");
  EXPECT_EQ(encode(35, "47"), "0000 0047 / 0000 002F");
  EXPECT_EQ(encode(36, "32775"), "0003 2775 / 0000 8007");
  EXPECT_EQ(encode(37, "1", 2, "WF726C"), "0000 0001 / 0000 0001");
  EXPECT_EQ(encode(38, "2430"), "0000 2430 / 0000 097E");
  EXPECT_EQ(encode(39, "2430"), "0000 2430 / 0000 097E");
  EXPECT_EQ(encode(40, "1"), "0000 0001 / 0000 0001");
  EXPECT_EQ(encode(41, "S|J"), "0006 5538 / 0001 0002");
  EXPECT_EQ(encode(41, "65538"), "0006 5538 / 0001 0002");
  EXPECT_EQ(encode(42, "1"), "0000 0001 / 0000 0001");
  EXPECT_EQ(encode(42, "87", 3), "0000 0087 / 0000 0057");
  EXPECT_EQ(encode(43, "52", 3), "0000 0052 / 0000 0034");
  EXPECT_EQ(encode(44, "10", 3), "0000 0010 / 0000 000A");
  EXPECT_EQ(encode(45, "50000", 3), "0005 0000 / 0000 C350");
  EXPECT_EQ(encode(46, "500"), "0000 0500 / 0000 01F4");
  EXPECT_EQ(encode(46, "25000", 3), "0002 5000 / 0000 61A8");
  EXPECT_EQ(encode(47, "500"), "0000 0500 / 0000 01F4");
  EXPECT_EQ(encode(47, "5000", 3), "0000 5000 / 0000 1388");
  EXPECT_EQ(encode(48, "55", 3), "0000 0055 / 0000 0037");
  EXPECT_EQ(encode(49, "1"), "0000 0001 / 0000 0001");
}

TEST_F(Wf725, VariantMeaningsFollowControlAndEncoder) {
  EXPECT_EQ(encode(22, "1.12", 3), "not applicable") << "Kv is closed loop only";
  EXPECT_EQ(encode(29, "32", 1, "WF725A"), "not applicable") << "split drive is WF 726 only";
  EXPECT_EQ(encode(1, "1200", 3, "WF725A"), "not applicable") << "open-loop voltage ramps are WF 726 only";
  EXPECT_EQ(encode(1, "1200", 3, "WF726A"), "0000 1200 / 0000 04B0");
  EXPECT_NE(encode(11, "80000000").find("BCD limit"), std::string::npos);
  EXPECT_NE(encode(22, "1.125").find("multiple"), std::string::npos);
}

TEST_F(Wf725, DecodeBothFormats) {
  auto ref = profile_->resolve("MD11");
  const auto& v = ref->spec->variants.front();
  EXPECT_EQ(hp::to_string(hp::decode_wire(*profile_, v, "8002 4537")->at(0)), "-24537");
  EXPECT_EQ(hp::to_string(hp::decode_wire(*profile_, v, "HEX FFFF A027")->at(0)), "-24537");
  EXPECT_FALSE(hp::decode_wire(*profile_, v, "8002 45A7")) << "invalid BCD digit";
  auto md3 = profile_->resolve("MD 3");
  EXPECT_EQ(hp::to_string(hp::decode_wire(*profile_, md3->spec->variants.front(), "BCD 00852100")->at(0)), "8521");
}

TEST_F(Wf725, ModeChangeChecks) {
  const std::string base =
      "MD 49 = 1\nMD 4 = 1\nMD 11 = -24537\nMD 12 = -42728\nMD 13 = 96417\nMD 14 = 137428\nMD 19 = 1\nMD 20 = 0\nMD 34 "
      "= 10000\n";
  EXPECT_FALSE(has(check(base), "wf.")) << "the manual's ordering example is valid";
  EXPECT_TRUE(has(check(base + "MD 19 = 0\n"), "error 19"));
  EXPECT_TRUE(has(check(base + "MD 34 = 0\n"), "error 1A"));
  EXPECT_TRUE(has(check(base + "MD 12 = -20000\n"), "1B"));
  EXPECT_TRUE(has(check(base + "MD 14 = 90000\n"), "1C"));
  EXPECT_TRUE(has(check(base + "MD 33 = 50\nMD 25 = 40\n"), "error 10"));
  EXPECT_TRUE(has(check(base + "MD 32 = 42\nMD 25 = 12\n"), "clamping"));
  EXPECT_TRUE(has(check(base + "MD 4 = 2\n"), "error 30"));
  EXPECT_FALSE(has(check(base + "MD 4 = 2\nMD 21 = 2\nMD 41 = U\n", {{"module", std::string("WF726B")}}), "error 30"));
}

TEST_F(Wf725, ResolutionScalesRangesAndSteps) {
  auto v = check("MD 49 = 2\nMD 11 = -24537\n");
  EXPECT_TRUE(has(v, "step resolution")) << "at 10 µm positions are multiples of 10";
  v = check("MD 49 = 2\nMD 24 = 655350\n");
  EXPECT_FALSE(has(v, "MD24")) << "the window limit scales to 655 350";
  v = check("MD 49 = 1\nMD 24 = 655350\n");
  EXPECT_TRUE(has(v, "MD24"));
  v = check("MD 49 = 3\nMD 14 = 79999999\n");
  EXPECT_TRUE(has(v, "MD14"));
  v = check("MD 49 = 1\nMD 38 = 1960\n");
  EXPECT_TRUE(has(v, "MD38"));
  EXPECT_FALSE(has(check("MD 49 = 2\nMD 38 = 19500\n"), "MD38"));
}

TEST_F(Wf725, ParserReportsEveryBadLine) {
  auto r = parser_->parse("MD 0 = 1\nMD 51 = 1\nMD x\nfoo\nMD 11 = abc\nMD 11 BCD 8002 45A7\n");
  ASSERT_EQ(r.problems.size(), 6u);
  EXPECT_NE(r.problems[0].message.find("error 121"), std::string::npos);
  EXPECT_NE(r.problems[1].message.find("error 121"), std::string::npos);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(r.problems[static_cast<std::size_t>(i)].line, i + 1);
}

TEST_F(Wf725, Catalogues) {
  const auto* t = profile_->catalogue("traversing");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->find(0x95)->text, "Pre-limit switch negative (MD 11)");
  EXPECT_EQ(t->find(0x95)->reaction, hp::Reaction::stop);
  EXPECT_EQ(t->find(0x15)->reaction, hp::Reaction::drive_off);
  EXPECT_EQ(t->find(0x07)->reaction, hp::Reaction::needs_reset);
  EXPECT_EQ(t->find(0x0A), nullptr) << "unused codes are not in the catalogue";
  EXPECT_EQ(t->parse_code("1B"), 0x1B);
  EXPECT_TRUE(t->find(0x01) && t->find(0x05));
  const auto* io = profile_->catalogue("program_io");
  ASSERT_TRUE(io);
  EXPECT_EQ(io->find(121)->text, "MD number not valid");
  ASSERT_TRUE(profile_->catalogue("standard2")->find(870));
}
