// SPDX-License-Identifier: MIT
// End to end: examples/stepdir-demo.yaml through the runtime (motion core, program, expectations)
// on the stepdir transport with mock lines, virtual time, --verify-steps.
#include <gtest/gtest.h>

#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"

TEST(StepDirScenario, DemoRunsWithVerifiedEdgeStreams) {
  auto scenario = hil::runtime::load_scenario("examples/stepdir-demo.yaml");
  ASSERT_TRUE(scenario) << scenario.error().describe();
  hil::TransportRegistry registry;
  registry.add("stepdir", [] { return std::make_unique<hil::drives::stepdir::StepDirTransportFactory>(); });
  hil::runtime::RunOptions opts;
  opts.virtual_time = true;
  opts.verify_steps = true;
  auto result = hil::runtime::run_scenario(*scenario, registry, opts);
  ASSERT_TRUE(result) << result.error().describe();
  for (const auto& f : result->failures) ADD_FAILURE() << f;
  EXPECT_TRUE(result->ok);
  bool seen = false;
  for (const auto& r : result->reports) {
    for (const auto& l : r.report.lines) {
      EXPECT_EQ(l.find("VIOLATION"), std::string::npos) << l;
      seen = seen || l.find("timing rules held") != std::string::npos;
    }
  }
  EXPECT_TRUE(seen);
}
