// SPDX-License-Identifier: MIT
// The verifier finds each rule's violation at the right edge; the edge-log codec round-trips and
// rejects bad input with line/column.
#include <gtest/gtest.h>

#include "hil/stepdir/edge_log.hpp"
#include "hil/stepdir/verifier.hpp"

using namespace hil::stepdir;
using hil::gpio::Edge;

namespace {

StepTiming rules() {
  StepTiming t;
  t.step_len_ns = 2'000;
  t.step_space_ns = 2'000;
  t.dir_setup_ns = 5'000;
  t.dir_hold_ns = 3'000;
  t.max_freq_hz = 100'000;  // 10 us
  return t;
}

std::optional<Violation> check(std::vector<Edge> e, std::optional<std::int64_t> n = std::nullopt) {
  return verify_edges(e, rules(), n);
}

}  // namespace

TEST(StepVerifier, CleanStreamPasses) {
  VerifyStats st;
  const std::vector<Edge> e = {{0, 0, true},       {2'000, 0, false}, {10'000, 0, true}, {12'000, 0, false},
                               {15'000, 1, false}, {20'000, 0, true}, {22'000, 0, false}};
  auto v = verify_edges(e, rules(), 1, {}, &st);
  EXPECT_FALSE(v) << v->describe();
  EXPECT_EQ(st.steps_forward, 2);
  EXPECT_EQ(st.steps_backward, 1);
  EXPECT_EQ(st.min_period_ns, 10'000);
}

TEST(StepVerifier, FindsEachRule) {
  struct Case {
    std::vector<Edge> edges;
    Rule rule;
    std::size_t index;
  };
  const std::vector<Case> cases = {
      {{{0, 0, true}, {1'999, 0, false}}, Rule::pulse_width, 1},
      {{{0, 0, true}, {2'000, 0, false}, {3'000, 0, true}}, Rule::step_space, 2},
      {{{0, 0, true}, {2'000, 0, false}, {9'999, 0, true}}, Rule::max_frequency, 2},
      {{{0, 0, true}, {2'000, 0, false}, {8'000, 1, false}, {12'999, 0, true}}, Rule::dir_setup, 3},
      {{{0, 0, true}, {2'000, 0, false}, {4'999, 1, false}}, Rule::dir_hold, 2},
      {{{0, 0, true}, {1'000, 1, false}}, Rule::dir_during_pulse, 1},
      {{{0, 0, true}, {2'000, 0, true}}, Rule::redundant_edge, 1},
      {{{5, 0, true}, {4, 0, false}}, Rule::time_order, 1},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    auto v = check(cases[i].edges);
    ASSERT_TRUE(v) << "case " << i;
    EXPECT_EQ(v->rule, cases[i].rule) << "case " << i << ": " << v->describe();
    EXPECT_EQ(v->index, cases[i].index) << "case " << i;
  }
}

TEST(StepVerifier, StepCountMismatch) {
  auto v = check({{0, 0, true}, {2'000, 0, false}}, 2);
  ASSERT_TRUE(v);
  EXPECT_EQ(v->rule, Rule::step_count);
  EXPECT_EQ(v->measured, 1);
  EXPECT_EQ(v->limit, 2);
  EXPECT_NE(v->describe().find("expected 2"), std::string::npos);
}

TEST(StepVerifier, NegativePolarityCountsFallingEdges) {
  StepTiming t = rules();
  t.polarity = Polarity::negative_edge;
  t.dir_forward_level = false;
  StepVerifier v(t, {}, 1);
  v.feed(std::vector<Edge>{{0, 0, false}, {2'000, 0, true}});
  EXPECT_TRUE(v.ok());
  EXPECT_EQ(v.stats().steps_forward, 1);
  StepVerifier w(t);
  w.feed(std::vector<Edge>{{0, 0, true}});  // idle is high: a rising edge is redundant
  ASSERT_FALSE(w.ok());
  EXPECT_EQ(w.first_violation()->rule, Rule::redundant_edge);
}

TEST(EdgeLog, RoundTrip) {
  std::vector<Edge> e = {{0, 0, true}, {2'000, 0, false}, {3'000, 1, true}, {4'000, 2, true}, {5'000, 17, false}};
  auto text = format_edge_log(e);
  auto back = parse_edge_log(text);
  ASSERT_TRUE(back) << back.error().describe();
  EXPECT_EQ(*back, e);
}

TEST(EdgeLog, CommentsAndBlankLines) {
  auto r = parse_edge_log("# header\n\n  10 step 1 # rising\n\t20 step 0\r\n");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->size(), 2U);
  EXPECT_EQ((*r)[1].t_ns, 20);
}

TEST(EdgeLog, ErrorsNameLineAndColumn) {
  auto r = parse_edge_log("10 step 1\n20 step 2\n");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().line, 2U);
  EXPECT_EQ(r.error().column, 9U);
  EXPECT_NE(r.error().describe().find("level must be 0 or 1"), std::string::npos);
  EXPECT_FALSE(parse_edge_log("x step 1"));
  EXPECT_FALSE(parse_edge_log("1 foo 1"));
  EXPECT_FALSE(parse_edge_log("1 70000 1"));
  EXPECT_FALSE(parse_edge_log("1 step"));
  EXPECT_FALSE(parse_edge_log("1 step 1 extra"));
  EXPECT_FALSE(parse_edge_log("99999999999999999999 step 1"));
  // Times the verifier could not subtract without signed overflow (UBSan report before).
  EXPECT_FALSE(parse_edge_log("-9223372036854775808 step 1\n9223372036854775807 step 0\n"));
  EXPECT_FALSE(parse_edge_log("-1 step 1"));
  EXPECT_TRUE(parse_edge_log("4611686018427387904 step 1"));
}
