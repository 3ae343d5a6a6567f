// SPDX-License-Identifier: MIT
// SF FGEN (type 5, manual §3.6): reference input variable generator. A position ramp X(t) for
// the sink (typically the master of an FIPW through an SF link), E1 start/continue (1) / stop (0):
//   velocity (increments per SF cycle): internal DD4 x Tsf / DW2 (DD4 increments per DW2 time),
//   or external = the source's increments per SF cycle (BA bit0); times the override MW[DW8] / 1024
//   (0 = no output: the position holds at once);
//   continuous (BA bit1 = 0): ramp up on E1 = 1, ramp down to rest on E1 = 0, forever;
//   sequence (BA bit1 = 1): an E1 0->1 edge at rest starts a sequence of DD4 increments that ramps
//   up from rest and ramps down to end at rest exactly at DD4 (the velocity never above the one
//   that still stops in the rest, (sqrt(dv^2 + 8 dv d) - dv) / 2); with
//   SfOptions::fgen_sequence_without_ramps it starts at full velocity and stops at DD4 without a
//   ramp (the literal reading of the manual's exception "beginning and end of a sequence");
//   E1 = 0 interrupts with the ramp, E1 = 1 continues the rest with the ramp;
//   the ramp is DD6, or DD24 while E2 = 1 with BA bit2.
// Feedback zeroing (fct bit1): at each start the position feedback of the AWs in DW9 is taken as
// zero; ED 128 + 4(n-1) shows AWn's feedback relative to it every cycle. Position monitoring
// (fct bit2): A2..A8 = 1 while the k-th selected AW (ascending) is beyond position limit k
// (DD10..DD22), on the relative feedback when zeroing is on. A1 = 1 at rest, 0 while outputting.
// The output is a 32-bit position continuing from the sink's value at START (no jump); the
// velocity's fractional increments are carried, so nothing drifts.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"

namespace hil::controllers::amkasyn {
namespace {

class Fgen final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    fct_ = cmd.dl(0);
    if (fct_ > 7) return start_error("FGEN", "DL0 fct", fct_, "0..7 (bit0 generator, bit1 zeroing, bit2 monitoring)");
    if (cmd.dl(1) > 7)
      return start_error("FGEN", "DL1 BA", cmd.dl(1),
                         "0..7 (bit0 external velocity, bit1 sequence, bit2 2 accelerations)");
    if (cmd.dw(3) != io.cycle_half_ms)
      return start_error("FGEN", "DW3 SF cycle time", cmd.dw(3), "must equal ID 2 (0.5 ms units, 1..131)");
    if (auto f = take(cmd)) return f;
    ba_ = cmd.dl(1);
    increments_ = cmd.dd(4);
    if (increments_ < 1) return start_error("FGEN", "DD4 cycle output increments", increments_, "1..2^31-1");
    override_word_ = cmd.dw(8);
    if (override_word_ != 0 && (override_word_ < 2 || override_word_ > 126 || override_word_ % 2 != 0))
      return start_error("FGEN", "DW8 override flag word address", override_word_, "0 (none) or 2, 4, ..., 126");
    aw_mask_ = cmd.dr(9);
    if (cmd.dl(9) != 0) return start_error("FGEN", "DW9 AW mask", cmd.dw(9), "bit0..7 = AW1..AW8 (high byte 0)");
    if (std::popcount(static_cast<unsigned>(aw_mask_)) > 7)
      return start_error("FGEN", "DW9 AW mask", aw_mask_, "at most 7 AWs (one per output A2..A8)");
    if ((ba_ & 1) && init.source.address == 0 && init.source.offset == 0)
      return start_error("FGEN", "source", 0, "external velocity (BA bit0) needs a 16-bit source");
    if ((fct_ & 1) && init.sink.address == 0)
      return start_error("FGEN", "sink address", 0, "the generator needs a sink");
    encoder_ = hil::motion::EncoderInput(16);
    src_prev_ = encoder_.update(static_cast<std::uint32_t>(io.source.value));
    base_ = io.sink_now;
    position_ = 0;
    frac_ = 0.0;
    v_ = 0.0;
    remaining_ = 0;
    prev_e1_ = io.e(1);
    steps_ = io.options && io.options->fgen_sequence_without_ramps;
    zero_.fill(0);
    io.a(1, true);
    return std::nullopt;
  }

  std::optional<SfFault> value_new(const DataBlock& cmd, SfIo&) override {
    if ((cmd.dl(1) & ~2) != (ba_ & ~2))
      return start_error("FGEN", "DL1 BA", cmd.dl(1), "VALUE NEW may only switch continuous <-> sequence (bit1)");
    if (auto f = take(cmd)) return f;
    ba_ = cmd.dl(1);
    return std::nullopt;
  }

  void step(SfIo& io) noexcept override {
    const std::int64_t src = encoder_.update(static_cast<std::uint32_t>(io.source.value));
    const std::int64_t src_delta = src - src_prev_;
    src_prev_ = src;
    const bool e1 = io.e(1);
    const bool rising = e1 && !prev_e1_;
    prev_e1_ = e1;
    const bool sequence = (ba_ & 2) != 0;
    if (rising && (!sequence || remaining_ == 0)) on_start(io);
    if (fct_ & 1) generate(io, e1, rising, sequence, src_delta);
    if (fct_ & 6) feedback(io);
  }

