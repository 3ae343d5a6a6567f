// SPDX-License-Identifier: MIT
// Run outputs: trace CSV contents, SVG plot parsed back as XML, JUnit XML structure.
#include <expat.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "hil/runtime/junit.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "hil/runtime/svg_plot.hpp"
#include "hil/runtime/trace_csv.hpp"
#include "sim_registry.hpp"

using namespace std::chrono_literals;
using namespace hil::runtime;

namespace {

const std::string two_axes =
    "name: outputs\n"
    "machine:\n"
    "  axes:\n"
    "    - name: x\n"
    "      inc_per_unit: 1000\n"
    "      limits: {velocity: 100, acceleration: 1000, jerk: 10000}\n"
    "      supervision: {following_error: 1.0, in_position: 0.01}\n"
    "      drive: {transport: sim, kv: 80, feedforward: 1.0}\n"
    "    - name: c\n"
    "      rotary: true\n"
    "      inc_per_unit: 100\n"
    "      limits: {velocity: 360, acceleration: 3600}\n"
    "      supervision: {following_error: 2.0, in_position: 0.02}\n"
    "      drive: {transport: sim, kv: 60, feedforward: 1.0}\n"
    "program:\n"
    "  - enable: all\n"
    "  - parallel:\n"
    "      - move_absolute: {axis: x, position: 50}\n"
    "      - move_absolute: {axis: c, position: 90}\n";

/// A parsed XML element tree (expat), enough to check structure.
struct Element {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::vector<Element> children;
  std::string text;
};

struct XmlParse {
  Element root;
  std::vector<Element*> stack;
  bool ok = false;
  std::string error;
};

XmlParse parse_xml(const std::string& doc) {
  XmlParse p;
  XML_Parser parser = XML_ParserCreate("UTF-8");
  XML_SetUserData(parser, &p);
  XML_SetElementHandler(
      parser,
      [](void* ud, const XML_Char* name, const XML_Char** atts) {
        auto& s = *static_cast<XmlParse*>(ud);
        Element e;
        e.name = name;
        for (int i = 0; atts[i]; i += 2) e.attrs[atts[i]] = atts[i + 1];
        if (s.stack.empty()) {
          s.root = std::move(e);
          s.stack.push_back(&s.root);
        } else {
          s.stack.back()->children.push_back(std::move(e));
          s.stack.push_back(&s.stack.back()->children.back());
        }
      },
      [](void* ud, const XML_Char*) { static_cast<XmlParse*>(ud)->stack.pop_back(); });
  XML_SetCharacterDataHandler(parser, [](void* ud, const XML_Char* s, int len) {
    auto& p2 = *static_cast<XmlParse*>(ud);
    if (!p2.stack.empty()) p2.stack.back()->text.append(s, static_cast<std::size_t>(len));
  });
  p.ok = XML_Parse(parser, doc.data(), static_cast<int>(doc.size()), 1) == XML_STATUS_OK;
  if (!p.ok)
    p.error = std::string(XML_ErrorString(XML_GetErrorCode(parser))) + " at line " +
              std::to_string(XML_GetCurrentLineNumber(parser));
  XML_ParserFree(parser);
  return p;
}

void collect(const Element& e, const std::string& name, std::vector<const Element*>& out) {
  if (e.name == name) out.push_back(&e);
  for (const auto& c : e.children) collect(c, name, out);
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(line);
  while (std::getline(in, cur, sep)) out.push_back(cur);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

}  // namespace

TEST(TraceCsv, HeaderQuotesAUnitWithACommaOrQuote) {
  std::string yaml = two_axes;
  yaml.replace(yaml.find("      inc_per_unit: 1000\n"), 0, "      units: \"m,\\\"m\"\n");
  auto s = parse_scenario(yaml, "t.yaml");
  ASSERT_TRUE(s.has_value()) << s.error().describe();
  const auto path = std::filesystem::temp_directory_path() / "hil_runtime_trace_quote_test.csv";
  TraceCsvWriter trace;
  ASSERT_FALSE(trace.open(path));
  RunOptions o;
  o.observers.push_back(&trace);
  ASSERT_TRUE(run_scenario(*s, hil::testing::sim_registry(), o).has_value());
  ASSERT_FALSE(trace.close());
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(
      header.substr(0, header.find(",x_state")),
      "t_s,\"x_position_m,\"\"m\",\"x_command_m,\"\"m\",\"x_velocity_m,\"\"m_per_s\",\"x_following_error_m,\"\"m\"");
  std::filesystem::remove(path);
}

TEST(TraceCsv, OneRowPerCycleWithEveryAxisColumn) {
  auto s = parse_scenario(two_axes, "t.yaml");
  ASSERT_TRUE(s.has_value()) << s.error().describe();
  const auto path = std::filesystem::temp_directory_path() / "hil_runtime_trace_test.csv";
  TraceCsvWriter trace;
  ASSERT_FALSE(trace.open(path));
  RunOptions o;
  o.observers.push_back(&trace);
  auto r = run_scenario(*s, hil::testing::sim_registry(), o);
  ASSERT_TRUE(r.has_value());
  ASSERT_TRUE(r->ok);
  ASSERT_FALSE(trace.close());

  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header,
            "t_s,x_position_mm,x_command_mm,x_velocity_mm_per_s,x_following_error_mm,x_state,x_fault,"
            "c_position_deg,c_command_deg,c_velocity_deg_per_s,c_following_error_deg,c_state,c_fault");
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(split(line, ','));
  ASSERT_EQ(rows.size(), r->scheduler.cycles);
  EXPECT_EQ(trace.rows(), r->scheduler.cycles);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 13u) << "row " << i;
    EXPECT_NEAR(std::stod(rows[i][0]), static_cast<double>(i) * 0.001, 1e-9);
  }
  EXPECT_EQ(rows.front()[5], "disabled");  // enable is commanded after the first cycle
  EXPECT_NEAR(std::stod(rows.back()[1]), 50.0, 0.01);
  EXPECT_NEAR(std::stod(rows.back()[7]), 90.0, 0.02);
  EXPECT_EQ(rows.back()[5], "standstill");
  EXPECT_EQ(rows.back()[6], "");
  // Somewhere in the middle x moves at speed.
  double vmax = 0;
  for (const auto& row : rows) vmax = std::max(vmax, std::stod(row[3]));
  EXPECT_GT(vmax, 90.0);
  std::filesystem::remove(path);
}

