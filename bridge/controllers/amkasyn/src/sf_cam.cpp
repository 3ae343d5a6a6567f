// SPDX-License-Identifier: MIT
// SF CAM (type 12, "NOCK", manual §3.13): up to 56 on/off cams on 8 tracks, absolute /
// incremental-modulo / time input, per-track offsets (summed changes), dead-time lead and
// monoflop; the cam table (Tab0) may change online. Hysteresis (V02.13) is not implemented:
// START refuses a non-zero hysteresis instead of ignoring it.
#include <cmath>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"
#include "hil/controllers/amkasyn/track_chain.hpp"

namespace hil::controllers::amkasyn {
namespace {

std::int64_t mod(std::int64_t v, std::int64_t m) {
  const std::int64_t r = v % m;
  return r < 0 ? r + m : r;
}

class Cam final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    ba_ = cmd.dl(1);
    if (ba_ > 2) return start_error("CAM", "DL1 BA", ba_, "0 absolute, 1 incremental, 2 time");
    if (cmd.dw(3) != io.cycle_half_ms)
      return start_error("CAM", "DW3 SF cycle time", cmd.dw(3),
                         "must equal the SF cycle (ID 2 x factor, 0.5 ms units)");
    const int mean = cmd.dw(4);
    if (mean < 0 || mean > 30000) return start_error("CAM", "DW4 dead time mean factor", mean, "0 (20), 1..30000");
    lead_.configure(mean);
    int sum = 0;
    tracks_ = 0;
    for (std::size_t k = 0; k < 8; ++k) {
      counts_[k] = k % 2 == 0 ? cmd.dr(6 + k / 2) : cmd.dl(6 + k / 2);
      if (counts_[k] > 56) return start_error("CAM", "cams on a track", counts_[k], "0..56");
      sum += counts_[k];
      if (counts_[k] > 0) tracks_ = static_cast<int>(k) + 1;
      const std::uint8_t mw = k % 2 == 0 ? cmd.dr(10 + k / 2) : cmd.dl(10 + k / 2);
      modes_[k] = TrackMode::from(mw);
      if (!modes_[k].valid_logic()) return start_error("CAM", "track mode bits 3..2", mw, "00 none, 01 AND, 10 OR");
      if (cmd.uw(16 + k) != 0)
        return SfFault{SfError::start_invalid,
                       fmt::format("CAM: DW{} hysteresis track{} = {}: hysteresis (V02.13) is not implemented by "
                                   "hilbridge; use 0",
                                   16 + k, k, cmd.uw(16 + k))};
      chain_[k].reset();
    }
    if (sum > 56) return start_error("CAM", "sum of cams", sum, "at most 56 over all tracks");
    modulo_ = cmd.dd(14);
    const DataBlock* tab = (*io.tables)[0];
    if (!tab) return start_error("CAM", "Tab0 DB", (*io.tables)[0] ? 1 : 0, "the cam table DB (Tab0) must exist");
    if (ba_ == 1 && (modulo_ <= 0 || modulo_ > (1 << 30) - 1))
      return start_error("CAM", "DD14 modulo value", modulo_, "1..2^30-1 in the incremental mode");
    if (ba_ == 2) {
      period_ = tab->dw(0);
      if (period_ < io.cycle_half_ms)
        return start_error("CAM", "Tab0 DW0 cycle time", period_, "SF cycle time..32767 (0.5 ms) in the time mode");
    }
    if (init.sink.address != 0 && init.sink.address != 129)
      return start_error("CAM", "sink address", init.sink.address, "none (0) or MD (129)");
    x_ = ba_ == 0 ? io.source.value : 0;
    prev_lo_ = static_cast<std::int16_t>(io.source.value & 0xFFFF);
    for (std::size_t k = 0; k < 8; ++k) {
      prev_off_[k] = tab->dw(8 + k);
      off_[k] = prev_off_[k];  // the offset at START counts as a change from 0 (docs/amkasyn.md)
    }
    return std::nullopt;
  }

  void step(SfIo& io) noexcept override {
    const DataBlock* tab = (*io.tables)[0];
    if (!tab) return;
    double v = 0.0;
    const std::int64_t m = ba_ == 1 ? modulo_ : period_;
    switch (ba_) {
      case 0: {
        const std::int64_t x = io.source.value;
        v = static_cast<double>(x - x_);
        x_ = x;
        break;
      }
      case 1: {
        const auto lo = static_cast<std::int16_t>(io.source.value & 0xFFFF);
        const auto d = static_cast<std::int16_t>(static_cast<std::uint16_t>(lo - prev_lo_));
        prev_lo_ = lo;
        x_ = mod(x_ + d, m);
        v = d;
        break;
      }
      default:
        x_ = mod(x_ + io.cycle_half_ms, m);
        v = io.cycle_half_ms;
        break;
    }
    lead_.push(v);
    std::size_t cam = 0;
    for (std::size_t k = 0; k < static_cast<std::size_t>(tracks_); ++k) {
      const std::int16_t now = tab->dw(8 + k);
      off_[k] += static_cast<std::int16_t>(static_cast<std::uint16_t>(now - prev_off_[k]));
      prev_off_[k] = now;
      if (ba_ != 0) off_[k] = mod(off_[k], m);
      const double lead = lead_.lead(tab->dw(16 + k), io.cycle_half_ms);
      double x = static_cast<double>(x_ + off_[k]) + lead;
      if (ba_ != 0)
        x = std::fmod(std::fmod(x, static_cast<double>(m)) + static_cast<double>(m), static_cast<double>(m));
      bool on = false;
      for (int c = 0; c < counts_[k]; ++c, ++cam) {
        const double x_on = tab->dd(32 + 4 * cam), x_off = tab->dd(34 + 4 * cam);
        if (x_on == x_off) continue;                                                      // inactive (spare) cam
        on = on || (x_on < x_off ? (x >= x_on && x < x_off) : (x >= x_on || x < x_off));  // wraps round the modulo
      }
      const auto out = chain_[k].step(modes_[k], on, io.e(static_cast<int>(k) + 1), tab->dw(24 + k), io.cycle_half_ms);
      if (out)
        io.a(static_cast<int>(k) + 1, *out);
      else
        io.out_owned = static_cast<std::uint8_t>(io.out_owned & ~(1u << k));
    }
    io.sink = static_cast<std::int32_t>(off_[tab->dr(1) & 7]);
  }

 private:
  int ba_ = 0, tracks_ = 0;
  std::array<int, 8> counts_{};
  std::array<TrackMode, 8> modes_{};
  std::array<TrackChain, 8> chain_{};
  std::array<std::int16_t, 8> prev_off_{};
  std::array<std::int64_t, 8> off_{};
  std::int64_t modulo_ = 0, period_ = 0, x_ = 0;
  std::int16_t prev_lo_ = 0;
  DeadTimeLead lead_;
};

}  // namespace

std::unique_ptr<FastFunction> make_cam() {
  return std::make_unique<Cam>();
}

}  // namespace hil::controllers::amkasyn
