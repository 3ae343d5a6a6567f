// SPDX-License-Identifier: MIT
// GPIO lines on the image (mock lines): an input line reaches its bit once per controller cycle
// (active-low inverted), an output bit drives its line only when it changes, and a read error
// leaves the bit and counts.
#include <gtest/gtest.h>

#include "hil/controllers/gpio_io.hpp"
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
  EXPECT_TRUE(io.get(start)) << "a failed read leaves the bit as the earlier source set it";
  EXPECT_EQ(bad.errors(), 1U);
}

}  // namespace
}  // namespace hil::controllers
