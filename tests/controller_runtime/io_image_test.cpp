// SPDX-License-Identifier: MIT
// The I/O image: bit and byte access per area, names, edges across cycles, the order sources
// and sinks run in, and out-of-layout addresses that read 0 and are ignored on write.
#include <gtest/gtest.h>

#include <vector>

#include "hil/controllers/io_image.hpp"

namespace hil::controllers {
namespace {

IoLayout layout() {
  return IoLayout{{4, 4, 8, 16}};
}

TEST(IoImage, BitsAndBytesPerArea) {
  IoImage io(layout());
  const BitAddress in{IoArea::input, 1, 3};
  const BitAddress out{IoArea::output, 1, 3};
  io.set(in, true);
  EXPECT_TRUE(io.get(in));
  EXPECT_FALSE(io.get(out)) << "areas are separate";
  EXPECT_EQ(io.get(ByteAddress{IoArea::input, 1}), 0x08);
  io.set(ByteAddress{IoArea::marker, 7}, 0xA5);
  EXPECT_TRUE(io.get(BitAddress{IoArea::marker, 7, 0}));
  EXPECT_FALSE(io.get(BitAddress{IoArea::marker, 7, 1}));
  EXPECT_TRUE(io.get(BitAddress{IoArea::marker, 7, 7}));
  io.set(BitAddress{IoArea::marker, 7, 7}, false);
  EXPECT_EQ(io.get(ByteAddress{IoArea::marker, 7}), 0x25);
  EXPECT_EQ(io.bytes(IoArea::data).size(), 16U);
  EXPECT_EQ(io.bytes(IoArea::marker)[7], 0x25);
}

TEST(IoImage, OutsideTheLayoutReadsZeroAndIgnoresWrites) {
  IoImage io(layout());
  const BitAddress beyond{IoArea::output, 4, 0};
  const BitAddress bad_bit{IoArea::output, 0, 8};
  EXPECT_FALSE(io.contains(beyond));
  EXPECT_FALSE(io.contains(bad_bit));
  io.set(beyond, true);
  io.set(bad_bit, true);
  EXPECT_FALSE(io.get(beyond));
  for (auto b : io.bytes(IoArea::output)) EXPECT_EQ(b, 0);
  for (auto b : io.bytes(IoArea::marker)) EXPECT_EQ(b, 0) << "no spill into the next area";
}

TEST(IoImage, NamesAreUniqueAndInsideTheImage) {
  IoImage io(layout());
  ASSERT_TRUE(io.name_bit("start", {IoArea::input, 0, 3}));
  ASSERT_TRUE(io.name_bit("also_start", {IoArea::input, 0, 3}));
  ASSERT_TRUE(io.name_byte("status", {IoArea::output, 2}));
  EXPECT_EQ(io.find_bit("start"), (BitAddress{IoArea::input, 0, 3}));
  EXPECT_EQ(io.find_byte("status"), (ByteAddress{IoArea::output, 2}));
  EXPECT_FALSE(io.find_bit("status")) << "a byte name is not a bit";
  EXPECT_FALSE(io.find_byte("start"));
  const auto dup = io.name_bit("start", {IoArea::input, 1, 0});
  ASSERT_FALSE(dup);
  EXPECT_NE(dup.error().find("twice"), std::string::npos) << dup.error();
  const auto out = io.name_bit("far", {IoArea::input, 9, 0});
  ASSERT_FALSE(out);
  EXPECT_NE(out.error().find("outside"), std::string::npos) << out.error();
  EXPECT_FALSE(io.name_bit("", {IoArea::input, 0, 0}));
  EXPECT_EQ(io.signals().size(), 3U);
}

struct Recorder : IoSink {
  std::vector<std::uint8_t> seen;
  std::vector<TimePoint> times;
  void write(TimePoint now, const IoImage& image) noexcept override {
    seen.push_back(image.get(ByteAddress{IoArea::output, 0}));
    times.push_back(now);
  }
};

struct Toggle : IoSource {
  BitAddress bit;
  int calls = 0;
  explicit Toggle(BitAddress b) : bit(b) {}
  void read(TimePoint, IoImage& image) noexcept override {
    image.set(bit, !image.get(bit));
    ++calls;
  }
};

TEST(IoImage, EdgesCompareWithTheEndOfThePreviousCycle) {
  IoImage io(layout());
  const BitAddress b{IoArea::input, 0, 0};
  Toggle t(b);
  io.attach(t);
  io.read_inputs(TimePoint{});
  EXPECT_TRUE(io.rising(b));
  EXPECT_FALSE(io.falling(b));
  io.read_inputs(TimePoint{});
  EXPECT_TRUE(io.falling(b));
  EXPECT_FALSE(io.rising(b));
  // A marker set by the logic in one cycle is a rising edge until the next read_inputs.
  const BitAddress m{IoArea::marker, 0, 1};
  io.set(m, true);
  EXPECT_TRUE(io.rising(m));
  io.read_inputs(TimePoint{});
  EXPECT_FALSE(io.rising(m));
  EXPECT_TRUE(io.previous(m));
  EXPECT_EQ(t.calls, 3);
}

TEST(IoImage, SourcesRunInAttachOrderAndSinksSeeTheOutputs) {
  IoImage io(layout());
  const BitAddress b{IoArea::input, 2, 5};
  struct Set : IoSource {
    BitAddress bit;
    bool value;
    Set(BitAddress a, bool v) : bit(a), value(v) {}
    void read(TimePoint, IoImage& image) noexcept override { image.set(bit, value); }
  } first(b, true), second(b, false);
  io.attach(first);
  io.attach(second);
  Recorder rec;
  io.attach(rec);
  io.read_inputs(TimePoint{});
  EXPECT_FALSE(io.get(b)) << "the later source wins";
  io.set(ByteAddress{IoArea::output, 0}, 0x81);
  io.write_outputs(TimePoint{std::chrono::milliseconds(4)});
  ASSERT_EQ(rec.seen.size(), 1U);
  EXPECT_EQ(rec.seen[0], 0x81);
  EXPECT_EQ(rec.times[0], TimePoint{std::chrono::milliseconds(4)});
}

TEST(IoImage, FormatsGenericAddresses) {
  EXPECT_EQ(format_address(BitAddress{IoArea::marker, 12, 3}), "marker 12.3");
  EXPECT_EQ(format_address(ByteAddress{IoArea::data, 4}), "data byte 4");
}

}  // namespace
}  // namespace hil::controllers
