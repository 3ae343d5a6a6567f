// SPDX-License-Identifier: MIT
// Every shipped profile loads, its catalogues are complete, its defaults are valid and survive a
// wire round trip; the loader reports bad YAML with file, line and key.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "hil/profiles/loader.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/validation.hpp"
#include "hil/profiles/wire.hpp"

namespace hp = hil::profiles;

TEST(Loader, FindsTheShippedProfiles) {
  const auto names = hp::list_profiles();
  for (const char* d : {"clm14"}) EXPECT_NE(std::find(names.begin(), names.end(), d), names.end()) << d;
  auto p = hp::find_profile("clm14");
  ASSERT_TRUE(p) << p.error().describe();
  auto again = hp::find_profile("clm14");
  EXPECT_EQ(p->get(), again->get()) << "profiles are cached so error categories stay unique";
  auto missing = hp::find_profile("no-such-device");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("HILBRIDGE_PROFILES"), std::string::npos);
}

class EveryProfile : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryProfile, LoadsWithParametersAndCatalogues) {
  auto p = hp::find_profile(GetParam());
  ASSERT_TRUE(p) << p.error().describe();
  EXPECT_FALSE((*p)->parameters.empty());
  EXPECT_FALSE((*p)->catalogues.empty());
  EXPECT_FALSE((*p)->title.empty());
  EXPECT_TRUE(hp::make_parameter_set_parser(*p)) << "no parser for text_format " << (*p)->text_format;
}

// Completeness: every code has a text, a reaction and an acknowledgement, and its error_code
// message names it.
TEST_P(EveryProfile, CataloguesAreComplete) {
  auto p = hp::find_profile(GetParam());
  ASSERT_TRUE(p);
  for (const auto& c : (*p)->catalogues) {
    EXPECT_FALSE(c->entries().empty()) << c->id();
    EXPECT_EQ(std::string(c->category().name()), (*p)->device + "." + c->id());
    for (const auto& e : c->entries()) {
      SCOPED_TRACE(c->id() + " " + e.code_text);
      EXPECT_FALSE(e.text.empty());
      EXPECT_FALSE(e.acknowledge.empty());
      EXPECT_FALSE(e.code_text.empty());
      EXPECT_NE(hp::to_string(e.reaction), "?");
      const auto ec = c->make_error_code(e.code);
      EXPECT_NE(ec.message().find(e.text), std::string::npos);
      EXPECT_EQ(c->parse_code(e.code_text), e.code);
      const auto fault = c->make_fault(e.code, "test");
      if (e.code != 0) {
        EXPECT_TRUE(fault) << "code 0 is std::error_code's 'no error'";
        EXPECT_NE(fault.describe().find((*p)->device), std::string::npos);
      }
    }
  }
}

// Defaults are valid, and every default value encodes to its wire form and decodes back.
TEST_P(EveryProfile, DefaultsAreValidAndRoundTrip) {
  auto p = hp::find_profile(GetParam());
  ASSERT_TRUE(p);
  const auto& prof = **p;
  const auto set = hp::default_set(prof);
  EXPECT_FALSE(set.entries.empty());
  for (const auto& problem : hp::validate(prof, set)) {
    if (problem.rule.starts_with("required")) continue;  // parameters without a default value
    ADD_FAILURE() << problem.describe();
  }
  const hp::Scope scope(prof, &set, {});
  for (const auto& e : set.entries) {
    SCOPED_TRACE(e.ref.id());
    const auto* v = hp::select_variant(e.ref, scope);
    ASSERT_TRUE(v);
    auto img = hp::encode_value(prof, *v, e.value);
    ASSERT_TRUE(img) << img.error();
    auto back = hp::decode_wire(prof, *v, img->bcd ? "BCD " + img->text : img->text);
    ASSERT_TRUE(back) << back.error() << " from '" << img->text << "'";
    ASSERT_EQ(back->size(), e.value.size());
    for (std::size_t i = 0; i < e.value.size(); ++i) EXPECT_EQ(hp::to_string((*back)[i]), hp::to_string(e.value[i]));
  }
  // the device's own text format round-trips the defaults
  auto parser = hp::make_parameter_set_parser(*p);
  ASSERT_TRUE(parser);
  const auto text = parser->write(set);
  const auto parsed = parser->parse(text);
  for (const auto& pr : parsed.problems) ADD_FAILURE() << pr.describe();
  EXPECT_EQ(parsed.set.entries.size(), set.entries.size());
  EXPECT_EQ(parser->write(parsed.set), text);
}

