// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include "hil/config/yaml_config.hpp"

using hil::yaml::Where;

TEST(YamlConfig, UnknownKeyNamesLineAndAllowedKeys) {
  auto doc = hil::yaml::load_string("axis:\n  kv: 30\n  kvv: 4\n", "m.yaml");
  ASSERT_TRUE(doc);
  auto r = hil::yaml::check_keys((*doc)["axis"], Where{"m.yaml", "axis"}, {"kv", "lag"});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().line, 3);
  EXPECT_EQ(r.error().key, "axis.kvv");
  EXPECT_NE(r.error().message.find("unknown key 'kvv'; allowed here: kv, lag"), std::string::npos);
}

TEST(YamlConfig, KeyGivenTwiceIsRefused) {
  auto doc = hil::yaml::load_string("axis:\n  kv: 30\n  kv: 4\n", "m.yaml");
  ASSERT_TRUE(doc);
  auto r = hil::yaml::check_keys((*doc)["axis"], Where{"m.yaml", "axis"}, {"kv", "lag"});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().describe(), "m.yaml:3:3: axis.kv: key 'kv' appears twice");
}

TEST(YamlConfig, TypedGetReportsBadValue) {
  auto doc = hil::yaml::load_string("kv: fast\nn: 3\n", "m.yaml");
  ASSERT_TRUE(doc);
  auto kv = hil::yaml::get_double(*doc, Where{"m.yaml", ""}, "kv");
  ASSERT_FALSE(kv);
  EXPECT_EQ(kv.error().describe(), "m.yaml:1:5: kv: expected a number, got 'fast'");
  auto n = hil::yaml::get_int(*doc, Where{"m.yaml", ""}, "n");
  ASSERT_TRUE(n);
  EXPECT_EQ(n->value(), 3);
  auto missing = hil::yaml::get_int(*doc, Where{"m.yaml", ""}, "absent");
  ASSERT_TRUE(missing);
  EXPECT_FALSE(missing->has_value());
}

TEST(YamlConfig, SyntaxErrorHasLine) {
  auto doc = hil::yaml::load_string("a: [1, 2\nb: 3\n", "bad.yaml");
  ASSERT_FALSE(doc);
  EXPECT_EQ(doc.error().file, "bad.yaml");
  EXPECT_GT(doc.error().line, 0);
}

TEST(YamlConfig, MissingFile) {
  auto doc = hil::yaml::load_file("/nonexistent/x.yaml");
  ASSERT_FALSE(doc);
  EXPECT_NE(doc.error().describe().find("cannot open"), std::string::npos);
}
