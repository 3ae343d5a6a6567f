// SPDX-License-Identifier: MIT
// Runner end to end on virtual time: cycle order, the demo's final positions, expectations that
// pass and fail (with the value and the miss in the message), program failures, transports.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "hil/runtime/machine.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "sim_registry.hpp"

using namespace std::chrono_literals;
using namespace hil::runtime;

namespace {

const std::string one_axis =
    "machine:\n"
    "  axes:\n"
    "    - name: x\n"
    "      inc_per_unit: 1000\n"
    "      limits: {velocity: 100, acceleration: 1000, jerk: 10000}\n"
    "      supervision: {following_error: 1.0, in_position: 0.01}\n"
    "      drive: {transport: sim, kv: 80, feedforward: 1.0}\n";

Scenario load(const std::string& text) {
  auto s = parse_scenario(text, "t.yaml");
  EXPECT_TRUE(s.has_value()) << (s ? "" : s.error().describe());
  return std::move(*s);
}

RunResult run(const Scenario& s, const hil::TransportRegistry& reg = hil::testing::sim_registry()) {
  RunOptions o;
  auto r = run_scenario(s, reg, o);
  EXPECT_TRUE(r.has_value()) << (r ? "" : r.error().describe());
  return std::move(*r);
}

}  // namespace

TEST(Runner, CycleOrderIsBeginAxesEnd) {
  std::vector<std::string> log;
  hil::TransportRegistry reg;
  reg.add("logging", [&log] { return std::make_unique<hil::testing::LoggingFactory>(log); });
  const Scenario s = load(
      "duration: 5ms\n"
      "machine:\n"
      "  axes:\n"
      "    - {name: a, inc_per_unit: 1000, limits: {velocity: 10, acceleration: 100}, drive: {transport: logging}}\n"
      "    - {name: b, inc_per_unit: 1000, limits: {velocity: 10, acceleration: 100}, drive: {transport: logging}}\n");
  const RunResult r = run(s, reg);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.scheduler.cycles, 5u);
  // One factory instance for both axes: one begin and one end per cycle around the axes.
  std::vector<std::string> one = {"begin", "read a", "write a", "read b", "write b", "end"};
  ASSERT_EQ(log.size(), 5 * one.size() + 1);
  for (std::size_t c = 0; c < 5; ++c)
    for (std::size_t i = 0; i < one.size(); ++i) EXPECT_EQ(log[c * one.size() + i], one[i]) << "cycle " << c;
  EXPECT_EQ(log.back(), "finish");
  ASSERT_EQ(r.reports.size(), 1u);
  EXPECT_EQ(r.reports[0].transport, "logging");
}

TEST(Runner, FailedTransportReportFailsTheRun) {
  std::vector<std::string> log;
  hil::TransportRegistry reg;
  reg.add("logging", [&log] { return std::make_unique<hil::testing::LoggingFactory>(log, false); });
  const RunResult r = run(load("duration: 2ms\n"
                               "machine:\n"
                               "  axes:\n"
                               "    - {name: a, inc_per_unit: 1000, limits: {velocity: 10, acceleration: 100}, drive: "
                               "{transport: logging}}\n"),
                          reg);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.failures.empty());
  EXPECT_NE(r.failures.back().find("transport logging reported a failure: logged"), std::string::npos);
}

TEST(Runner, DemoOnVirtualTimeEndsAtHome) {
  auto s = load_scenario("examples/demo.yaml");
  ASSERT_TRUE(s.has_value()) << s.error().describe();
  ASSERT_GE(s->axes.size(), 3u);
  const RunResult r = run(*s);
  for (const auto& f : r.failures) ADD_FAILURE() << f;
  EXPECT_TRUE(r.ok);
  ASSERT_EQ(r.axes.size(), 3u);
  for (const auto& a : r.axes) {
    EXPECT_NEAR(a.final_position, 0.0, 0.02) << a.name;
    EXPECT_EQ(a.final_state, "standstill") << a.name;
    EXPECT_TRUE(a.faults.empty()) << a.name;
    EXPECT_GT(a.max_following_error, 0.0) << a.name << " never moved?";
  }
  EXPECT_GT(r.simulated, 3s);
  EXPECT_LT(r.simulated, 30s);
  EXPECT_EQ(r.scheduler.cycles, static_cast<std::uint64_t>(r.simulated / 1ms) + 1);
}

