// SPDX-License-Identifier: MIT
// SINUMERIK ELG profile: tapes (%TEA1/%SEA, ISO parity image), the SD transfer-format vectors
// (shared/vectors/sinumerik-elg.md 11.4), the FE-limit and constants rules, the alarm catalogue.
#include <gtest/gtest.h>

#include "device_test.hpp"

#include <bit>
#include <fstream>
#include <sstream>

#include "hil/profiles/loader.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/validation.hpp"
#include "hil/profiles/wire.hpp"

namespace hp = hil::profiles;

namespace {

using hil::profiles::testing::read;

/// The text as a punched ISO tape: even parity in bit 7, NUL leader.
std::string iso_tape(std::string_view text) {
  std::string out(4, '\0');
  for (char c : text) {
    auto u = static_cast<unsigned char>(c);
    if (std::popcount(u) % 2) u |= 0x80;
    out += static_cast<char>(u);
  }
  return out;
}

class Elg : public hil::profiles::testing::DeviceTest {
 protected:
  Elg() : DeviceTest("sinumerik-elg") {}
  std::vector<hp::Problem> check(const std::string& text, hp::Settings s = {}) {
    return problems_of(parser_->parse(text, s), s);
  }
  std::string field(const hp::ParameterSet& s, std::string_view id, std::string_view name) {
    const auto* e = s.find(id);
    if (!e) return "<absent>";
    const auto& v = e->ref.spec->variants.front();
    for (std::size_t i = 0; i < v.fields.size(); ++i)
      if (v.fields[i].name == name) {
        const auto word = std::get<hp::Decimal>(e->value[i]).units;
        auto bits = hp::parse_bit_field(static_cast<std::uint64_t>(word), v.fields[i].bits);
        for (const auto& b : *bits) (void)b;
        return std::to_string(word);
      }
    return "<no field>";
  }
};

}  // namespace

TEST_F(Elg, ValidTapeParsesAndValidates) {
  const auto text = read("elg_valid.tape");
  for (const auto& p : check(text)) ADD_FAILURE() << p.describe();
  const auto r = parser_->parse(text);
  EXPECT_EQ(hp::to_string(r.set.find("MD3960")->value[0]), "180000");
  EXPECT_EQ(hp::to_string(r.set.find("SD5011")->value[0]), "194");  // C2H
  EXPECT_EQ(hp::to_string(r.set.find("R61")->value[0]), "8.18511");
  // the same tape as an ISO image with even parity in bit 7 gives the same set
  const auto img = parser_->parse(iso_tape(text));
  EXPECT_TRUE(img.problems.empty());
  EXPECT_EQ(parser_->write(img.set), parser_->write(r.set));
  EXPECT_EQ(parser_->write(parser_->parse(parser_->write(r.set)).set), parser_->write(r.set));
}

TEST_F(Elg, IsoTapeBytes) {
  // vectors: %TEA1⏎ = A5 D4 C5 41 B1 0A, M02⏎ = 4D 30 B2 0A
  EXPECT_EQ(iso_tape("%TEA1\n").substr(4), std::string("\xA5\xD4\xC5\x41\xB1\x0A"));
  EXPECT_EQ(iso_tape("M02\n").substr(4), std::string("\x4D\x30\xB2\x0A"));
  std::string bad = iso_tape("%TEA1\nN169=20\nM02\n");
  bad[bad.find('N') + 1] ^= static_cast<char>(0x80);  // '1' of N169 with odd parity
  const auto r = parser_->parse(bad);
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_NE(r.problems[0].message.find("alarm 23"), std::string::npos);
  EXPECT_EQ(r.problems[0].line, 2);
}

// 11.4: C2 → 2 stop, no parity, 300 Bd; C7 → 9600; C0 → 110; 10 → 1 stop, even parity, 110; 30 → odd
TEST_F(Elg, TransferFormatVectors) {
  const auto* sd = profile_->resolve("SD5011")->spec;
  const auto& f = sd->variants.front().fields.front();
  auto decode = [&](std::uint64_t w) {
    auto b = hp::parse_bit_field(w, f.bits);
    std::map<std::string, std::uint64_t> m;
    for (const auto& x : *b) m[x.name] = x.value;
    return m;
  };
  auto baud = [&](std::uint64_t code) {
    for (const auto& row : profile_->tables.at("transfer_format_baud"))
      if (row.at("code") == std::to_string(code)) return row.at("baud");
    return std::string("undefined");
  };
  auto c2 = decode(0xC2);
  EXPECT_EQ(baud(c2["baud"]), "300");
  EXPECT_EQ(c2["stop_bits"], 3u);
  EXPECT_EQ(c2["parity_bit"], 0u);
  EXPECT_EQ(baud(decode(0xC7)["baud"]), "9600");
  EXPECT_EQ(baud(decode(0xC0)["baud"]), "110");
  EXPECT_EQ(baud(decode(0xC3)["baud"]), "600");
  EXPECT_EQ(baud(decode(0xC4)["baud"]), "1200");
  EXPECT_EQ(baud(decode(0xC6)["baud"]), "4800");
  auto x10 = decode(0x10);
  EXPECT_EQ(x10["parity_bit"], 1u);
  EXPECT_EQ(x10["parity_odd"], 0u);
  EXPECT_EQ(x10["stop_bits"], 0u);
  EXPECT_EQ(decode(0x30)["parity_odd"], 1u);
  EXPECT_EQ(decode(0x80)["stop_bits"], 2u);
  // INPUT 9 preset
  for (const auto& row : profile_->tables.at("input9_preset")) {
    auto ref = profile_->resolve("SD" + row.at("sd"));
    ASSERT_TRUE(ref) << row.at("sd");
  }
}

