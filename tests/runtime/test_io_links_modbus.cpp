// SPDX-License-Identifier: MIT
// `io_links: - modbus:` on the runtime, on virtual time: a coil set on the simulated I/O terminal
// (as a peer would) reaches the WF 725/726 controller's image at the link's next poll, is seen by
// an expectation and in the CSV trace; controller outputs reach the terminal's coils; a terminal
// that stops answering fails the run with the link's modbus fault and its inputs read 0; wiring
// mistakes are configuration errors naming file, line and key path.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>

#include "hil/controllers/modbus_io_sim_bus.hpp"
#include "hil/runtime/run_observer.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "hil/runtime/trace_csv.hpp"
#include "sim_registry.hpp"

namespace hil::runtime {
namespace {

using std::chrono::milliseconds;

// Scenario file in examples/controllers so that the WF parameter file resolves next to it.
std::expected<RunResult, ConfigError> run_text(const std::string& text, std::vector<RunObserver*> observers = {}) {
  auto s = parse_scenario(text, "examples/controllers/modbus-io-test.yaml");
  if (!s) return std::unexpected(s.error());
  static Scenario keep;
  keep = std::move(*s);
  RunOptions o;
  o.observers = std::move(observers);
  return run_scenario(keep, hil::testing::sim_registry(), o);
}

const std::string wf_head = R"(
period: 1ms
controller: {device: wf725-726, parameters: wf725-axis-a.txt}
machine:
  axes:
    - name: A
      drive: {transport: sim, kv: 100, feedforward: 1.0}
)";

// Acts on the simulated terminal of io_links[0] from the cycle thread (what a peer or the field
// wiring does), and records coils.
class TerminalScript final : public RunObserver {
 public:
  std::function<void(Duration, controllers::SimModbusIoBus&)> act;
  void on_cycle(Duration t, const Machine& m) noexcept override {
    if (m.modbus_links().empty()) return;
    auto* bus = dynamic_cast<controllers::SimModbusIoBus*>(&m.modbus_links()[0].link->bus());
    if (bus != nullptr && act) act(t, *bus);
  }
};

bool coil(controllers::SimModbusIoBus& bus, std::uint16_t a) {
  return bus.server().with_terminal([&](mocks::IoTerminal& t) { return t.coil(a); });
}

std::size_t column(const std::string& header, const std::string& name) {
  std::stringstream ss(header);
  std::string cell;
  for (std::size_t k = 0; std::getline(ss, cell, ','); ++k)
    if (cell == name) return k;
  return SIZE_MAX;
}

TEST(IoLinksModbus, ACoilSetOnTheSimulatedTerminalIsSeenByAnExpectationAndInTheTrace) {
  const std::string path = ::testing::TempDir() + "/io_links_modbus_trace.csv";
  TraceCsvWriter trace;
  ASSERT_FALSE(trace.open(path));
  TerminalScript script;
  bool moving_coil_seen = false;
  bool in_position_coil_at_end = false;
  script.act = [&](Duration t, controllers::SimModbusIoBus& bus) {
    if (t == milliseconds(300)) bus.server().with_terminal([](mocks::IoTerminal& tm) { tm.set_coil(0, true); });
    moving_coil_seen = moving_coil_seen || coil(bus, 16);
    in_position_coil_at_end = coil(bus, 17);
  };
  const auto r = run_text(wf_head + R"(
io_links:
  - modbus: {bus: sim, unit: 1, poll: 10ms, status: "E 0.7"}
    inputs:
      reference_cam_A: {coil: 0}
    outputs:
      moving_A: {coil: 16}
      in_position_A: {coil: 17}
program:
  - enable: A
  - move_relative: {axis: A, distance: 5}
  - wait: 400ms
expect:
  - {io: reference_cam_A, first_edge: true, after: 299ms, by: 316ms}
  - {io: "E 0.7", state: true}
  - {io: moving_A, edges: 1, edge: rising}
)",
                          {&trace, &script});
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  EXPECT_TRUE(moving_coil_seen) << "the controller's moving_A output reached coil 16";
  EXPECT_TRUE(in_position_coil_at_end) << "in_position_A on coil 17 at the end";
  ASSERT_FALSE(trace.close());

  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  const std::size_t t_col = column(header, "t_s");
  const std::size_t io_col = column(header, "io_reference_cam_A");
  ASSERT_NE(io_col, SIZE_MAX) << header;
  double first_one = -1;
  while (std::getline(in, line) && first_one < 0) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (cells.size() > io_col && cells[io_col] == "1") first_one = std::stod(cells[t_col]);
  }
  // Set at 300 ms; the WF steps every 4 ms and the link polls at the first step 10 ms after the
  // last poll: polls at 0, 12, 24, ... 300, 312 ms. The coil set in the cycle of 300 ms (after the
  // controller step of that cycle) is read at 312 ms.
  EXPECT_NEAR(first_one, 0.312, 1e-9) << "first trace row with the reference cam input";
}

