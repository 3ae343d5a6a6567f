// SPDX-License-Identifier: MIT
// The runtime with a controller: `controller:` configures the axes from the device's parameter
// file, `io:` stimuli reach the image, I/O expectations pass and fail with the values, device
// errors reach the result, the trace gets the I/O columns, and the loader's errors name the key.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "hil/runtime/svg_plot.hpp"
#include "hil/runtime/trace_csv.hpp"
#include "scenario_text.hpp"

namespace hil::runtime {
namespace {

using scenario_text::run_text;
using scenario_text::wf_head;

TEST(ControllerScenario, AxesComeFromTheParameterFile) {
  const auto r = run_text(wf_head + R"(
program:
  - enable: A
  - move_absolute: {axis: A, position: 50}
expect:
  - {axis: A, position: 50, tolerance: 0.011}
  - {axis: A, no_fault: true}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  EXPECT_EQ(r->controller, "wf725-726");
  ASSERT_EQ(r->axes.size(), 1U);
  EXPECT_EQ(r->axes[0].units, "mm");
  EXPECT_TRUE(r->device_errors.empty());
}

TEST(ControllerScenario, SoftLimitIsTheDevicesErrorInTheResult) {
  const auto r = run_text(wf_head + R"(
program:
  - enable: A
  - move_velocity: {axis: A, velocity: 80}
    blocking: false
  - wait_until: {axis: A, state: error}
    timeout: 5s
expect:
  - {axis: A, fault: "wf725-726.traversing:96"}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  ASSERT_EQ(r->device_errors.size(), 1U);
  EXPECT_EQ(r->device_errors[0].code, "96");
  EXPECT_EQ(r->device_errors[0].category, "wf725-726.traversing");
  EXPECT_EQ(r->device_errors[0].reaction, "stop");
  EXPECT_NE(r->device_errors[0].describe().find("Pre-limit switch positive (MD 13)"), std::string::npos);
  // Without the expectation the device error fails the run with its number and text.
  const auto u = run_text(wf_head + R"(
program:
  - enable: A
  - move_velocity: {axis: A, velocity: 80}
    blocking: false
  - wait_until: {axis: A, state: error}
    timeout: 5s
)");
  ASSERT_TRUE(u);
  EXPECT_FALSE(u->ok);
  std::string all;
  for (const auto& f : u->failures) all += f + "\n";
  EXPECT_NE(all.find("wf725-726.traversing:96"), std::string::npos) << all;
}

TEST(ControllerScenario, AcknowledgeClearsTheDeviceErrorAndTheAxisMovesBack) {
  // WF 96 (pre-limit positive, reaction stop, acknowledged with data code 800C): the axis stays in
  // error until the operator acknowledges; then it is reset and may move away from the limit.
  const auto r = run_text(wf_head + R"(
program:
  - enable: A
  - move_velocity: {axis: A, velocity: 80}
    blocking: false
  - wait_until: {axis: A, state: error}
    timeout: 5s
  - acknowledge: acknowledge
    timeout: 1s
  - enable: A
  - move_absolute: {axis: A, position: 10}
expect:
  - {axis: A, fault: "wf725-726.traversing:96"}
  - {axis: A, position: 10, tolerance: 0.011}
  - {io: device_error, state: false}
  - {io: error_A, edges: 1, edge: falling}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  ASSERT_EQ(r->device_errors.size(), 1U);
  EXPECT_EQ(r->device_errors[0].code, "96");

  // Without a controller the step is a configuration error naming the fix.
  const auto bad = parse_scenario(R"(
machine:
  axes:
    - {name: x, inc_per_unit: 1000, limits: {velocity: 100, acceleration: 1000}, drive: {transport: sim}}
program:
  - acknowledge: reset
)",
                                  "ack.yaml");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().describe().find("add a 'controller:' block"), std::string::npos) << bad.error().describe();
}

TEST(ControllerScenario, StimuliAndIoExpectations) {
  const auto r = run_text(wf_head + R"(
io:
  - set: limit_minus_A
    at: 100ms
  - pulse: reference_cam_A
    when: {axis: A, position_above: 10}
    width: 8ms
  - {set: "E 0.0", value: false, at: 200ms}
program:
  - enable: A
  - move_absolute: {axis: A, position: 20}
expect:
  - {io: limit_minus_A, state: false, at: 50ms}
  - {io: limit_minus_A, first_edge: true, after: 100ms, by: 104ms}
  - {io: reference_cam_A, edges: 1}
  - {io: reference_cam_A, edges: 1, edge: falling}
  - {io: in_position_A, state: true}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  EXPECT_EQ(r->expectations.size(), 5U);
  bool found = false;
  for (const auto& io : r->io) {
    if (io.name != "reference_cam_A") continue;
    found = true;
    EXPECT_EQ(io.rising, 1U);
    EXPECT_EQ(io.address, "input 0.2");
  }
  EXPECT_TRUE(found);
}

TEST(ControllerScenario, FailedIoExpectationSaysWhatWasSeen) {
  const auto r = run_text(wf_head + R"(
io:
  - {pulse: reference_cam_A, at: 20ms}
program:
  - enable: A
expect:
  - {io: reference_cam_A, edges: 3}
  - {io: moving_A, state: true}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_FALSE(r->ok);
  ASSERT_EQ(r->failures.size(), 2U);
  EXPECT_NE(r->failures[0].find("saw 1 (1 rising, 1 falling)"), std::string::npos) << r->failures[0];
  EXPECT_NE(r->failures[1].find("was 0 at the end of the run"), std::string::npos) << r->failures[1];
}

TEST(ControllerScenario, TraceHasTheIoColumns) {
  const std::string path = ::testing::TempDir() + "/ctl_trace.csv";
  TraceCsvWriter trace;
  ASSERT_FALSE(trace.open(path));
  const auto r = run_text(wf_head + R"(
io:
  - {pulse: reference_cam_A, at: 20ms, width: 10ms}
program:
  - enable: A
  - wait: 50ms
)",
                          {&trace});
  ASSERT_TRUE(r) << r.error().describe();
  ASSERT_FALSE(trace.close());
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_NE(header.find(",io_reference_cam_A,"), std::string::npos) << header;
  EXPECT_NE(header.find(",io_in_position_A,"), std::string::npos) << header;
  EXPECT_TRUE(header.ends_with(",controller_error")) << header;
  std::string line;
  int ones = 0;
  std::size_t col = 0;
  {
    std::size_t pos = 0, k = 0;
    const std::size_t at = header.find("io_reference_cam_A");
    while (pos < at) {
      if (header[pos] == ',') ++k;
      ++pos;
    }
    col = k;
  }
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    for (std::size_t k = 0; k <= col && std::getline(ss, cell, ','); ++k) {
    }
    if (cell == "1") ++ones;
  }
  // The WF reads its inputs once per cycle (4 ms with this parameter set: no jerk limit) and the
  // trace shows its image: the pulse from 20 to 30 ms is read at 20, 24 and 28 ms and is gone at
  // the read at 32 ms, so the image holds it 12 ms.
  EXPECT_EQ(ones, 12) << "a 10 ms pulse read at the WF's 4 ms cycle";
}

TEST(ControllerScenario, PlotDrawsTheIoBitsAsDigitalStripsWithEveryEdge) {
  // 16 points per curve only: the curves are decimated many times over the 2 s run, the strips
  // keep the 2 ms pulses at 0.5 s and 1.5 s exactly (as the WF's 4 ms cycle read them).
  PlotRecorder plot(16);
  const auto r = run_text(wf_head + R"(
io:
  - {pulse: reference_cam_A, at: 500ms, width: 2ms}
  - {pulse: reference_cam_A, at: 1500ms, width: 2ms}
program:
  - enable: A
  - move_absolute: {axis: A, position: 20}
  - wait: 1.5s
)",
                          {&plot});
  ASSERT_TRUE(r) << r.error().describe();
  const auto& d = plot.data().digital;
  const auto cam = std::ranges::find_if(d, [](const PlotDigital& b) { return b.name == "reference_cam_A"; });
  ASSERT_NE(cam, d.end());
  EXPECT_EQ(cam->area, 'I');
  EXPECT_FALSE(cam->initial);
  EXPECT_FALSE(cam->truncated);
  ASSERT_EQ(cam->edges.size(), 4U);
  EXPECT_NEAR(cam->edges[0], 0.500, 1e-9);
  EXPECT_NEAR(cam->edges[1], 0.504, 1e-9) << "held for one WF cycle (4 ms)";
  EXPECT_NEAR(cam->edges[2], 1.500, 1e-9);
  const auto moving = std::ranges::find_if(d, [](const PlotDigital& b) { return b.name == "moving_A"; });
  ASSERT_NE(moving, d.end());
  EXPECT_EQ(moving->area, 'Q');
  EXPECT_EQ(moving->edges.size(), 2U) << "one move: up, then down";
  const auto error = std::ranges::find_if(d, [](const PlotDigital& b) { return b.name == "device_error"; });
  ASSERT_NE(error, d.end());
  EXPECT_EQ(error->area, 'M');
  EXPECT_TRUE(error->edges.empty());
  const std::string svg = render_svg(plot.data());
  EXPECT_NE(svg.find("<g class=\"digital\">"), std::string::npos);
  EXPECT_NE(svg.find(">reference_cam_A</text>"), std::string::npos);
  EXPECT_EQ(svg.find("more edges than the plot keeps"), std::string::npos);

  // More edges than kept: the strip says so instead of drawing a wrong level.
  PlotRecorder few(16);
  std::string pulses;
  for (int i = 0; i < 20; ++i)
    pulses += fmt::format("  - {{pulse: reference_cam_A, at: {}ms, width: 8ms}}\n", 20 * i + 20);
  const auto many = run_text(wf_head + "io:\n" + pulses + "program:\n  - wait: 500ms\n", {&few});
  ASSERT_TRUE(many) << many.error().describe();
  const auto c2 =
      std::ranges::find_if(few.data().digital, [](const PlotDigital& b) { return b.name == "reference_cam_A"; });
  ASSERT_NE(c2, few.data().digital.end());
  EXPECT_TRUE(c2->truncated);
  EXPECT_EQ(c2->edges.size(), 16U);
  EXPECT_NE(render_svg(few.data()).find("more edges than the plot keeps"), std::string::npos);
}

TEST(ControllerScenario, ElgAxisFaultsAreTheElgsAxisAlarmsNumberedByMeasuringCircuit) {
  // The annex tape: Z is the axial axis on measuring circuit 3 (MD 5021), so the motion core's
  // following-error fault on Z is ELG alarm 116* + 2 = 1162 "CONTOUR MONITORING"; X is the NC's
  // axis, not measured by the ELG: its fault stays the motion core's.
  const auto r = run_text(R"(
period: 1ms
duration: 3s
cut_off: expected
controller:
  device: sinumerik-elg
  parameters: elg-hobbing.tape.txt
  programs: [elg-annex.nc]
machine:
  axes:
    - {name: B, drive: {transport: sim, kv: 200, feedforward: 1.0}}
    - {name: C, drive: {transport: sim, kv: 200, feedforward: 1.0}}
    - {name: Z, drive: {transport: sim, kv: 200, feedforward: 1.0}}
    - {name: X, drive: {transport: sim, kv: 200, feedforward: 1.0}}
program:
  - wait: 1s
  - inject_fault: {axis: Z, fault: following_blowup}
  - inject_fault: {axis: X, fault: following_blowup}
  - wait: 2s
expect:
  - {axis: Z, fault: "sinumerik-elg.alarms:1162"}
  - {axis: X, fault: "motion:1"}
)");
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  ASSERT_EQ(r->device_errors.size(), 1U);
  EXPECT_EQ(r->device_errors[0].code, "1162");
  EXPECT_EQ(r->device_errors[0].reaction, "drive_off");
  EXPECT_NE(r->device_errors[0].describe().find("CONTOUR MONITORING"), std::string::npos);
}

TEST(ControllerScenario, ConfigurationErrorsNameTheKey) {
  const auto unknown_device = run_text(R"(
controller: {device: wf999, parameters: x.md}
machine:
  axes:
    - {name: A, drive: {transport: sim}}
)");
  ASSERT_FALSE(unknown_device);
  EXPECT_NE(unknown_device.error().message.find("wf725-726"), std::string::npos) << unknown_device.error().describe();

  const auto extra_key = parse_scenario(R"(
controller: {device: wf725-726, parameters: wf725-axis-a.txt}
machine:
  axes:
    - {name: A, limits: {velocity: 1, acceleration: 1}, drive: {transport: sim}}
)",
                                        "s.yaml");
  ASSERT_FALSE(extra_key);
  EXPECT_NE(extra_key.error().message.find("comes from the controller's parameter file"), std::string::npos)
      << extra_key.error().describe();