TEST(Runner, PassingExpectations) {
  const RunResult r = run(load(one_axis + "program:\n"
                                          "  - enable: x\n"
                                          "  - move_absolute: {axis: x, position: 100}\n"
                                          "expect:\n"
                                          "  - {axis: x, position: 100, tolerance: 0.01, by: 2s}\n"
                                          "  - {axis: x, position: 100, tolerance: 0.01, at: 2.5s}\n"
                                          "  - {axis: x, state: standstill, at: 2.5s}\n"
                                          "  - {axis: x, no_fault: true}\n"
                                          "  - {axis: x, max_following_error: 0.5}\n"));
  for (const auto& f : r.failures) ADD_FAILURE() << f;
  EXPECT_TRUE(r.ok);
  ASSERT_EQ(r.expectations.size(), 5u);
  for (const auto& e : r.expectations) EXPECT_TRUE(e.passed) << e.description << ": " << e.detail;
  EXPECT_GE(r.simulated, 2500ms);  // the run lasts until the latest expectation time
}

TEST(Runner, WrongPositionExpectationSaysWhichWhenAndByHowMuch) {
  const RunResult r = run(load(one_axis + "program:\n"
                                          "  - enable: x\n"
                                          "  - move_absolute: {axis: x, position: 100}\n"
                                          "expect:\n"
                                          "  - {axis: x, position: 100, tolerance: 0.01, at: 0.5s}\n"));
  EXPECT_FALSE(r.ok);
  ASSERT_EQ(r.failures.size(), 1u);
  // The whole message, with both figures to 3 decimals (std::regex is avoided: g++ 12 warns inside
  // it at -O1 with the sanitizers, the CI build).
  const std::string& f = r.failures[0];
  double was = 0;
  double off = 0;
  int end = 0;
  ASSERT_EQ(std::sscanf(f.c_str(),
                        "axis x: expected position 100.000 +/- 0.010 mm at t=0.500 s, was %lf mm (off by %lf mm)%n",
                        &was, &off, &end),
            2)
      << f;
  EXPECT_EQ(static_cast<std::size_t>(end), f.size()) << f;
  EXPECT_EQ(fmt::format("was {:.3f} mm (off by {:.3f} mm)", was, off), f.substr(f.find("was "))) << f;
  EXPECT_NEAR(100.0 - was, off, 0.0011);
  EXPECT_GT(100.0 - was, 10.0);  // half a second into a ~1.1 s move
  ASSERT_EQ(r.expectations.size(), 1u);
  EXPECT_FALSE(r.expectations[0].passed);
  EXPECT_EQ(r.expectations[0].line, 12);
}

TEST(Runner, OtherFailedExpectationsExplainThemselves) {
  const RunResult r = run(load(one_axis + "program:\n"
                                          "  - enable: x\n"
                                          "  - move_absolute: {axis: x, position: 50}\n"
                                          "expect:\n"
                                          "  - {axis: x, fault: \"motion:1\", by: 1s}\n"
                                          "  - {axis: x, state: moving}\n"
                                          "  - {axis: x, max_following_error: 0.000001}\n"
                                          "  - {axis: x, position: 80, tolerance: 0.01, by: 1s}\n"));
  EXPECT_FALSE(r.ok);
  ASSERT_EQ(r.expectations.size(), 4u);
  for (const auto& e : r.expectations) EXPECT_FALSE(e.passed) << e.description;
  EXPECT_EQ(r.expectations[0].detail, "no fault occurred");
  EXPECT_NE(r.expectations[1].detail.find("was standstill"), std::string::npos) << r.expectations[1].detail;
  EXPECT_NE(r.expectations[2].detail.find("reached"), std::string::npos) << r.expectations[2].detail;
  EXPECT_NE(r.expectations[3].detail.find("was 50.000 mm (off by 30.000 mm); closest 29.99"), std::string::npos)
      << r.expectations[3].detail;
}