 private:
  std::optional<SfFault> take(const DataBlock& cmd) {
    cycle_time_ = cmd.dw(2);
    if (cycle_time_ < 1) return start_error("FGEN", "DW2 cycle time", cycle_time_, "1..32767 (0.5 ms units)");
    acc1_ = cmd.dd(6);
    if (acc1_ < 1 || acc1_ > 500000000) return start_error("FGEN", "DD6 acceleration", acc1_, "1..500000000 incr/s^2");
    acc2_ = cmd.dd(24);
    if ((cmd.dl(1) & 4) && (acc2_ < 1 || acc2_ > 500000000))
      return start_error("FGEN", "DD24 acceleration2", acc2_, "1..500000000 incr/s^2 (BA bit2)");
    for (std::size_t k = 0; k < 7; ++k) {
      limit_[k] = cmd.dd(10 + 2 * k);
      if (limit_[k] < 0) return start_error("FGEN", "DD10..DD22 position limit", limit_[k], "0..2^31-1 increments");
    }
    return std::nullopt;
  }

  // A start (not a continue): zero the selected feedback values, a new sequence.
  void on_start(SfIo& io) noexcept {
    if (fct_ & 2)
      for (std::size_t n = 0; n < 8; ++n)
        if ((aw_mask_ >> n) & 1) zero_[n] = io.image.aw[n].position_feedback;
    if (ba_ & 2) {
      remaining_ = increments_;
      fresh_ = true;
    }
  }

  void generate(SfIo& io, bool e1, bool rising, bool sequence, std::int64_t src_delta) noexcept {
    const int ovr = override_word_ ? io.image.mw(override_word_) : 1024;
    const double tsf_s = io.cycle_half_ms * 0.0005;
    const double acc = ((ba_ & 4) && io.e(2)) ? static_cast<double>(acc2_) : static_cast<double>(acc1_);
    const double dv = acc * tsf_s * tsf_s;  // increments per cycle, per cycle
    double v_set =
        (ba_ & 1) ? static_cast<double>(src_delta) : static_cast<double>(increments_) * io.cycle_half_ms / cycle_time_;
    v_set = v_set * ovr / 1024.0;
    if (sequence) v_set = std::fabs(v_set);  // a sequence runs forwards (DD4 > 0)
    const bool go = e1 && (!sequence || remaining_ > 0);
    if (ovr == 0) {
      v_ = 0.0;  // override 0: no output
    } else if (sequence && steps_ && fresh_ && rising) {
      v_ = v_set;  // a sequence begins at full velocity
    } else {
      double target = go ? v_set : 0.0;
      if (sequence && !steps_) {  // ramp down so that the sequence ends at rest exactly at DD4
        const double d = std::max(static_cast<double>(remaining_) - frac_, 0.0);
        target = std::min(target, (std::sqrt(dv * dv + 8.0 * dv * d) - dv) / 2.0);
      }
      v_ = v_ < target ? std::min(v_ + dv, target) : std::max(v_ - dv, target);
    }
    fresh_ = false;
    frac_ += v_;
    auto step = static_cast<std::int64_t>(std::floor(frac_));
    if (sequence) {
      step = std::clamp<std::int64_t>(step, 0, remaining_);
      remaining_ -= step;
    }
    frac_ -= static_cast<double>(step);
    if (sequence && remaining_ == 0) {  // the end of the sequence: exactly DD4, no ramp
      v_ = 0.0;
      frac_ = 0.0;
    }
    position_ += step;
    io.sink = static_cast<std::int32_t>(base_ + position_);
    io.a(1, v_ == 0.0);
  }

  void feedback(SfIo& io) noexcept {
    int k = 0;
    for (std::size_t n = 0; n < 8; ++n) {
      if (((aw_mask_ >> n) & 1) == 0) continue;
      const std::int32_t fb = io.image.aw[n].position_feedback;
      const auto rel = static_cast<std::int32_t>(static_cast<std::uint32_t>(fb) - static_cast<std::uint32_t>(zero_[n]));
      if (fct_ & 2) {
        const int ed = 128 + 4 * static_cast<int>(n);  // ED 128..ED 156
        ProcessImage::set_word(io.image.e, ed, static_cast<std::int32_t>(static_cast<std::uint32_t>(rel) >> 16));
        ProcessImage::set_word(io.image.e, ed + 2,
                               static_cast<std::int32_t>(static_cast<std::uint32_t>(rel) & 0xFFFFu));
      }
      if ((fct_ & 4) && k < 7) io.a(k + 2, ((fct_ & 2) ? rel : fb) > limit_[static_cast<std::size_t>(k)]);
      ++k;
    }
  }

  int fct_ = 0, ba_ = 0, cycle_time_ = 1, override_word_ = 0;
  std::uint8_t aw_mask_ = 0;
  std::int64_t increments_ = 1, acc1_ = 1, acc2_ = 1;
  std::array<std::int64_t, 7> limit_{};
  std::array<std::int32_t, 8> zero_{};
  hil::motion::EncoderInput encoder_{16};
  std::int64_t src_prev_ = 0;
  std::int64_t base_ = 0, position_ = 0, remaining_ = 0;
  double v_ = 0.0, frac_ = 0.0;
  bool prev_e1_ = false, fresh_ = false, steps_ = false;
};

}  // namespace

std::unique_ptr<FastFunction> make_fgen() {
  return std::make_unique<Fgen>();
}

}  // namespace hil::controllers::amkasyn