TEST_F(Elg, RulesAndAlarmConditions) {
  const auto base = read("elg_valid.tape");
  auto with = [&](std::string md, std::string sd) {
    std::string t = base;
    t.insert(t.find("M02"), md);
    t.insert(t.rfind("M02"), sd);
    return check(t);
  };
  EXPECT_TRUE(has(with("", "R40=10\n"), "below MD 169"));
  EXPECT_FALSE(has(with("", "R40=100\n"), "below MD 169"));
  EXPECT_TRUE(has(with("N3960=2500000\n", ""), "MD3960"));
  EXPECT_TRUE(has(with("N2520=150\n", ""), "alarm 2200"));
  EXPECT_TRUE(has(with("N3961=0\n", ""), "alarm 2203")) << "drive axis C = axis 2 (MD 5020 bits 3-0)";
  EXPECT_FALSE(has(with("N3960=0\n", ""), "alarm 2203"));
  EXPECT_TRUE(has(with("", "R21=0\n"), "R21"));
  EXPECT_TRUE(has(with("N2120=50\n", ""), "alarm 112*"));
  EXPECT_TRUE(has(with("N2000=1400\n", ""), "MD2000"));
  EXPECT_TRUE(has(with("N5002=00010001\n", ""), "only measuring system 0.5"));
  EXPECT_TRUE(has(with("N5020=00010001\n", ""), "two different declared axes"));
  EXPECT_TRUE(has(with("", "N8000=5\n"), "SD8000 does not exist")) << "service data are not setting data";
}

TEST_F(Elg, TapeFormatErrors) {
  auto r = parser_->parse("%TEA1\nN5002=0010\nN3960=1234567890\nN9999=1\nX12\n%XYZ\nN169=20\n" + std::string(300, ' ') +
                          "N1=1\n");
  ASSERT_GE(r.problems.size(), 6u);
  EXPECT_NE(r.problems[0].message.find("alarm 32"), std::string::npos);
  EXPECT_NE(r.problems[1].message.find("alarm 32"), std::string::npos);
  EXPECT_NE(r.problems[2].message.find("alarm 3018"), std::string::npos);
  EXPECT_NE(r.problems[3].message.find("alarm 32"), std::string::npos);
  EXPECT_NE(r.problems[4].message.find("unknown tape identification"), std::string::npos);
  EXPECT_NE(r.problems[5].message.find("outside a %TEA1"), std::string::npos);
  EXPECT_NE(r.problems[6].message.find("alarm 29"), std::string::npos);
  EXPECT_FALSE(parser_->parse("no tape here").problems.empty());
  // block parity (optional): "%SEA" + LF is 5 characters
  auto p = parser_->parse("%SEA\nN5010=00000000\nM02\n", {{"block_parity", 1.0L}});
  EXPECT_FALSE(p.problems.empty());
  EXPECT_TRUE(parser_->parse("%SEA\nN5010=00000000\nM02\n").problems.empty());
}

TEST_F(Elg, Sd5016MappingIsConfigurable) {
  const auto ref = *profile_->resolve("SD5016");
  hp::ParameterSet empty;
  const hp::Scope a(*profile_, &empty, {});
  const hp::Scope b(*profile_, &empty, {{"sd5016_map", std::string("12.2")}});
  const auto* va = hp::select_variant(ref, a);
  const auto* vb = hp::select_variant(ref, b);
  ASSERT_TRUE(va && vb);
  EXPECT_NE(va, vb);
  EXPECT_EQ(va->fields[0].bits.fields[0].name, "no_trailer");
  EXPECT_EQ(va->fields[0].bits.fields[0].first, 1u);
  EXPECT_EQ(vb->fields[0].bits.fields[0].first, 0u);
}

TEST_F(Elg, AlarmCatalogue) {
  const auto* a = profile_->catalogue("alarms");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->find(2215)->reaction, hp::Reaction::drive_off);
  EXPECT_EQ(a->find(1321)->reaction, hp::Reaction::needs_reset);
  EXPECT_EQ(a->find(1321)->group, "reset alarm, axis 2");
  EXPECT_EQ(a->find(2200)->acknowledge, "POWER ON RESET only");
  EXPECT_EQ(a->find(29)->text, "BLOCK TOO LONG (MAX. 254 CHARACTERS) V.24");
  EXPECT_EQ(a->find(3016)->reaction, hp::Reaction::message);
  EXPECT_TRUE(a->find(1040) && a->find(1043) && a->find(1843));
  EXPECT_EQ(a->find(1000), nullptr);
}
