// SPDX-License-Identifier: MIT
// hil::yaml::Field: the checked cursor of the scenario loader, on hil::yaml's Where and error_at.
#include <chrono>

#include <gtest/gtest.h>

#include "hil/config/yaml_field.hpp"

using hil::yaml::Field;
using hil::yaml::Where;
using namespace std::chrono_literals;

namespace {

hil::ConfigError failure_of(const auto& read) {
  try {
    read();
  } catch (const hil::yaml::Failure& f) {
    return f.error;
  }
  ADD_FAILURE() << "no hil::yaml::Failure thrown";
  return {};
}

Field top(const YAML::Node& root) {
  return Field(root, Where{"m.yaml", ""}, YAML::Mark{});
}

}  // namespace

TEST(YamlField, MissingKeyBlamesTheParentWithTheKeyPath) {
  const YAML::Node root = YAML::Load("axes:\n  - name: x\n    kv: 3\n");
  const auto e =
      failure_of([&] { (void)top(root).required("axes", "the axes").items()[0].required("drive", "a drive block"); });
  EXPECT_EQ(e.describe(), "m.yaml:2:5: axes[0].drive: missing key 'drive' (a drive block)");
}

TEST(YamlField, ErrorOfAPresentNodeIsErrorAt) {
  const YAML::Node root = YAML::Load("axis:\n  kv: fast\n");
  const Field kv = top(root).child("axis").child("kv");
  const auto via_field = kv.error("expected a number");
  const auto via_error_at = hil::yaml::error_at(root["axis"]["kv"], Where{"m.yaml", "axis.kv"}, "expected a number");
  EXPECT_EQ(via_field.describe(), via_error_at.describe());
  EXPECT_EQ(via_field.describe(), "m.yaml:2:7: axis.kv: expected a number");
  EXPECT_EQ(failure_of([&] { (void)kv.as_number("the gain"); }).message, "expected the gain, got 'fast'");
}

TEST(YamlField, DurationsUseTheOneGrammar) {
  const YAML::Node root = YAML::Load("a: 250ms\nb: 2\nc: 30us\nd: soon\n");
  EXPECT_EQ(top(root).child("a").as_duration(), 250ms);
  EXPECT_EQ(top(root).child("b").as_duration(), 2s);
  EXPECT_EQ(top(root).child("c").as_duration(), 30us);
  EXPECT_FALSE(top(root).optional_duration("absent").has_value());
  const auto e = failure_of([&] { (void)top(root).child("d").as_duration(); });
  EXPECT_EQ(e.describe(), "m.yaml:4:4: d: expected a duration (seconds, or '250ms', '2s'; 0 .. 10 days), got 'soon'");
}

TEST(YamlField, ExpectMapRejectsUnknownAndDuplicateKeys) {
  const YAML::Node unknown = YAML::Load("axis:\n  kv: 1\n  kvv: 2\n");
  EXPECT_EQ(failure_of([&] {
              (void)top(unknown).child("axis").expect_map({"kv", "lag"});
            }).describe(),
            "m.yaml:3:3: axis.kvv: unknown key 'kvv'; allowed here: kv, lag");
  const YAML::Node twice = YAML::Load("axis:\n  kv: 1\n  kv: 2\n");
  EXPECT_EQ(failure_of([&] { (void)top(twice).child("axis").expect_map({"kv"}); }).describe(),
            "m.yaml:3:3: axis.kv: key 'kv' appears twice");
  const YAML::Node good = YAML::Load("axis: {kv: 1}\n");
  EXPECT_EQ(top(good).child("axis").expect_map({"kv", "lag"}), std::vector<std::string>{"kv"});
}

TEST(YamlField, ReadDocumentTurnsFailuresIntoExpected) {
  const YAML::Node root = YAML::Load("mode: fast\n");
  auto ok = hil::yaml::read_document("m.yaml", [&] { return top(root).child("mode").as_enum({"slow", "fast"}); });
  ASSERT_TRUE(ok);
  EXPECT_EQ(*ok, 1u);
  auto bad = hil::yaml::read_document("m.yaml", [&] { return top(root).child("mode").as_enum({"slow"}); });
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().describe(), "m.yaml:1:7: mode: expected one of: slow; got 'fast'");
}
