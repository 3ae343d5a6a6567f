// SPDX-License-Identifier: MIT
// SF REGL (type 6, manual §3.7): PID controller. One control cycle (every SF cycle, or only on a
// 0->1 edge of E1 / E4 with BA bit1 "external sync"; the output holds in between):
//   w1 = DW16 ? MW[DW16] : DW18                            command value source1
//   x  = source (16 bit); without DL5 bit1 a 12-bit ADC value in offset binary (0x800 = 0) is
//        converted to two's complement; DL5 bit0 negates; DR5 1 masks the 2 LSBs, 2 averages the
//        last 4 samples
//   e  = (S1 ? w1 : 0) - x
//   sums in 1/256: P = Kp e, I += Ki e (|I| <= 256 i_max, only while S2 is closed), D = Kd (e - e_prev)
//   u  = S2 ? v (P + I + D) / 256 : 0   (v = output gain; BA bit5 clears I while S2 is open)
//   w2 = DW17 ? MD[DW17] : DD20                           command value source2 (feed-forward)
//   BA bit4 = 0: y = clamp(u) + (S3 ? w2 : 0);  bit4 = 1: y = clamp(u + (S3 ? w2 : 0))
//   clamp to [BA bit3 ? 0 : -ymax, BA bit2 ? 0 : +ymax]; A1 = positive, A2 = negative limitation.
// S1..S3 = DW4 bits 0..2, or E1..E3 with BA bit0. Tn = Tsf Kp/Ki, Tv = Tsf Kd/Kp (the manual's
// relations hold for these sums). Decisions (docs/amkasyn.md): the ADC format, S1 gating w1, the
// first control cycle without a derivative kick (e_prev = e), rounding half away from zero.
#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"

