// SPDX-License-Identifier: MIT
// GPIO lines on the image (mock lines): an input line reaches its bit once per controller cycle
// (active-low inverted), an output bit drives its line only when it changes, and a read error
// leaves the bit and counts.
#include <gtest/gtest.h>

#include "hil/controllers/gpio_io.hpp"
#include "hil/controllers/gpio_link.hpp"
#include "hil/mocks/gpio/mock_lines.hpp"

namespace hil::controllers {
namespace {

using std::chrono::milliseconds;

gpio::LineSpec line(const char* role, unsigned offset, gpio::LineDirection dir) {
  gpio::LineSpec l;
  l.role = role;
  l.offset = offset;
  l.direction = dir;
  return l;
}

std::vector<gpio::LineSpec> specs() {
  return {line("start", 0, gpio::LineDirection::input), line("limit", 1, gpio::LineDirection::input),
          line("lamp", 2, gpio::LineDirection::output)};
}

TEST(GpioIo, InputsAndOutputsThroughTheImage) {
  VirtualClock clock;
  gpio::mock::MockLines lines(specs(), clock);
  IoImage io(IoLayout{{1, 1, 0, 0}});
  const BitAddress start{IoArea::input, 0, 0}, limit{IoArea::input, 0, 1}, lamp{IoArea::output, 0, 5};
  GpioInputs in(lines, {{0, start, false}, {1, limit, true}});
  GpioOutputs out(lines, {{2, lamp, false}, {7, {IoArea::output, 0, 6}, false}});
  io.attach(in);
  io.attach(out);

  lines.set_input(0, true);
  lines.set_input(1, true);
  io.read_inputs(clock.now());
  EXPECT_TRUE(io.get(start));
  EXPECT_FALSE(io.get(limit)) << "active-low";
  EXPECT_TRUE(io.rising(start));

  io.set(lamp, true);
  io.write_outputs(clock.now());
  EXPECT_EQ(*lines.get_value(2), true);
  const auto edges = lines.recorded().size();
  clock.advance(milliseconds(4));
  io.write_outputs(clock.now());
  EXPECT_EQ(lines.recorded().size(), edges) << "unchanged bits are not written again";
  io.set(lamp, false);
  clock.advance(milliseconds(4));
  io.write_outputs(clock.now());
  EXPECT_EQ(*lines.get_value(2), false);
  EXPECT_GE(out.errors(), 1U) << "line 7 does not exist";

  lines.set_input(0, false);
  io.read_inputs(clock.now());
  EXPECT_TRUE(io.falling(start));
  EXPECT_EQ(in.errors(), 0U);
  GpioInputs bad(lines, {{9, start, false}});
  io.attach(bad);
  lines.set_input(0, true);
  io.read_inputs(clock.now());
  EXPECT_FALSE(io.get(start)) << "a line that cannot be read reads 0 (fail-safe), whatever an earlier source set";
  EXPECT_EQ(bad.errors(), 1U);
  EXPECT_EQ(bad.outages(), 1U);
  io.read_inputs(clock.now());
  EXPECT_EQ(bad.outages(), 1U) << "one outage while it keeps failing";
}

TEST(GpioLink, MockChipScriptsInputsOnScenarioTimeAndDrivesOutputs) {
  VirtualClock clock;
  clock.advance(milliseconds(1000));  // the run starts at a clock time other than 0
  IoImage io(IoLayout{{1, 1, 0, 0}});
  const BitAddress start{IoArea::input, 0, 0}, lamp{IoArea::output, 0, 5};
  GpioLinkConfig c;
  c.chip = "mock";
  c.inputs.push_back({"start", 3, "", start, false, gpio::Bias::as_is, {{milliseconds(10), true}}});
  c.outputs.push_back({"lamp", 6, "", lamp, true, gpio::Bias::as_is, {}});
  auto link = GpioLink::open(c, clock);
  ASSERT_TRUE(link) << link.error();
  ASSERT_NE((*link)->mock_lines(), nullptr);
  io.attach(*(*link)->source());
  io.attach(*(*link)->sink());
  auto& lines = *(*link)->mock_lines();

  io.read_inputs(clock.now());  // scenario time 0
  EXPECT_FALSE(io.get(start));
  io.write_outputs(clock.now());
  EXPECT_TRUE(lines.output_level(1)) << "active-low output: bit 0 drives the line high";
  clock.advance(milliseconds(10));
  io.read_inputs(clock.now());
  EXPECT_TRUE(io.rising(start)) << "the script's level at 10 ms of scenario time";
  io.set(lamp, true);
  io.write_outputs(clock.now());
  EXPECT_FALSE(lines.output_level(1));
  EXPECT_EQ((*link)->errors(), 0U);

  // A line that fails (the chip went away): the input reads 0 at once, one outage is one fault
  // naming the chip, the signal and the errno; the line reads again when it heals.
  lines.set_input(0, true);
  io.read_inputs(clock.now());
  ASSERT_TRUE(io.get(start));
  EXPECT_EQ((*link)->fault_count(), 0U);
  EXPECT_FALSE((*link)->fault());
  lines.fail_line(0, std::make_error_code(std::errc::no_such_device));
  io.read_inputs(clock.now());
  io.read_inputs(clock.now());
  EXPECT_FALSE(io.get(start));
  EXPECT_EQ((*link)->fault_count(), 1U);
  const Fault f = (*link)->fault();
  EXPECT_EQ(f.code, std::errc::no_such_device);
  EXPECT_NE(f.text.find("GPIO mock: reading the input line of 'start' failed"), std::string::npos) << f.text;
  lines.fail_line(0, {});
  io.read_inputs(clock.now());
  EXPECT_TRUE(io.get(start));
  lines.fail_line(1, std::make_error_code(std::errc::io_error));
  io.set(lamp, false);
  io.write_outputs(clock.now());
  EXPECT_EQ((*link)->fault_count(), 2U) << "a failed output write is an outage of the link too";
  lines.fail_line(1, {});
  io.write_outputs(clock.now());
  EXPECT_TRUE(lines.output_level(1)) << "retried: active-low, bit 0 drives the line high";

  // A line given twice and a chip that does not exist are errors naming them.
  GpioLinkConfig twice = c;
  twice.outputs[0].offset = 3;
  const auto dup = GpioLink::open(twice, clock);
  ASSERT_FALSE(dup);
  EXPECT_EQ(dup.error(), "mock: line 3 is wired twice ('start' and 'lamp')");
  GpioLinkConfig missing = c;
  missing.chip = "hil-no-such-chip";
  missing.inputs[0].mock.clear();
  const auto none = GpioLink::open(missing, clock);
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().find("hil-no-such-chip"), std::string::npos) << none.error();
}

}  // namespace
}  // namespace hil::controllers