INSTANTIATE_TEST_SUITE_P(Shipped, EveryProfile, ::testing::ValuesIn(hp::list_profiles()));

TEST(Loader, ReportsFileLineAndKey) {
  auto r = hp::load_profile_text(
      "device: x\nparameters:\n  - id: P1\n    fields:\n      - {name: a, format: \"x.3\"}\n", "bad.yaml");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().file, "bad.yaml");
  EXPECT_EQ(r.error().line, 5);
  EXPECT_EQ(r.error().key, "parameters[0].fields[0].format");
  auto no_reaction = hp::load_profile_text(
      "device: x\ncatalogues:\n  - id: e\n    entries:\n      - {code: '1', text: t, acknowledge: a}\n", "e.yaml");
  ASSERT_FALSE(no_reaction);
  EXPECT_NE(no_reaction.error().message.find("reaction"), std::string::npos);
  auto dup = hp::load_profile_text("device: x\nparameters:\n  - {id: P1, range: [0, 1]}\n  - {id: p1, range: [0, 1]}\n",
                                   "d.yaml");
  ASSERT_FALSE(dup);
  EXPECT_NE(dup.error().message.find("twice"), std::string::npos);
  auto bad_expr = hp::load_profile_text("device: x\nconstraints:\n  - {id: c, rule: 'a <'}\n", "c.yaml");
  ASSERT_FALSE(bad_expr);
  EXPECT_EQ(bad_expr.error().line, 3);
  auto yaml = hp::load_profile_text("device: [x\n", "y.yaml");
  ASSERT_FALSE(yaml);
  EXPECT_GT(yaml.error().line, 0);
}

TEST(Loader, IncludesAreMerged) {
  const auto dir = std::filesystem::temp_directory_path() / "hil_profiles_include_test";
  std::filesystem::create_directories(dir / "part");
  std::ofstream(dir / "dev.yaml") << "device: dev\ntext_format: wf-md\ninclude: [part/a.yaml]\nparameters:\n  - {id: "
                                     "MD1, number: 1, range: [0, 10]}\n";
  std::ofstream(dir / "part" / "a.yaml") << "device: dev\nparameters:\n  - {id: MD2, number: 2, range: [0, 10]}\n";
  auto p = hp::load_profile(dir / "dev.yaml");
  ASSERT_TRUE(p) << p.error().describe();
  EXPECT_TRUE((*p)->resolve("MD 2"));
  std::ofstream(dir / "part" / "a.yaml") << "device: other\n";
  auto wrong = hp::load_profile(dir / "dev.yaml");
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.error().message.find("other"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(Loader, SearchPathHonoursHilbridgeProfiles) {
  const auto dir = std::filesystem::temp_directory_path() / "hil_profiles_env_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "env-only-device.yaml")
      << "device: env-only-device\ntext_format: wf-md\nparameters:\n  - {id: MD1, number: 1, range: [0, 10]}\n"
         "catalogues:\n  - id: e\n    entries:\n      - {code: '1', text: t, reaction: stop, acknowledge: a}\n";
  const char* old = std::getenv("HILBRIDGE_PROFILES");
  const std::string saved = old ? old : "";
  ::setenv("HILBRIDGE_PROFILES", dir.c_str(), 1);
  EXPECT_EQ(hp::profile_search_path().front(), std::filesystem::weakly_canonical(dir));
  const auto names = hp::list_profiles();
  EXPECT_NE(std::find(names.begin(), names.end(), "env-only-device"), names.end());
  auto p = hp::find_profile("env-only-device");
  ASSERT_TRUE(p) << p.error().describe();
  EXPECT_EQ((*p)->catalogue("e")->category().name(), std::string("env-only-device.e"));
  if (old)
    ::setenv("HILBRIDGE_PROFILES", saved.c_str(), 1);
  else
    ::unsetenv("HILBRIDGE_PROFILES");
  std::filesystem::remove_all(dir);
}
