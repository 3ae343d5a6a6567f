// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <map>

#include "hil/profiles/expression.hpp"

namespace hp = hil::profiles;

namespace {

hp::Expression::Lookup table(std::map<std::string, hp::ExprValue, std::less<>> m) {
  return [m = std::move(m)](std::string_view n) -> std::optional<hp::ExprValue> {
    if (auto it = m.find(n); it != m.end()) return it->second;
    return std::nullopt;
  };
}

bool test(std::string_view e, const hp::Expression::Lookup& l) {
  auto x = hp::Expression::parse(e);
  EXPECT_TRUE(x) << e << ": " << (x ? "" : x.error());
  auto r = x->test(l);
  EXPECT_TRUE(r) << e << ": " << (r ? "" : r.error().message);
  return r && *r;
}

}  // namespace

TEST(Expression, ChainedComparisonWf725Limits) {
  // MD 12 < MD 11 < MD 13 < MD 14 with the manual's example values
  auto ok = table({{"MD11", -24537.0L}, {"MD12", -42728.0L}, {"MD13", 96417.0L}, {"MD14", 137428.0L}});
  EXPECT_TRUE(test("MD12 < MD11 < MD13 < MD14", ok));
  auto bad = table({{"MD11", -50000.0L}, {"MD12", -42728.0L}, {"MD13", 96417.0L}, {"MD14", 137428.0L}});
  EXPECT_FALSE(test("MD12 < MD11 < MD13 < MD14", bad));
}

TEST(Expression, ArithmeticFunctionsAndStrings) {
  auto l =
      table({{"Ax12.rpm", 3000.0L}, {"Ax01", 10.0L}, {"Ax06", 100.0L}, {"encoder", std::string("I")}, {"n", 8.0L}});
  EXPECT_TRUE(test("Ax06 <= Ax12.rpm / 60 * Ax01", l));
  EXPECT_TRUE(test("encoder == 'I' && not (encoder == 'A')", l));
  EXPECT_TRUE(test("n in [1, 2, 4, 8]", l));
  EXPECT_FALSE(test("n in [1, 2, 4]", l));
  EXPECT_TRUE(test("pow2(n) and !pow2(6)", l));
  EXPECT_TRUE(test("if(encoder == 'I', 1, 0) == 1", l));
  EXPECT_TRUE(test("abs(-3) == 3 && min(2, 5) == 2 && max(2, 5) == 5 && 7 % 4 == 3", l));
  EXPECT_TRUE(test("digit(2120, 1) == 2 && digit(2120, 0) == 0 && bit(5, 2) == 1", l));
  EXPECT_TRUE(test("defined(n) && !defined(zz)", l));
  EXPECT_TRUE(test("-n + 2 * 3 == -2", l));
}

TEST(Expression, ErrorsAreReported) {
  EXPECT_FALSE(hp::Expression::parse("1 +"));
  EXPECT_FALSE(hp::Expression::parse("(1"));
  EXPECT_FALSE(hp::Expression::parse("foo(1)"));
  EXPECT_FALSE(hp::Expression::parse("if(1, 2)"));
  EXPECT_FALSE(hp::Expression::parse("'open"));
  EXPECT_FALSE(hp::Expression::parse("1 $ 2"));
  EXPECT_FALSE(hp::Expression::parse(std::string(200, '(') + "1" + std::string(200, ')')));
  auto e = *hp::Expression::parse("MD3 / MD4 > 1");
  auto r = e.evaluate(table({{"MD3", 1.0L}, {"MD4", 0.0L}}));
  ASSERT_FALSE(r);
  EXPECT_FALSE(r.error().undefined);
  auto u = e.evaluate(table({}));
  ASSERT_FALSE(u);
  EXPECT_TRUE(u.error().undefined);
  EXPECT_EQ(e.names(), (std::vector<std::string>{"MD3", "MD4"}));
}
