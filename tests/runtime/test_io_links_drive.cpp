// SPDX-License-Identifier: MIT
// `io_links: - drive: A` with the axis on `transport: canopen` (our master and the simulated CiA
// 402 node on the in-process virtual bus, as `hilbridge run` builds them): the node's home switch
// (0x60FD bit 2, from its plant's `switches:`) reaches the WF 725/726 image as reference_cam_A,
// seen by expectations and in the CSV trace; the WF's in_position_A output reaches the node's
// 0x60FE:1 bit 16; the positive limit switch (bit 1) stops the axis with the WF's own error; and
// every wiring mistake is a configuration error naming file, line and key.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "hil/cia402/canopen_transport.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "hil/runtime/trace_csv.hpp"
#include "sim_registry.hpp"

namespace hil::runtime {
namespace {

/// The transports `hilbridge` registers that this test uses: `canopen` and `sim`.
TransportRegistry registry() {
  TransportRegistry r = hil::testing::sim_registry();
  r.add("canopen", [] { return cia402::make_canopen_transport(); });
  return r;
}

std::expected<RunResult, ConfigError> run_text(const std::string& text, std::vector<RunObserver*> observers = {}) {
  // Relative parameter paths resolve against the scenario's folder: pretend it lives in examples/controllers.
  auto s = parse_scenario(text, "examples/controllers/test.yaml");
  if (!s) return std::unexpected(s.error());
  static Scenario keep;
  keep = std::move(*s);
  RunOptions o;
  o.observers = std::move(observers);
  static const TransportRegistry transports = registry();
  return run_scenario(keep, transports, o);
}

// The WF axis (1 um per increment: 1000 inc/mm) on a simulated CANopen node with a home cam at
// 20..25 mm and the positive limit switch at 60 mm.
const std::string wf_canopen = R"(
period: 1ms
controller: {device: wf725-726, parameters: wf725-axis-a.txt}
machine:
  axes:
    - name: A
      drive: {transport: canopen, node: 5, kv: 100, feedforward: 1.0,
              switches: {home: [20000, 25000], positive: 60000}}
)";

std::size_t column(const std::string& header, const std::string& name) {
  std::stringstream ss(header);
  std::string cell;
  for (std::size_t k = 0; std::getline(ss, cell, ','); ++k)
    if (cell == name) return k;
  return SIZE_MAX;
}

std::string all_lines(const RunResult& r) {
  std::string out;
  for (const auto& rep : r.reports)
    for (const auto& l : rep.report.lines) out += l + "\n";
  return out;
}

TEST(IoLinksDrive, HomeSwitchOfTheCanopenNodeReachesTheImageAndOutputsReachTheNode) {
  const std::string path = ::testing::TempDir() + "/io_links_drive_trace.csv";
  TraceCsvWriter trace;
  ASSERT_FALSE(trace.open(path));
  const auto r = run_text(wf_canopen + R"(
io_links:
  - drive: A
    inputs:
      reference_cam_A: {bit: 2}
    outputs:
      in_position_A: {bit: 16}
program:
  - enable: A
  - move_absolute: {axis: A, position: 22.5}
  - wait: 100ms
  - move_absolute: {axis: A, position: 40}
  - wait: 20ms
expect:
  - {io: reference_cam_A, edges: 1, edge: rising}
  - {io: reference_cam_A, edges: 1, edge: falling}
  - {io: reference_cam_A, first_edge: true, after: 100ms, by: 1s}
  - {io: reference_cam_A, state: false}
  - {axis: A, position: 40, tolerance: 0.011}
  - {axis: A, no_fault: true}
)",
                          {&trace});
  ASSERT_TRUE(r) << r.error().describe();
  ASSERT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front()) << "\n" << all_lines(*r);
  ASSERT_FALSE(trace.close());
  for (const auto& e : r->expectations) EXPECT_TRUE(e.passed) << e.description << ": " << e.detail;

  // The trace: reference_cam_A is 1 exactly while the axis stands on the cam (20..25 mm), give or
  // take the PDO round trip and the WF's 4 ms input cycle.
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  const auto cam = column(header, "io_reference_cam_A");
  const auto pos = column(header, "A_position_mm");
  ASSERT_NE(cam, SIZE_MAX) << header;
  ASSERT_NE(pos, SIZE_MAX) << header;
  int ones = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    ASSERT_GT(cells.size(), std::max(cam, pos)) << line;
    if (cells[cam] != "1") continue;
    ++ones;
    const double p = std::stod(cells[pos]);
    EXPECT_GT(p, 20.0 - 1.0) << line;  // at most ~8 ms late at <= 100 mm/s
    EXPECT_LT(p, 25.0 + 1.0) << line;
  }
  EXPECT_GT(ones, 100) << "on the cam for the 100 ms wait and the way on and off it";

  // The WF's in_position_A drove 0x60FE:1 bit 16 (inside the default 0x60FE:2 mask 0xFFFF0000):
  // the axis ends in position, off every switch.
  const auto lines = all_lines(*r);
  EXPECT_NE(lines.find("node 5 (simulated) at the end: digital inputs 0x60FD = 0x00000000, outputs 0x60FE = "
                       "0x00010000"),
            std::string::npos)
      << lines;
  EXPECT_NE(lines.find("0x60FD digital inputs (32 bit)"), std::string::npos) << "in a TPDO:\n" << lines;
  const auto io = std::ranges::find_if(r->io, [](const IoSummary& s) { return s.name == "reference_cam_A"; });
  ASSERT_NE(io, r->io.end());
  EXPECT_EQ(io->rising, 1U);
}

