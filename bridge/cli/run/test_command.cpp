// SPDX-License-Identifier: MIT
// `hilbridge test FILE|DIR...`: run scenarios on virtual time as fast as possible, print pass/fail
// per scenario and per expectation, write JUnit XML, exit non-zero on any failure.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "hil/cli/context.hpp"
#include "hil/cli/json_output.hpp"
#include "hil/runtime/junit.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"

namespace hil::cli {
namespace {

struct TestArgs {
  std::vector<std::string> paths;
  std::string junit;
  bool verbose = false;
  bool json = false;  ///< the summary as one JSON object on stdout; the PASS/FAIL lines go to stderr
};

/// One scenario of `hilbridge test --json` (docs/json.md).
nlohmann::json outcome_json(const runtime::ScenarioOutcome& o) {
  nlohmann::json j{{"file", o.file}, {"wall_s", o.wall_s}};
  if (!o.result) {
    j["ok"] = false;
    j["error"] = o.error;
    return j;
  }
  const auto& r = *o.result;
  j["scenario"] = r.scenario;
  j["ok"] = r.ok;
  j["simulated_s"] = to_seconds(r.simulated);
  j["failures"] = r.failures;
  j["warnings"] = r.warnings;
  j["cut_off"] =
      r.cut_off ? nlohmann::json{{"reason", *r.cut_off}, {"expected", r.cut_off_expected}} : nlohmann::json(nullptr);
  nlohmann::json expectations = nlohmann::json::array();
  for (const auto& e : r.expectations)
    expectations.push_back({{"axis", e.axis},
                            {"description", e.description},
                            {"passed", e.passed},
                            {"detail", e.detail},
                            {"line", e.line},
                            {"path", e.path}});
  j["expectations"] = std::move(expectations);
  return j;
}

std::vector<std::filesystem::path> collect(const std::vector<std::string>& paths, std::string& error) {
  std::vector<std::filesystem::path> files;
  for (const auto& p : paths) {
    std::error_code ec;
    if (std::filesystem::is_directory(p, ec)) {
      std::vector<std::filesystem::path> found;
      for (const auto& e : std::filesystem::recursive_directory_iterator(p, ec)) {
        const auto ext = e.path().extension();
        if (e.is_regular_file() && (ext == ".yaml" || ext == ".yml")) found.push_back(e.path());
      }
      if (ec) {
        error = fmt::format("cannot read the folder {}: {}", p, ec.message());
        return {};
      }
      std::sort(found.begin(), found.end());
      if (found.empty()) {
        error = fmt::format("no scenario files (*.yaml, *.yml) in {}", p);
        return {};
      }
      files.insert(files.end(), found.begin(), found.end());
    } else if (std::filesystem::is_regular_file(p, ec)) {
      files.emplace_back(p);
    } else {
      error = fmt::format("{}: no such file or folder", p);
      return {};
    }
  }
  return files;
}

int test_command(Context& ctx, const TestArgs& args) {
  std::string error;
  const auto files = collect(args.paths, error);
  if (!error.empty()) return report_error(args.json, "error: ", error, 2);
  // Under --json stdout carries only the JSON summary; what a person reads goes to stderr.
  std::FILE* const out = args.json ? stderr : stdout;
  if (!args.junit.empty()) {
    // Find out now, not after a long suite, that the report cannot be written (append: an
    // existing report stays as it is until the new one replaces it).
    std::ofstream probe(args.junit, std::ios::app);
    if (!probe)
      return report_error(args.json, "error: ",
                          fmt::format("cannot write the JUnit report {}: {}", args.junit, std::strerror(errno)), 2);
  }
  std::vector<runtime::ScenarioOutcome> outcomes;
  std::size_t passed = 0;
  for (const auto& file : files) {
    runtime::ScenarioOutcome o;
    o.file = file.string();
    const auto wall0 = std::chrono::steady_clock::now();
    auto scenario = runtime::load_scenario(file);
    if (scenario) {
      runtime::RunOptions options;
      options.virtual_time = true;
      auto r = runtime::run_scenario(*scenario, ctx.transports, options);
      if (r)
        o.result = std::move(*r);
      else
        o.error = r.error().describe();
    } else {
      o.error = scenario.error().describe();
    }
    o.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (!o.result) {
      fmt::print(out, "ERROR {}\n  {}\n", o.file, o.error);
    } else {
      const auto& r = *o.result;
      fmt::print(out, "{} {} ({}): {:.3f} s simulated in {:.3f} s\n", r.ok ? "PASS " : "FAIL ", r.scenario, o.file,
                 to_seconds(r.simulated), o.wall_s);
      for (const auto& e : r.expectations)
        if (!e.passed || args.verbose)
          fmt::print(out, "  {} {}: {}{}\n", e.passed ? "pass" : "FAIL", e.subject(), e.description,
                     e.passed ? ""
                              : fmt::format("\n       expected {}, {} ({}:{} {})", e.description, e.detail, o.file,
                                            e.line, e.path));
      for (const auto& f : r.failures)
        if ((!f.starts_with("axis ") || f.find(": expected ") == std::string::npos) && !f.starts_with("I/O: expected "))
          fmt::print(out, "  FAIL {}\n", f);  // expectation failures were printed above, with their line
      if (r.cut_off && r.cut_off_expected) fmt::print(out, "  note: {} (cut_off: expected)\n", *r.cut_off);
      for (const auto& w : r.warnings) fmt::print(out, "  warning: {}\n", w);
      if (r.ok) ++passed;
    }
    outcomes.push_back(std::move(o));
  }
  fmt::print(out, "\n{} of {} scenarios passed{}\n", passed, outcomes.size(),
             passed == outcomes.size() ? "" : fmt::format(", {} failed", outcomes.size() - passed));
  if (!args.junit.empty()) {
    std::ofstream xml(args.junit, std::ios::trunc);
    xml << runtime::make_junit_xml(outcomes);
    xml.close();
    if (!xml) return report_error(args.json, "error: ", fmt::format("cannot write the JUnit report {}", args.junit), 2);
    fmt::print(out, "wrote {}\n", args.junit);
  }
  if (args.json) {
    nlohmann::json scenarios = nlohmann::json::array();
    for (const auto& o : outcomes) scenarios.push_back(outcome_json(o));
    print_json({{"ok", passed == outcomes.size()},
                {"total", outcomes.size()},
                {"passed", passed},
                {"failed", outcomes.size() - passed},
                {"junit", args.junit.empty() ? nlohmann::json(nullptr) : nlohmann::json(args.junit)},
                {"scenarios", std::move(scenarios)}});
  }
  return passed == outcomes.size() ? 0 : 1;
}

}  // namespace

void register_test_command(Context& ctx) {
  auto args = std::make_shared<TestArgs>();
  // One line for `hilbridge --help`; the details go to the footer of `hilbridge test --help`.
  auto* test =
      ctx.app.add_subcommand("test", "Run scenario files as tests on virtual time; JUnit XML; exit 1 on a failure");
  test->footer(
      "Run scenario files as tests: each on virtual time as fast as the CPU allows, checking its\n"
      "'expect:' entries (position within tolerance at/by a time, a fault code by a time, a state,\n"
      "no fault, maximum following error). A fault that no 'fault:' expectation of its axis accounts\n"
      "for, a failed or timed-out program step, or a failed transport report also fails the scenario,\n"
      "and so does a fixed 'duration:' that cuts the program off (steps left, an axis still moving)\n"
      "unless the scenario says 'cut_off: expected'.\n"
      "Prints PASS/FAIL per scenario and every failed expectation with its value, e.g.\n"
      "  axis x: expected position 100.000 +/- 0.010 mm at t=2.000 s, was 99.412 mm (off by 0.588 mm)\n"
      "Exit status: 0 all passed; 1 a scenario failed or did not load; 2 bad arguments.\n"
      "Scenario keys: docs/scenarios.md; examples: examples/tests/.");
  test->add_option("paths", args->paths, "Scenario files, or folders searched recursively for *.yaml / *.yml")
      ->required();
  test->add_option("--junit", args->junit, "Write a JUnit XML report to this file (for CI test views)");
  test->add_flag("-v,--verbose", args->verbose, "List passing expectations too");
  test->add_flag("--json", args->json,
                 "Print the summary as one JSON object on stdout (every scenario with its verdict, failures, "
                 "expectations and cut-off; docs/json.md); the PASS/FAIL lines go to stderr");
  test->callback([&ctx, args] { ctx.exit_code = test_command(ctx, *args); });
}

}  // namespace hil::cli