TEST(SvgPlot, WellFormedWithAxesTicksLabelsAndLegend) {
  auto s = parse_scenario(two_axes, "t.yaml");
  ASSERT_TRUE(s.has_value());
  PlotRecorder plot(500);  // small cap: exercises decimation
  RunOptions o;
  o.observers.push_back(&plot);
  auto r = run_scenario(*s, hil::testing::sim_registry(), o);
  ASSERT_TRUE(r.has_value());
  ASSERT_EQ(plot.data().axes.size(), 2u);
  EXPECT_LT(plot.data().axes[0].t.size(), 500u);
  EXPECT_GT(plot.data().axes[0].t.size(), 200u);

  const std::string svg = render_svg(plot.data());
  const XmlParse p = parse_xml(svg);
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.root.name, "svg");
  EXPECT_EQ(p.root.attrs.at("xmlns"), "http://www.w3.org/2000/svg");
  std::vector<const Element*> charts, polylines, texts;
  collect(p.root, "g", charts);
  collect(p.root, "polyline", polylines);
  collect(p.root, "text", texts);
  EXPECT_EQ(charts.size(), 6u);     // 3 charts per axis
  EXPECT_EQ(polylines.size(), 8u);  // position (actual + command), velocity, following error
  for (const auto* pl : polylines) EXPECT_GT(split(pl->attrs.at("points"), ' ').size(), 100u);
  std::string all;
  for (const auto* t : texts) all += t->text + "|";
  for (const char* want : {"x: position [mm]", "x: velocity [mm/s]", "x: following error [mm]", "c: position [deg]",
                           "t [s]", "actual", "command", "hilbridge run: outputs"})
    EXPECT_NE(all.find(want), std::string::npos) << want;
  EXPECT_NE(all.find("|50|"), std::string::npos) << "a y tick at 50 mm";

  const auto ticks = nice_ticks(-0.3, 101.2, 5);
  ASSERT_FALSE(ticks.empty());
  EXPECT_DOUBLE_EQ(ticks.front(), 0.0);
  EXPECT_DOUBLE_EQ(ticks[1], 50.0);  // 101.5 / 5 = 20.3 -> next nice step 50
  EXPECT_DOUBLE_EQ(ticks.back(), 100.0);
}

