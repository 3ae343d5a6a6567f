// SPDX-License-Identifier: MIT
// SF BINEA (type 8, manual §3.9): outputs by position from a point table (Tab0): A-value Px is
// output for P(x-1) < x' <= Px (Figure 29; the vector's Gray-code example), absolute /
// incremental-modulo / time input, offset (MW or DW6), dead-time lead (fct 1, BA 1), track chain.
#include <cmath>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"
#include "hil/controllers/amkasyn/track_chain.hpp"

namespace hil::controllers::amkasyn {
namespace {

class Binea final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb&, SfIo& io) override {
    fct_ = cmd.dl(0);
    ba_ = cmd.dl(1);
    if (ba_ > 2) return start_error("BINEA", "DL1 BA", ba_, "0 absolute, 1 incremental, 2 time");
    if (fct_ > 1) return start_error("BINEA", "DL0 fct", fct_, "0 none, 1 dead-time compensation");
    if (fct_ == 1 && ba_ != 1) return start_error("BINEA", "DL0 fct", fct_, "dead-time compensation needs BA 1");
    if (auto f = take(cmd, io)) return f;
    if (cmd.dw(3) != io.cycle_half_ms)
      return start_error("BINEA", "DW3 SF cycle time", cmd.dw(3), "must equal the SF cycle (0.5 ms units)");
    tracks_ = cmd.dw(4);
    if (tracks_ < 1 || tracks_ > 8) return start_error("BINEA", "DW4 tracks", tracks_, "1..8");
    for (std::size_t k = 0; k < 8; ++k) {
      modes_[k] = TrackMode::from(cmd.uw(8 + k));
      if (!modes_[k].valid_logic()) return start_error("BINEA", "track mode bits 3..2", cmd.uw(8 + k), "00, 01 or 10");
      chain_[k].reset();
    }
    const int mean = cmd.dw(16);
    if (mean < 0 || mean > 30000) return start_error("BINEA", "DW16 dead time mean factor", mean, "0 (20), 1..30000");
    lead_.configure(mean);
    const DataBlock* tab = (*io.tables)[0];
    if (!tab) return start_error("BINEA", "Tab0", 0, "the output table DB must exist");
    points_ = tab->dw(0) - 1;
    if (points_ < 1 || points_ > 63) return start_error("BINEA", "Tab0 DW0 points + 1", points_ + 1, "2..64");
    for (int x = 0; x < points_; ++x) {
      const std::int32_t p = tab->dd(static_cast<std::size_t>(4 + 4 * x));
      if (ba_ != 0 && p < 0) return start_error("BINEA", "Tab0 point", p, "0..2^31-1 in BA 1 and 2");
      if (x > 0 && p <= tab->dd(static_cast<std::size_t>(4 * x)))
        return start_error("BINEA", "Tab0 point", p, "points must increase");
    }
    modulo_ = tab->dd(static_cast<std::size_t>(4 + 4 * (points_ - 1)));
    if (ba_ != 0 && modulo_ <= 0) return start_error("BINEA", "last point (modulo)", modulo_, "must be > 0");
    acc_ = 0;
    prev_lo_ = static_cast<std::int16_t>(io.source.value & 0xFFFF);
    return std::nullopt;
  }

  std::optional<SfFault> value_new(const DataBlock& cmd, SfIo& io) override { return take(cmd, io); }

  void step(SfIo& io) noexcept override {
    const DataBlock* tab = (*io.tables)[0];
    if (!tab) return;
    const std::int32_t offset = offset_mw_ ? io.image.mw(offset_mw_) : offset_;
    double xp = 0.0;
    switch (ba_) {
      case 0:
        xp = static_cast<double>(io.source.value) + offset;
        break;
      case 1: {
        const auto lo = static_cast<std::int16_t>(io.source.value & 0xFFFF);
        const auto d = static_cast<std::int16_t>(static_cast<std::uint16_t>(lo - prev_lo_));
        prev_lo_ = lo;
        acc_ = wrap(acc_ + d);
        lead_.push(d);
        xp = static_cast<double>(acc_ + offset);
        if (fct_ == 1) xp += lead_.lead(dead_half_ms_, io.cycle_half_ms);
        xp = wrapd(xp);
        break;
      }
      default:
        acc_ = wrap(acc_ + io.cycle_half_ms);
        xp = static_cast<double>(acc_);
        break;
    }
    if (ba_ != 0 && xp == 0.0) xp = static_cast<double>(modulo_);  // 0 is the modulo point: the last interval
    int idx = points_ - 1;
    for (int x = 0; x < points_; ++x)
      if (xp <= tab->dd(static_cast<std::size_t>(4 + 4 * x))) {
        idx = x;
        break;
      }
    const std::uint8_t value = tab->dr(static_cast<std::size_t>(6 + 4 * idx));
    const int a_time = tab->dw(static_cast<std::size_t>(7 + 4 * idx));
    for (std::size_t k = 0; k < static_cast<std::size_t>(tracks_); ++k) {
      const auto out =
          chain_[k].step(modes_[k], ((value >> k) & 1) != 0, io.e(static_cast<int>(k) + 1), a_time, io.cycle_half_ms);
      if (out)
        io.a(static_cast<int>(k) + 1, *out);
      else
        io.out_owned = static_cast<std::uint8_t>(io.out_owned & ~(1u << k));
    }
    io.out_owned = static_cast<std::uint8_t>(io.out_owned & ((1u << tracks_) - 1u));
  }

 private:
  std::optional<SfFault> take(const DataBlock& cmd, SfIo&) {
    dead_half_ms_ = cmd.dw(2);
    if (dead_half_ms_ < 0 || dead_half_ms_ > 32000)
      return start_error("BINEA", "DW2 dead time", dead_half_ms_, "0..32000");
    offset_mw_ = cmd.dw(5);
    if (offset_mw_ != 0 && (offset_mw_ < 2 || offset_mw_ > 126 || offset_mw_ % 2 != 0))
      return start_error("BINEA", "DW5 offset MW address", offset_mw_, "0 (use DW6) or 2..126, even");
    offset_ = cmd.dw(6);
    return std::nullopt;
  }
  [[nodiscard]] std::int64_t wrap(std::int64_t v) const noexcept {
    const std::int64_t r = v % modulo_;
    return r < 0 ? r + modulo_ : r;
  }
  [[nodiscard]] double wrapd(double v) const noexcept {
    const double m = static_cast<double>(modulo_);
    return std::fmod(std::fmod(v, m) + m, m);
  }

  int fct_ = 0, ba_ = 0, tracks_ = 0, points_ = 0;
  int dead_half_ms_ = 0, offset_mw_ = 0;
  std::int32_t offset_ = 0;
  std::int64_t modulo_ = 1, acc_ = 0;
  std::int16_t prev_lo_ = 0;
  std::array<TrackMode, 8> modes_{};
  std::array<TrackChain, 8> chain_{};
  DeadTimeLead lead_;
};

}  // namespace

std::unique_ptr<FastFunction> make_binea() {
  return std::make_unique<Binea>();
}

}  // namespace hil::controllers::amkasyn
