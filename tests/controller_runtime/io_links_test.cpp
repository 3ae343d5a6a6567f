// SPDX-License-Identifier: MIT
// `io_links:` on the runtime: GPIO lines wired to a controller's image. A mock chip's scripted
// input reaches the image (seen by an expectation, in the trace, and acted on by the device: a
// WF 725/726 limit switch), an image output drives a line, active-low lines invert, and every
// wiring mistake is a configuration error naming the key. The same scenario on gpio-sim runs in
// the kernel label (tests/gpio/io_link_gpio_sim.sh).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "hil/runtime/trace_csv.hpp"
#include "scenario_text.hpp"

namespace hil::runtime {
namespace {

using scenario_text::run_text;
using scenario_text::wf_head;

// Column index of `name` in a CSV header.
std::size_t column(const std::string& header, const std::string& name) {
  std::stringstream ss(header);
  std::string cell;
  for (std::size_t k = 0; std::getline(ss, cell, ','); ++k)
    if (cell == name) return k;
  return SIZE_MAX;
}

TEST(IoLinks, MockGpioLimitSwitchStopsTheAxisWithTheDevicesError) {
  // The positive range-limit switch of the WF axis is wired to line 4 of a mock chip; its level
  // goes high at 300 ms while the axis runs positive: the WF reports 16 (reaction: drive off).
  const std::string path = ::testing::TempDir() + "/io_links_trace.csv";
  TraceCsvWriter trace;
  ASSERT_FALSE(trace.open(path));
  const auto r = run_text(wf_head + R"(
io_links:
  - gpio: {chip: mock}
    inputs:
      limit_plus_A: {line: 4, mock: [{at: 300ms, level: true}]}
    outputs:
      moving_A: 7
program:
  - enable: A
  - move_velocity: {axis: A, velocity: 20}
    blocking: false
  - wait: 600ms
expect:
  - {io: limit_plus_A, first_edge: true, after: 299ms, by: 305ms}
  - {io: moving_A, edges: 1, edge: falling}
  - {axis: A, fault: "wf725-726.traversing:16"}
)",
                          {&trace});
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  ASSERT_EQ(r->device_errors.size(), 1U);
  EXPECT_EQ(r->device_errors[0].code, "16");
  ASSERT_FALSE(trace.close());

  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  const std::size_t t_col = column(header, "t_s");
  const std::size_t io_col = column(header, "io_limit_plus_A");
  ASSERT_NE(io_col, SIZE_MAX) << header;
  ASSERT_NE(t_col, SIZE_MAX) << header;
  double first_one = -1;
  while (std::getline(in, line) && first_one < 0) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (cells.size() > io_col && cells[io_col] == "1") first_one = std::stod(cells[t_col]);
  }
  // The WF reads its image every 4 ms: the level set at 300 ms is in the image from the cycle at 300 ms.
  EXPECT_NEAR(first_one, 0.300, 0.0045) << "first trace row with the limit switch input";
}

TEST(IoLinks, ActiveLowInputInvertsTheLine) {
  // An NC contact wired active-low: the line is high (closed) until 100 ms, so the image bit is 0
  // and rises when the line drops.
  const auto r = run_text(wf_head + R"(
io_links:
  - gpio: {chip: mock}
    inputs:
      reference_cam_A: {line: 0, active_low: true, mock: [{at: 0s, level: true}, {at: 100ms, level: false}]}
program:
  - wait: 200ms
expect:
  - {io: reference_cam_A, state: false, at: 50ms}
  - {io: reference_cam_A, first_edge: true, after: 99ms, by: 104ms}
  - {io: reference_cam_A, state: true}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
}

TEST(IoLinks, WiringMistakesNameTheKey) {
  const auto expect_error = [](const std::string& links, const std::string& path, const std::string& text) {
    const auto r = run_text(wf_head + links + "program:\n  - wait: 10ms\n");
    ASSERT_FALSE(r) << links;
    EXPECT_EQ(r.error().key, path) << r.error().describe();
    EXPECT_NE(r.error().message.find(text), std::string::npos) << r.error().describe();
  };
  expect_error("io_links:\n  - gpio: {chip: mock}\n    inputs: {moving_A: 1}\n", "io_links[0].inputs.moving_A",
               "a link's inputs are input (or device data) bits");
  expect_error("io_links:\n  - gpio: {chip: mock}\n    outputs: {limit_plus_A: 1}\n",
               "io_links[0].outputs.limit_plus_A", "a link's outputs are output (or marker) bits");
  expect_error("io_links:\n  - gpio: {chip: mock}\n    inputs: {no_such_signal: 1}\n",
               "io_links[0].inputs.no_such_signal", "no_such_signal");
  expect_error("io_links:\n  - gpio: {chip: mock}\n    inputs: {limit_plus_A: 1, limit_minus_A: 1}\n",
               "io_links[0].gpio", "line 1 is wired twice ('limit_plus_A' and 'limit_minus_A')");
  expect_error("io_links:\n  - gpio: {chip: mock}\n    inputs: {limit_plus_A: LIMIT}\n",
               "io_links[0].inputs.limit_plus_A", "mock lines have offsets, not names");
  expect_error("io_links:\n  - gpio: {chip: gpiochip0}\n    inputs: {limit_plus_A: {line: 1, mock: []}}\n",
               "io_links[0].inputs.limit_plus_A.mock", "'mock' scripts an input line of 'chip: mock'");
  expect_error("io_links:\n  - gpio: {chip: mock}\n    outputs: {moving_A: {line: 1, bias: pull-up}}\n",
               "io_links[0].outputs.moving_A.bias", "'bias' applies to input lines");
  expect_error("io_links:\n  - gpio: {chip: mock}\n", "io_links[0]", "the gpio link wires nothing");
  expect_error("io_links:\n  - gpio: {chip: hil-no-such-chip}\n    inputs: {limit_plus_A: 1}\n", "io_links[0].gpio",
               "cannot open the GPIO lines: ");
  expect_error("io_links:\n  - {inputs: {limit_plus_A: 1}}\n", "io_links[0]", "needs one of: gpio");

  // Without a controller there is no image to wire.
  const auto bare = parse_scenario(R"(
machine:
  axes:
    - {name: x, inc_per_unit: 1000, limits: {velocity: 100, acceleration: 1000}, drive: {transport: sim}}
io_links:
  - gpio: {chip: mock}
    inputs: {start: 1}
)",
                                   "t.yaml");
  ASSERT_FALSE(bare);
  EXPECT_NE(bare.error().message.find("add a 'controller:' block"), std::string::npos) << bare.error().describe();
}

}  // namespace
}  // namespace hil::runtime