namespace hil::controllers::amkasyn {
namespace {

std::int64_t div_round(std::int64_t n, std::int64_t d) noexcept {
  return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d);
}

class Regl final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    if (cmd.dl(0) != 0) return start_error("REGL", "DL0 fct", cmd.dl(0), "must be 0 (PID controller)");
    if (cmd.dl(1) > 63) return start_error("REGL", "DL1 BA", cmd.dl(1), "0..63 (bits 0..5)");
    if (cmd.dw(3) < 0 || cmd.dw(3) > 131)
      return start_error("REGL", "DW3 SF cycle time", cmd.dw(3), "0..131 (0.5 ms units; not used)");
    filter_ = cmd.dr(5);
    if (filter_ > 2) return start_error("REGL", "DR5 filter type", filter_, "0 none, 1 mask 2 LSBs, 2 mean of 4");
    assess_ = cmd.dl(5);
    if (assess_ > 3)
      return start_error("REGL", "DL5 source assessment", assess_, "bit0 negate, bit1 no ADC conversion");
    if (init.sink.address == 0) return start_error("REGL", "sink address", 0, "REGL needs a sink (SWQ2, MD or 255)");
    ba_ = cmd.dl(1);
    if (auto f = take(cmd)) return f;
    i256_ = 0;
    e_prev_ = 0;
    first_ = true;
    hist_.fill(0);
    hist_n_ = 0;
    hist_i_ = 0;
    prev_trigger_ = trigger(io);
    io.a(1, false);
    io.a(2, false);
    return std::nullopt;
  }

  std::optional<SfFault> value_new(const DataBlock& cmd, SfIo&) override {
    if (auto f = take(cmd)) return f;
    ba_ = (ba_ & ~12) | (cmd.dl(1) & 12);  // only the limit selection (bits 2/3) of the BA
    return std::nullopt;
  }

  void step(SfIo& io) noexcept override {
    if (ba_ & 2) {  // external sync: a control cycle only on a positive edge
      const bool t = trigger(io);
      const bool edge = t && !prev_trigger_;
      prev_trigger_ = t;
      if (!edge) return;
    }
    const bool s1 = (ba_ & 1) ? io.e(1) : (switches_ & 1) != 0;
    const bool s2 = (ba_ & 1) ? io.e(2) : (switches_ & 2) != 0;
    const bool s3 = (ba_ & 1) ? io.e(3) : (switches_ & 4) != 0;
    const std::int64_t w1 = w1_word_ ? io.image.mw(w1_word_) : w1_;
    const std::int64_t x = feedback(io.source.value);
    const std::int64_t e = (s1 ? w1 : 0) - x;
    if (first_) e_prev_ = e;
    first_ = false;
    std::int64_t u = 0;
    if (s2) {
      i256_ += ki_ * e;
      const std::int64_t lim = i_max_ * 256;
      i256_ = i256_ > lim ? lim : (i256_ < -lim ? -lim : i256_);
      const std::int64_t sum = kp_ * e + i256_ + kd_ * (e - e_prev_);
      u = div_round(gain_ * sum, 256);
    } else if (ba_ & 32) {
      i256_ = 0;  // "delete integrator"
    }
    e_prev_ = e;
    const std::int64_t w2 = s3 ? (w2_dword_ ? io.image.md(w2_dword_) : w2_) : 0;
    const std::int64_t hi = (ba_ & 4) ? 0 : y_max_, lo = (ba_ & 8) ? 0 : -y_max_;
    std::int64_t y = (ba_ & 16) ? u + w2 : u;
    bool pos = false, neg = false;
    if (y > hi) {
      y = hi;
      pos = true;
    } else if (y < lo) {
      y = lo;
      neg = true;
    }
    if ((ba_ & 16) == 0) y += w2;
    io.sink = static_cast<std::int32_t>(y);
    io.a(1, pos);
    io.a(2, neg);
  }

 private:
  std::optional<SfFault> take(const DataBlock& cmd) {
    switches_ = cmd.dw(4);
    if (switches_ < 0 || switches_ > 7) return start_error("REGL", "DW4 switch bit mask", switches_, "0..7 (S1..S3)");
    kp_ = cmd.dw(6);
    ki_ = cmd.dw(7);
    kd_ = cmd.dw(8);
    if (kp_ < 0 || kp_ > 16383) return start_error("REGL", "DW6 Kp", kp_, "0..16383 (1/256)");
    if (ki_ < 0 || ki_ > 16383) return start_error("REGL", "DW7 Ki", ki_, "0..16383 (1/256)");
    if (kd_ < 0 || kd_ > 16383) return start_error("REGL", "DW8 Kd", kd_, "0..16383 (1/256)");
    y_max_ = cmd.dd(10);
    if (y_max_ < 0 || y_max_ > (1 << 30) - 1) return start_error("REGL", "DD10 output limit", y_max_, "0..2^30-1");
    gain_ = cmd.dw(12);
    if (gain_ == 0) return start_error("REGL", "DW12 output gain", 0, "-32768..-1 or 1..32767 (0 is not allowed)");
    i_max_ = cmd.dd(14);
    if (i_max_ < 0 || i_max_ > (1 << 21) - 1) return start_error("REGL", "DD14 integration limit", i_max_, "0..2^21-1");
    w1_word_ = cmd.dw(16);
    if (w1_word_ != 0 && (w1_word_ < 2 || w1_word_ > 126 || w1_word_ % 2 != 0))
      return start_error("REGL", "DW16 MW address source1", w1_word_, "0 (use DW18) or 2, 4, ..., 126");
    w2_dword_ = cmd.dw(17);
    if (w2_dword_ != 0 && (w2_dword_ < 4 || w2_dword_ > 124 || w2_dword_ % 4 != 0))
      return start_error("REGL", "DW17 MD address source2", w2_dword_, "0 (use DD20) or 4, 8, ..., 124");
    w1_ = cmd.dw(18);
    w2_ = cmd.dd(20);
    return std::nullopt;
  }

  [[nodiscard]] bool trigger(const SfIo& io) const noexcept { return io.e((ba_ & 1) ? 4 : 1); }

  std::int64_t feedback(std::int32_t raw) noexcept {
    std::int64_t x = static_cast<std::int16_t>(raw & 0xFFFF);
    if ((assess_ & 2) == 0) x = static_cast<std::int64_t>(raw & 0xFFF) - 2048;  // 12-bit offset binary
    if (assess_ & 1) x = -x;
    if (filter_ == 1) x &= ~std::int64_t{3};
    if (filter_ == 2) {
      hist_[static_cast<std::size_t>(hist_i_)] = x;
      hist_i_ = (hist_i_ + 1) % 4;
      if (hist_n_ < 4) ++hist_n_;
      std::int64_t s = 0;
      for (int k = 0; k < hist_n_; ++k) s += hist_[static_cast<std::size_t>(k)];
      x = div_round(s, hist_n_);
    }
    return x;
  }

  int ba_ = 0, filter_ = 0, assess_ = 0, switches_ = 0;
  std::int64_t kp_ = 0, ki_ = 0, kd_ = 0, y_max_ = 0, gain_ = 1, i_max_ = 0;
  int w1_word_ = 0, w2_dword_ = 0;
  std::int64_t w1_ = 0, w2_ = 0;
  std::int64_t i256_ = 0, e_prev_ = 0;
  bool first_ = true, prev_trigger_ = false;
  std::array<std::int64_t, 4> hist_{};
  int hist_i_ = 0, hist_n_ = 0;
};

}  // namespace

std::unique_ptr<FastFunction> make_regl() {
  return std::make_unique<Regl>();
}

}  // namespace hil::controllers::amkasyn