TEST(Runner, InjectedFaultIsExpectedOrFailsTheRun) {
  const std::string program =
      "program:\n"
      "  - enable: x\n"
      "  - move_absolute: {axis: x, position: 100}\n"
      "    blocking: false\n"
      "  - wait: 200ms\n"
      "  - inject_fault: {axis: x, fault: following_blowup}\n"
      "  - wait_until: {axis: x, state: error}\n"
      "    timeout: 2s\n";
  const RunResult expected = run(load(one_axis + program + "expect:\n  - {axis: x, fault: \"motion:1\", by: 1s}\n"));
  for (const auto& f : expected.failures) ADD_FAILURE() << f;
  EXPECT_TRUE(expected.ok);
  ASSERT_FALSE(expected.faults.empty());
  EXPECT_GT(expected.faults.front().t, 200ms);

  const RunResult unexpected = run(load(one_axis + program));
  EXPECT_FALSE(unexpected.ok);
  ASSERT_FALSE(unexpected.failures.empty());
  EXPECT_NE(unexpected.failures[0].find("axis x: unexpected axis fault at t="), std::string::npos)
      << unexpected.failures[0];
}

TEST(Runner, StepTimeoutAndRejectedCommandFailTheProgram) {
  const RunResult slow = run(load(one_axis + "program:\n"
                                             "  - enable: x\n"
                                             "  - move_absolute: {axis: x, position: 100}\n"
                                             "    timeout: 300ms\n"));
  EXPECT_FALSE(slow.ok);
  ASSERT_FALSE(slow.failures.empty());
  EXPECT_NE(slow.failures[0].find("t.yaml:10 program[1] (move_absolute x): did not complete within 0.300 s"),
            std::string::npos)
      << slow.failures[0];

  const RunResult disabled = run(load(one_axis + "program:\n  - move_absolute: {axis: x, position: 1}\n"));
  EXPECT_FALSE(disabled.ok);
  ASSERT_FALSE(disabled.failures.empty());
  EXPECT_NE(disabled.failures[0].find("axis x rejected the command"), std::string::npos) << disabled.failures[0];
}

TEST(Runner, ScenarioTimeout) {
  const RunResult r =
      run(load(one_axis + "timeout: 1s\nprogram:\n  - enable: x\n  - wait_until: {axis: x, position_above: 5}\n"));
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.failures.empty());
  EXPECT_NE(r.failures[0].find("timeout 1.000 s"), std::string::npos) << r.failures[0];
}

TEST(Runner, BuildErrorsNameTheDriveBlock) {
  auto unknown = run_scenario(
      load("machine:\n  axes:\n    - name: x\n      inc_per_unit: 1\n      limits: {velocity: 1, acceleration: 1}\n"
           "      drive: {transport: warp}\n"),
      hil::testing::sim_registry(), RunOptions{});
  ASSERT_FALSE(unknown.has_value());
  EXPECT_EQ(unknown.error().line, 6);
  EXPECT_EQ(unknown.error().key, "machine.axes[0].drive.transport");
  EXPECT_NE(unknown.error().message.find("unknown transport 'warp'; this hilbridge knows: sim"), std::string::npos);

  auto bad_fault = run_scenario(load(one_axis + "program:\n  - inject_fault: {axis: x, fault: gremlins}\n"),
                                hil::testing::sim_registry(), RunOptions{});
  ASSERT_FALSE(bad_fault.has_value());
  EXPECT_EQ(bad_fault.error().line, 9);
  EXPECT_NE(bad_fault.error().message.find("has no fault 'gremlins'; it accepts: encoder"), std::string::npos)
      << bad_fault.error().describe();

  auto factory_error = run_scenario(
      load("machine:\n  axes:\n    - name: x\n      inc_per_unit: 1\n      limits: {velocity: 1, acceleration: 1}\n"
           "      drive: {transport: sim, kv: -3}\n"),
      hil::testing::sim_registry(), RunOptions{});
  ASSERT_FALSE(factory_error.has_value());
  EXPECT_EQ(factory_error.error().line, 6);
  // The transport's own keys use the same path as the loader's (RunEnvironment::drive_key).
  EXPECT_EQ(factory_error.error().key, "machine.axes[0].drive.kv");
}