  const auto wrong_axis = run_text(R"(
controller: {device: wf725-726, parameters: wf725-axis-a.txt}
machine:
  axes:
    - {name: B, drive: {transport: sim}}
)");
  ASSERT_FALSE(wrong_axis);
  EXPECT_NE(wrong_axis.error().message.find("defines axis 'A'"), std::string::npos) << wrong_axis.error().describe();

  const auto bad_signal = run_text(wf_head + "io:\n  - {set: no_such_input, at: 1s}\n");
  ASSERT_FALSE(bad_signal);
  EXPECT_NE(bad_signal.error().message.find("no_such_input"), std::string::npos) << bad_signal.error().describe();

  const auto output = run_text(wf_head + "io:\n  - {set: moving_A, at: 1s}\n");
  ASSERT_FALSE(output);
  EXPECT_NE(output.error().message.find("drives inputs"), std::string::npos) << output.error().describe();

  const auto period = run_text(R"(
period: 3ms
controller: {device: wf725-726, parameters: wf725-axis-a.txt}
machine:
  axes:
    - {name: A, drive: {transport: sim}}
)");
  ASSERT_FALSE(period);
  EXPECT_NE(period.error().message.find("whole multiple"), std::string::npos) << period.error().describe();

  const auto no_controller = parse_scenario(
      "machine:\n  axes:\n    - {name: A, inc_per_unit: 1, limits: {velocity: 1, "
      "acceleration: 1}, drive: {transport: sim}}\nio:\n  - {set: x, at: 1s}\n");
  ASSERT_FALSE(no_controller);
  EXPECT_EQ(no_controller.error().key, "io");

  const auto bad_param = run_text(R"(
controller: {device: ip247, parameters: ../serial/clm14-parameters.par}
machine:
  axes:
    - {name: "1", drive: {transport: sim}}
)");
  ASSERT_FALSE(bad_param);
  EXPECT_NE(bad_param.error().file.find("clm14-parameters.par"), std::string::npos) << bad_param.error().describe();
}

}  // namespace
}  // namespace hil::runtime
