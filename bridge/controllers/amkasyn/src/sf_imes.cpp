// SPDX-License-Identifier: MIT
// SF IMES (type 7, manual §3.8): pulse distance measurement. The spacing of the zero pulses of a
// counter input (the 32-bit AZ message's zero-pulse latch, ProcessImage::az_zero), in the
// counter's increments. Per new pulse at counter value c (d = c - c_last, 32-bit wrapping):
//   |d| < blocked range (DD8 > 0): ignored (always);
//   absolute (BA bit0 = 1): out = d;
//   difference (bit0 = 0), command spacing cs = DD4 > 0: r = d mod cs in [0, cs);
//     no limitation (BA bits3..2 = 00): out = r or r - cs, in (-cs/2, cs/2];
//     positive (01): out = r in [0, cs-1], valid only if d >= cs;
//     negative (10): out = r - cs (0 for r = 0) in [-(cs-1), 0], valid only if d < cs;
//   cs = 0: out = d;
//   window DD6 > 0: valid only if |out| <= window (the deviation from the nearest multiple of cs,
//   "pulse spacing modulo command spacing"; absolute: |d - cs|).
// Valid: the sink := out, A1 = 1 for this one SF cycle, A2 = 1, c_last := c. Invalid: A2 = 0, and
// with "set down" (BA bit1) c_last := c. The first pulse after START only sets c_last.
#include <cstdlib>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"

namespace hil::controllers::amkasyn {
namespace {

class Imes final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    if (cmd.dl(0) != 0) return start_error("IMES", "DL0 fct", cmd.dl(0), "must be 0");
    ba_ = cmd.dl(1);
    if (ba_ > 15 || (ba_ & 12) == 12)
      return start_error("IMES", "DL1 BA", ba_, "bit0 abs/diff, bit1 set down, bits3..2 00 / 01 / 10 limitation");
    if (cmd.dw(3) < 0 || cmd.dw(3) > 131)
      return start_error("IMES", "DW3 SF cycle time", cmd.dw(3), "0..131 (0.5 ms units; not used)");
    if (init.source.address != 0 || init.source.offset < 16 || init.source.offset > 22 || init.source.offset % 2 != 0)
      return start_error("IMES", "source offset", init.source.offset,
                         "the 32-bit AZ message (address 0, offset 16/18/20/22) with its zero pulse");
    if (init.sink.address != 128 && init.sink.address != 255)
      return start_error("IMES", "sink address", init.sink.address, "128 (MW) or 255 (SF link)");
    if (auto f = take(cmd)) return f;
    channel_ = static_cast<std::size_t>((init.source.offset - 16) / 2);
    seen_ = io.image.az_zero[channel_].count;
    have_last_ = false;
    io.a(1, false);
    io.a(2, false);
    return std::nullopt;
  }

  std::optional<SfFault> value_new(const DataBlock& cmd, SfIo&) override { return take(cmd); }

  void step(SfIo& io) noexcept override {
    io.a(1, false);
    const ZeroPulseLatch& z = io.image.az_zero[channel_];
    if (z.count == seen_) return;
    seen_ = z.count;
    const std::int32_t c = z.position;
    if (!have_last_) {
      last_ = c;
      have_last_ = true;
      return;
    }
    const auto d = static_cast<std::int64_t>(
        static_cast<std::int32_t>(static_cast<std::uint32_t>(c) - static_cast<std::uint32_t>(last_)));
    if (blocked_ > 0 && std::llabs(d) < blocked_) return;  // a long pulse seen twice
    std::int64_t out = d, deviation = cs_ > 0 ? d - cs_ : 0;
    bool valid = true;
    if ((ba_ & 1) == 0 && cs_ > 0) {
      const std::int64_t r = ((d % cs_) + cs_) % cs_;
      switch ((ba_ >> 2) & 3) {
        case 1:
          out = r;
          valid = d >= cs_;
          break;
        case 2:
          out = r == 0 ? 0 : r - cs_;
          valid = d < cs_;
          break;
        default:
          out = r > cs_ / 2 ? r - cs_ : r;
          break;
      }
      deviation = out;
    }
    if (window_ > 0 && std::llabs(deviation) > window_) valid = false;
    if (valid) {
      io.sink = static_cast<std::int32_t>(out);
      io.a(1, true);
      io.a(2, true);
      last_ = c;
    } else {
      io.a(2, false);
      if (ba_ & 2) last_ = c;  // set down: the invalid pulse starts the next spacing
    }
  }

 private:
  std::optional<SfFault> take(const DataBlock& cmd) {
    cs_ = cmd.dd(4);
    window_ = cmd.dd(6);
    blocked_ = cmd.dd(8);
    constexpr std::int64_t max = (std::int64_t{1} << 30) - 1;
    if (cs_ < 0 || cs_ > max) return start_error("IMES", "DD4 command spacing", cs_, "0..2^30-1 increments");
    if (window_ < 0 || window_ > max)
      return start_error("IMES", "DD6 permissible window", window_, "0..2^30-1 (0 = always valid)");
    if (blocked_ < 0 || blocked_ > max)
      return start_error("IMES", "DD8 blocked range", blocked_, "0..2^30-1 (0 = none)");
    return std::nullopt;
  }

  int ba_ = 0;
  std::size_t channel_ = 0;
  std::int64_t cs_ = 0, window_ = 0, blocked_ = 0;
  std::uint32_t seen_ = 0;
  std::int32_t last_ = 0;
  bool have_last_ = false;
};

}  // namespace

std::unique_ptr<FastFunction> make_imes() {
  return std::make_unique<Imes>();
}

}  // namespace hil::controllers::amkasyn