namespace {
/// Records the first scenario time each axis moved.
class FirstMotion final : public RunObserver {
 public:
  void on_cycle(hil::Duration t, const Machine& m) noexcept override {
    for (const auto& a : m.axes())
      if (!first.contains(a.spec->name) && std::abs(a.axis->status().command_velocity) > 0.0) first[a.spec->name] = t;
  }
  std::map<std::string, hil::Duration> first;
};
}  // namespace

TEST(Runner, AtDelaysAStepParallelStartsTogetherNonBlockingGoesOn) {
  const std::string machine =
      "machine:\n"
      "  axes:\n"
      "    - {name: a, inc_per_unit: 1000, limits: {velocity: 100, acceleration: 1000}, drive: {transport: sim, kv: "
      "80, feedforward: 1.0}}\n"
      "    - {name: b, inc_per_unit: 1000, limits: {velocity: 100, acceleration: 1000}, drive: {transport: sim, kv: "
      "80, feedforward: 1.0}}\n"
      "    - {name: c, inc_per_unit: 1000, limits: {velocity: 100, acceleration: 1000}, drive: {transport: sim, kv: "
      "80, feedforward: 1.0}}\n";
  auto s = parse_scenario(machine +
                              "program:\n"
                              "  - enable: all\n"
                              "  - parallel:\n"
                              "      - move_absolute: {axis: a, position: 10}\n"
                              "      - move_absolute: {axis: b, position: 20}\n"
                              "    at: 300ms\n"
                              "  - move_absolute: {axis: c, position: 5}\n"
                              "    blocking: false\n"
                              "  - move_relative: {axis: a, distance: 1}\n",
                          "t.yaml");
  ASSERT_TRUE(s.has_value()) << s.error().describe();
  FirstMotion fm;
  RunOptions o;
  o.observers.push_back(&fm);
  auto r = run_scenario(*s, hil::testing::sim_registry(), o);
  ASSERT_TRUE(r.has_value());
  for (const auto& f : r->failures) ADD_FAILURE() << f;
  ASSERT_EQ(fm.first.size(), 3u);
  // Commanded in the cycle at 300 ms, moving from the next update on; a and b in the same cycle.
  EXPECT_EQ(fm.first["a"], 301ms);
  EXPECT_EQ(fm.first["b"], 301ms);
  // c starts when the parallel block completed; the relative move of a starts one cycle later
  // without waiting for c (blocking: false), so c is still moving then.
  EXPECT_GT(fm.first["c"], 400ms);
  EXPECT_NEAR(r->axes[0].final_position, 11.0, 0.01);
  EXPECT_NEAR(r->axes[1].final_position, 20.0, 0.01);
  EXPECT_NEAR(r->axes[2].final_position, 5.0, 0.01);
}

namespace {
class EnvProbe final : public hil::TransportFactory {
 public:
  explicit EnvProbe(std::vector<std::string>& seen) : seen_(seen) {}
  std::expected<hil::DrivePtr, hil::ConfigError> make_drive(const std::string& axis, const YAML::Node& node,
                                                            hil::RunEnvironment& env) override {
    seen_.push_back(fmt::format("{} virtual={} verify={} period={} file={} io={}", axis, env.virtual_time,
                                env.verify_edge_streams, env.period.count(), env.source_file, env.io != nullptr));
    YAML::Node plain = YAML::Clone(node);
    plain["transport"] = "sim";
    return sim_->make_drive(axis, plain, env);
  }