TEST(IoLinksDrive, PositiveLimitSwitchOfTheNodeStopsTheAxisWithTheDevicesError) {
  const auto r = run_text(wf_canopen + R"(
io_links:
  - drive: A
    inputs:
      limit_plus_A: {bit: 1}
program:
  - enable: A
  - move_velocity: {axis: A, velocity: 30}
    blocking: false
  - wait: 3s
expect:
  - {io: limit_plus_A, first_edge: true, after: 1.9s, by: 2.3s}
  - {io: error_A, state: true}
  - {axis: A, fault: "wf725-726.traversing:16"}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front()) << "\n" << all_lines(*r);
  ASSERT_EQ(r->device_errors.size(), 1U);
  EXPECT_EQ(r->device_errors[0].code, "16");
  ASSERT_EQ(r->axes.size(), 1U);
  EXPECT_GE(r->axes[0].final_position, 60.0) << "stopped on the switch, not before it";
  EXPECT_LT(r->axes[0].final_position, 62.0);
}

TEST(IoLinksDrive, WiringErrorsNameTheKey) {
  struct Case {
    std::string links;
    std::string where;  ///< file:line of the key
    std::string error;
  };
  // wf_canopen is 8 lines (a leading empty one): `io_links:` is line 9, the entry line 10.
  const Case cases[] = {
      {"  - drive: B\n    inputs: {reference_cam_A: {bit: 2}}\n",
       "test.yaml:10:", "io_links[0].drive: unknown axis 'B': the machine's axes are A"},
      {"  - drive: A\n    inputs: {reference_cam_A: {bit: 32}}\n", "test.yaml:11:",
       "io_links[0].inputs.reference_cam_A.bit: expected a drive bit 0..31 (CiA 402 0x60FD inputs / 0x60FE:1 "
       "outputs), got '32'"},
      {"  - drive: A\n    inputs: {reference_cam_A: {line: 2}}\n",
       "test.yaml:11:", "io_links[0].inputs.reference_cam_A.line: unknown key 'line'; allowed here: bit"},
      {"  - drive: A\n    outputs: {in_position_A: {bit: 0}}\n", "test.yaml:11:",
       "io_links[0].outputs.in_position_A: bit 0 is not among the digital outputs the drive of axis A "
       "(canopen:virtual:canopen/5) applies (mask 0xFFFF0000); a canopen drive's `output_mask` (0x60FE:2) sets them"},
      {"  - drive: A\n    outputs: {in_position_A: {bit: 16}, moving_A: 16}\n",
       "test.yaml:11:", "io_links[0].outputs.moving_A: drive bit 16 of axis A is already driven by another output"},
      {"  - drive: A\n    outputs: {in_position_A: {bit: 16}}\n  - drive: A\n    outputs: {moving_A: 16}\n",
       "test.yaml:13:", "io_links[1].outputs.moving_A: drive bit 16 of axis A is already driven by another output"},
      {"  - drive: A\n    outputs: {reference_cam_A: {bit: 16}}\n",
       "test.yaml:11:", "io_links[0].outputs.reference_cam_A: 'reference_cam_A' is a input bit"},
  };
  for (const auto& c : cases) {
    const auto r = run_text(wf_canopen + "io_links:\n" + c.links + "program:\n  - enable: A\n");
    ASSERT_FALSE(r) << c.links;
    const auto text = r.error().describe();
    EXPECT_NE(text.find(c.error), std::string::npos) << c.links << "\n" << text;
    EXPECT_NE(text.find(c.where), std::string::npos) << c.links << "\n" << text;
  }
  // A drive without digital I/O: the simulated drive's EDS without 0x60FD and 0x60FE.
  const auto no_io = run_text(R"(
period: 1ms
controller: {device: wf725-726, parameters: wf725-axis-a.txt}
machine:
  axes:
    - name: A
      drive: {transport: canopen, node: 5, eds: ../../tests/runtime/data/drive_without_dio.eds}
io_links:
  - drive: A
    inputs: {reference_cam_A: {bit: 2}}
)");
  ASSERT_FALSE(no_io);
  EXPECT_NE(no_io.error().describe().find("io_links[0].inputs.reference_cam_A: the drive of axis A "
                                          "(canopen:virtual:canopen/5) has no digital inputs (CiA 402 0x60FD)"),
            std::string::npos)
      << no_io.error().describe();
}

}  // namespace
}  // namespace hil::runtime