TEST(IoLinksModbus, ATerminalThatStopsAnsweringFailsTheRunAndItsInputsReadZero) {
  TerminalScript script;
  script.act = [](Duration t, controllers::SimModbusIoBus& bus) {
    if (t == milliseconds(0)) bus.server().with_terminal([](mocks::IoTerminal& tm) { tm.set_discrete_input(5, true); });
    if (t == milliseconds(200)) bus.set_answering(false);
  };
  const auto r = run_text(wf_head + R"(
io_links:
  - modbus: {bus: sim, poll: 10ms, timeout: 50ms}
    inputs:
      reference_cam_A: {discrete_input: 5}
program:
  - wait: 400ms
expect:
  - {io: reference_cam_A, state: true, at: 150ms}
  - {io: reference_cam_A, state: false, at: 300ms}
)",
                          {&script});
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_FALSE(r->ok);
  ASSERT_EQ(r->failures.size(), 1u) << r->failures.front();
  EXPECT_NE(r->failures[0].find("io_links[0]: I/O link fault at t="), std::string::npos) << r->failures[0];
  EXPECT_NE(r->failures[0].find("modbus:"), std::string::npos) << r->failures[0];
  ASSERT_EQ(r->faults.size(), 1u);
  EXPECT_EQ(r->faults[0].source, "io_link");
  EXPECT_EQ(r->faults[0].axis, "io_links[0]");
  EXPECT_EQ(r->faults[0].fault.code, modbus::make_error_code(modbus::ModbusError::timeout));
  // The poll started at or after 200 ms is answered by nobody; 50 ms later the link faults.
  EXPECT_GE(r->faults[0].t, milliseconds(250));
  EXPECT_LE(r->faults[0].t, milliseconds(266));
  for (const auto& e : r->expectations) EXPECT_TRUE(e.passed) << e.description << ": " << e.detail;
}

TEST(IoLinksModbus, WiringMistakesNameTheKey) {
  const auto expect_error = [](const std::string& links, const std::string& path, const std::string& text, int line) {
    const auto r = run_text(wf_head + links + "program:\n  - wait: 10ms\n");
    ASSERT_FALSE(r) << links;
    EXPECT_EQ(r.error().key, path) << r.error().describe();
    EXPECT_EQ(r.error().file, "examples/controllers/modbus-io-test.yaml");
    EXPECT_EQ(r.error().line, line) << r.error().describe();
    EXPECT_NE(r.error().message.find(text), std::string::npos) << r.error().describe();
  };
  // wf_head has 7 lines (a leading newline), so io_links: is line 8 and its first entry line 9.
  expect_error("io_links:\n  - modbus: {bus: serial}\n    inputs: {limit_plus_A: {coil: 1}}\n",
               "io_links[0].modbus.bus", "expected sim (the simulated terminal) or tcp://HOST[:PORT]", 9);
  expect_error(
      "io_links:\n  - modbus: {bus: \"tcp://10.0.0.9\", listen: \"127.0.0.1:0\"}\n"
      "    inputs: {limit_plus_A: {coil: 1}}\n",
      "io_links[0].modbus.listen", "it needs 'bus: sim'", 9);
  expect_error("io_links:\n  - modbus: {listen: 127.0.0.1}\n    inputs: {limit_plus_A: {coil: 1}}\n",
               "io_links[0].modbus.listen", "expected HOST:PORT", 9);
  expect_error("io_links:\n  - modbus: {unit: 300}\n    inputs: {limit_plus_A: {coil: 1}}\n", "io_links[0].modbus.unit",
               "expected a unit id 0..255", 9);
  expect_error("io_links:\n  - modbus: {poll: 10ms, stale_after: 5ms}\n    inputs: {limit_plus_A: {coil: 1}}\n",
               "io_links[0].modbus.stale_after", "at least the poll period", 9);
  expect_error("io_links:\n  - modbus: {}\n    outputs:\n      moving_A: {discrete_input: 3}\n",
               "io_links[0].outputs.moving_A.discrete_input", "a discrete input is read-only", 11);
  expect_error("io_links:\n  - modbus: {}\n    inputs:\n      limit_plus_A: {coil: 70000}\n",
               "io_links[0].inputs.limit_plus_A.coil", "0..65535", 11);
  expect_error("io_links:\n  - modbus: {}\n    inputs:\n      limit_plus_A: 4\n", "io_links[0].inputs.limit_plus_A",
               "expected {discrete_input | coil: ADDRESS}", 11);
  expect_error("io_links:\n  - modbus: {}\n    inputs:\n      limit_plus_A: {coil: 1, discrete_input: 1}\n",
               "io_links[0].inputs.limit_plus_A", "exactly one of", 11);
  expect_error("io_links:\n  - modbus: {}\n    inputs:\n      moving_A: {coil: 1}\n", "io_links[0].inputs.moving_A",
               "a link's inputs are input (or device data) bits", 11);
  expect_error("io_links:\n  - modbus: {}\n    outputs:\n      moving_A: {coil: 1}\n      in_position_A: {coil: 1}\n",
               "io_links[0].outputs", "coil 1 is written twice", 9);
  expect_error("io_links:\n  - modbus: {status: moving_A}\n    inputs: {limit_plus_A: {coil: 1}}\n",
               "io_links[0].modbus.status", "a link's inputs are input (or device data) bits", 9);
}

}  // namespace
}  // namespace hil::runtime