 private:
  std::unique_ptr<hil::TransportFactory> sim_ = hil::mocks::make_sim_transport();
  std::vector<std::string>& seen_;
};
}  // namespace

TEST(Runner, TransportsSeeTheRunEnvironment) {
  std::vector<std::string> seen;
  hil::TransportRegistry reg;
  reg.add("probe", [&seen] { return std::make_unique<EnvProbe>(seen); });
  const Scenario s = load(
      "period: 500us\nduration: 1ms\n"
      "machine:\n"
      "  axes:\n"
      "    - {name: a, inc_per_unit: 1000, limits: {velocity: 10, acceleration: 100}, drive: {transport: probe}}\n");
  RunOptions o;
  o.verify_steps = true;
  auto r = run_scenario(s, reg, o);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->scheduler.cycles, 2u);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0], "a virtual=true verify=true period=500000 file=t.yaml io=false");
}

TEST(Runner, RealTimeSmokeRun) {
  // ~60 ms of real time on the Asio scheduler: same cycle code, real-time statistics filled in.
  const Scenario s = load(one_axis +
                          "duration: 60ms\ncut_off: expected\nprogram:\n  - enable: x\n"
                          "  - move_relative: {axis: x, distance: 0.5}\n    blocking: false\n");
  RunOptions o;
  o.virtual_time = false;
  auto r = run_scenario(s, hil::testing::sim_registry(), o);
  ASSERT_TRUE(r.has_value());
  for (const auto& f : r->failures) ADD_FAILURE() << f;
  EXPECT_FALSE(r->scheduler.virtual_time);
  // The run ends with the first cycle at or past 59 ms (cycles after an overrun skip ahead on the grid).
  EXPECT_GE(r->scheduler.cycles + r->scheduler.skipped_cycles, 60u);
  EXPECT_GE(r->simulated, 59ms);
  EXPECT_LE(r->simulated, 59ms + 1ms * static_cast<long>(r->scheduler.skipped_cycles));
  EXPECT_EQ(r->scheduler.wake_latency.count(), r->scheduler.cycles);
  EXPECT_GE(r->scheduler.wall, 59ms);
  EXPECT_GT(r->axes[0].final_position, 0.0);
}

TEST(Runner, AnExpectationThatHoldsFromTheStartAndNeverChangesIsAWarning) {
  // The axis starts at 0 and a `by:` expectation of 0 is met at the first cycle: it checks nothing,
  // even though the axis moves later. So does `state: disabled` on an axis never enabled.
  const RunResult trivial =
      run(load(one_axis +
               "program:\n  - enable: x\n  - move_absolute: {axis: x, position: 5}\n  - move_absolute: {axis: x, "
               "position: 0}\nexpect:\n  - {axis: x, position: 0, by: 2s}\n  - {axis: x, position: 0}\n"));
  EXPECT_TRUE(trivial.ok);
  ASSERT_EQ(trivial.warnings.size(), 1u) << fmt::format("{}", fmt::join(trivial.warnings, "\n"));
  EXPECT_NE(trivial.warnings[0].find("t.yaml:"), std::string::npos) << trivial.warnings[0];
  EXPECT_NE(trivial.warnings[0].find("expect[0]"), std::string::npos) << trivial.warnings[0];
  EXPECT_NE(trivial.warnings[0].find("already holds at the start of the run"), std::string::npos);

  const RunResult idle = run(load(one_axis + "duration: 100ms\nexpect:\n  - {axis: x, position: 0}\n"
                                             "  - {axis: x, state: disabled}\n"));
  EXPECT_TRUE(idle.ok);
  EXPECT_EQ(idle.warnings.size(), 2u) << fmt::format("{}", fmt::join(idle.warnings, "\n"));

  // Expectations the run has to earn: no warning.
  const RunResult earned =
      run(load(one_axis + "program:\n  - enable: x\n  - move_absolute: {axis: x, position: 5}\n"
                          "expect:\n  - {axis: x, position: 5, by: 2s}\n  - {axis: x, state: standstill}\n"));
  EXPECT_TRUE(earned.ok);
  EXPECT_TRUE(earned.warnings.empty()) << fmt::format("{}", fmt::join(earned.warnings, "\n"));
}