TEST(JUnit, StructureCountsAndMessages) {
  RunResult pass;
  pass.scenario = "good";
  pass.file = "good.yaml";
  pass.expectations.push_back({"x", "no fault", true, "", 3, "expect[0]"});
  RunResult fail;
  fail.scenario = "bad <&>";
  fail.file = "bad.yaml";
  fail.ok = false;
  fail.expectations.push_back(
      {"x", "position 100.000 +/- 0.010 mm at t=2.000 s", false, "was 99.412 mm (off by 0.588 mm)", 12, "expect[1]"});
  fail.expectations.push_back({"x", "no fault", true, "", 13, "expect[2]"});
  fail.failures = {"axis x: expected position 100.000 +/- 0.010 mm at t=2.000 s, was 99.412 mm (off by 0.588 mm)",
                   "program failed: t=1.000 s: bad.yaml:9 program[1] (move_absolute x): did not complete"};
  std::vector<ScenarioOutcome> outcomes;
  outcomes.push_back({"good.yaml", pass, "", 0.01});
  outcomes.push_back({"bad.yaml", fail, "", 0.02});
  outcomes.push_back({"broken.yaml", std::nullopt, "broken.yaml:3:1: machine: missing key 'machine'", 0.0});

  const XmlParse p = parse_xml(make_junit_xml(outcomes));
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.root.name, "testsuites");
  EXPECT_EQ(p.root.attrs.at("tests"), "6");
  EXPECT_EQ(p.root.attrs.at("failures"), "2");
  EXPECT_EQ(p.root.attrs.at("errors"), "1");
  ASSERT_EQ(p.root.children.size(), 3u);
  const Element& good = p.root.children[0];
  EXPECT_EQ(good.attrs.at("name"), "good");
  EXPECT_EQ(good.attrs.at("failures"), "0");
  const Element& bad = p.root.children[1];
  EXPECT_EQ(bad.attrs.at("name"), "bad <&>");
  EXPECT_EQ(bad.attrs.at("tests"), "3");
  EXPECT_EQ(bad.attrs.at("failures"), "2");
  std::vector<const Element*> failures;
  collect(bad, "failure", failures);
  ASSERT_EQ(failures.size(), 2u);
  EXPECT_EQ(failures[0]->attrs.at("message"),
            "axis x: expected position 100.000 +/- 0.010 mm at t=2.000 s, was 99.412 mm (off by 0.588 mm)");
  EXPECT_NE(failures[0]->text.find("bad.yaml:12 expect[1]"), std::string::npos);
  EXPECT_NE(failures[1]->attrs.at("message").find("program failed"), std::string::npos);
  const Element& broken = p.root.children[2];
  std::vector<const Element*> errors;
  collect(broken, "error", errors);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0]->attrs.at("type"), "ConfigError");
}

TEST(SvgPlot, RotaryPositionBreaksAtTheWrap) {
  PlotData d;
  d.title = "wrap";
  PlotSeries s;
  s.axis = "c";
  s.units = "deg";
  s.rotary = true;
  for (int i = 0; i < 100; ++i) {  // 300 -> 359 then 0 -> 40 deg
    const double p = std::fmod(300.0 + i, 360.0);
    s.t.push_back(i * 0.01);
    s.position.push_back(p);
    s.command.push_back(p);
    s.velocity.push_back(100.0);
    s.following_error.push_back(0.0);
  }
  d.axes.push_back(s);
  const XmlParse p = parse_xml(render_svg(d));
  ASSERT_TRUE(p.ok) << p.error;
  std::vector<const Element*> polylines;
  collect(p.root, "polyline", polylines);
  EXPECT_EQ(polylines.size(), 6u);  // actual and command in two pieces each, velocity, following error
}