// A fixed `duration:` that ends the run while program steps are left or an axis still moves fails
// with what was cut, unless the scenario says `cut_off: expected` (docs/scenarios.md).
TEST(Runner, ADurationThatCutsTheProgramOffFailsWithWhatWasCut) {
  const std::string program =
      "program:\n"
      "  - enable: x\n"
      "  - move_absolute: {axis: x, position: 50}\n"
      "  - move_absolute: {axis: x, position: 0}\n";
  const RunResult cut = run(load(one_axis + "duration: 200ms\n" + program));
  EXPECT_FALSE(cut.ok);
  ASSERT_TRUE(cut.cut_off.has_value());
  EXPECT_FALSE(cut.cut_off_expected);
  EXPECT_EQ(*cut.cut_off,
            "cut off by duration at t=0.200 s: step 2 of 3 (move_absolute x, t.yaml:11 program[1]) not completed; "
            "axis x still moving");
  ASSERT_EQ(cut.failures.size(), 1u) << fmt::format("{}", fmt::join(cut.failures, "\n"));
  EXPECT_TRUE(cut.failures[0].starts_with(*cut.cut_off)) << cut.failures[0];
  EXPECT_NE(cut.failures[0].find("cut_off: expected"), std::string::npos) << "says what to do: " << cut.failures[0];

  const RunResult intended = run(load(one_axis + "duration: 200ms\ncut_off: expected\n" + program));
  EXPECT_TRUE(intended.ok) << fmt::format("{}", fmt::join(intended.failures, "\n"));
  ASSERT_TRUE(intended.cut_off.has_value());
  EXPECT_TRUE(intended.cut_off_expected);
  EXPECT_EQ(*intended.cut_off,
            "cut off by duration at t=0.200 s: step 2 of 3 (move_absolute x, t.yaml:12 program[1]) not completed; "
            "axis x still moving");

  // Long enough: the program ends and the axis rests before the duration does.
  const RunResult whole = run(load(one_axis + "duration: 5s\n" + program));
  EXPECT_TRUE(whole.ok) << fmt::format("{}", fmt::join(whole.failures, "\n"));
  EXPECT_FALSE(whole.cut_off.has_value()) << *whole.cut_off;
}

TEST(Runner, CutOffNamesStepsLeftAndMovingAxesSeparately) {
  // Steps left, every axis at rest: a wait longer than the duration.
  const RunResult waiting = run(load(one_axis + "duration: 100ms\nprogram:\n  - enable: x\n  - wait: 1s\n"));
  EXPECT_FALSE(waiting.ok);
  ASSERT_TRUE(waiting.cut_off.has_value());
  EXPECT_EQ(*waiting.cut_off,
            "cut off by duration at t=0.100 s: step 2 of 2 (wait, t.yaml:11 program[1]) not completed");

  // Program done, axis still running: a velocity move completes when it is commanded.
  const RunResult running = run(load(one_axis + "duration: 300ms\nprogram:\n  - enable: x\n"
                                                "  - move_velocity: {axis: x, velocity: 10}\n"));
  EXPECT_FALSE(running.ok);
  ASSERT_TRUE(running.cut_off.has_value());
  EXPECT_EQ(*running.cut_off, "cut off by duration at t=0.300 s: axis x still moving");

  // Nothing to cut: no program and nothing moving.
  const RunResult idle = run(load(one_axis + "duration: 50ms\n"));
  EXPECT_TRUE(idle.ok);
  EXPECT_FALSE(idle.cut_off.has_value());
}
