// SPDX-License-Identifier: MIT
// SF CAM (type 12, "NOCK", manual §3.13): up to 56 on/off cams on 8 tracks, absolute /
// incremental-modulo / time input, per-track offsets (summed changes), dead-time lead and
// monoflop; the cam table (Tab0) may change online. Hysteresis H (V02.13, DW16..DW23 x 100
// increments) per track, per cam a direction-dependent state machine (digest §3.13):
//   positive rules: forward X_On -> 1, X_Off -> 0; backward X_Off - H -> 1, X_On - H -> 0;
//   negative rules: backward X_Off -> 1, X_On -> 0; forward X_On + H -> 1, X_Off + H -> 0;
//   the positive rules switch to the negative ones at a reversal after the cam was passed by H
//   (X_Free = X_Off + H), and back at a reversal after X_On - H; a new approach resets X_Free.
// Thresholds act when the track position crosses them (a cycle's step, modulo-aware).
#include <cmath>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"
#include "hil/controllers/amkasyn/track_chain.hpp"
#include "hil/motion/gear_ratio.hpp"

namespace hil::controllers::amkasyn {
namespace {

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
      hyst_[k] = 100LL * cmd.uw(16 + k);
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
    // Hysteresis constraints (BA 1): H < modulo - (X_Off - X_On), or H < X_On - X_Off for a wrapping cam.
    for (std::size_t k = 0, cam = 0; k < 8; ++k)
      for (int c = 0; c < counts_[k]; ++c, ++cam) {
        const std::int64_t on = tab->dd(32 + 4 * cam), off = tab->dd(34 + 4 * cam);
        const std::int64_t room = off > on ? modulo_ - (off - on) : on - off;
        if (ba_ == 1 && hyst_[k] > 0 && on != off && hyst_[k] >= room)
          return SfFault{SfError::start_invalid,
                         fmt::format("CAM: DW{} hysteresis track{} = {} x 100 increments: must be below {} for cam "
                                     "{} (On {}, Off {}, modulo {})",
                                     16 + k, k, hyst_[k] / 100, room, cam, on, off, modulo_)};
        hstate_[cam] = {};
      }
    first_ = true;
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
        x_ = motion::floor_mod(x_ + d, m);
        v = d;
        break;
      }
      default:
        x_ = motion::floor_mod(x_ + io.cycle_half_ms, m);
        v = io.cycle_half_ms;
        break;
    }
    lead_.push(v);
    std::size_t cam = 0;
    for (std::size_t k = 0; k < static_cast<std::size_t>(tracks_); ++k) {
      const std::int16_t now = tab->dw(8 + k);
      off_[k] += static_cast<std::int16_t>(static_cast<std::uint16_t>(now - prev_off_[k]));
      prev_off_[k] = now;
      if (ba_ != 0) off_[k] = motion::floor_mod(off_[k], m);
      const double lead = lead_.lead(tab->dw(16 + k), io.cycle_half_ms);
      double x = static_cast<double>(x_ + off_[k]) + lead;
      if (ba_ != 0)
        x = std::fmod(std::fmod(x, static_cast<double>(m)) + static_cast<double>(m), static_cast<double>(m));
      double step = first_ ? 0.0 : x - xprev_[k];
      if (ba_ != 0 && m > 0) {  // the shorter way round the modulo
        const double md = static_cast<double>(m);
        if (step > md / 2) step -= md;
        if (step < -md / 2) step += md;
      }
      xprev_[k] = x;
      bool on = false;
      for (int c = 0; c < counts_[k]; ++c, ++cam) {
        const double x_on = tab->dd(32 + 4 * cam), x_off = tab->dd(34 + 4 * cam);
        if (x_on == x_off) continue;                                                            // inactive (spare) cam
        const bool level = x_on < x_off ? (x >= x_on && x < x_off) : (x >= x_on || x < x_off);  // wraps round
        if (hyst_[k] == 0 || first_) {
          hstate_[cam].s = level;
          on = on || level;
          continue;
        }
        on = hysteresis(hstate_[cam], x - step, x, x_on, x_off < x_on ? x_off + static_cast<double>(m) : x_off,
                        static_cast<double>(hyst_[k]), ba_ != 0 ? static_cast<double>(m) : 0.0) ||
             on;
      }
      const auto out = chain_[k].step(modes_[k], on, io.e(static_cast<int>(k) + 1), tab->dw(24 + k), io.cycle_half_ms);
      if (out)
        io.a(static_cast<int>(k) + 1, *out);
      else
        io.out_owned = static_cast<std::uint8_t>(io.out_owned & ~(1u << k));
    }
    io.sink = static_cast<std::int32_t>(off_[tab->dr(1) & 7]);
    first_ = false;
  }

 private:
  struct Hysteresis {
    bool s = false, negative = false, free = false;
  };

  // One cam with hysteresis h, the track position moving from x0 to x1 (unwrapped; modulo m, or
  // 0 in the absolute mode); `off` > `on` (a wrapping cam's Off is given + m).
  static bool hysteresis(Hysteresis& st, double x0, double x1, double on, double off, double h, double m) noexcept {
    const auto crossed = [&](double t, bool up) {
      for (int k = m > 0 ? -1 : 0; k <= (m > 0 ? 1 : 0); ++k) {
        const double tk = t + k * m;
        if (up ? (x0 < tk && tk <= x1) : (x1 < tk && tk <= x0)) return true;
      }
      return false;
    };
    if (x1 > x0) {
      if (st.negative && st.free) st = {st.s, false, false};  // a reversal after X_Free: positive rules
      if (!st.negative) {
        if (crossed(on, true)) st.s = true, st.free = false;
        if (crossed(off, true)) st.s = false;
        if (crossed(off + h, true)) st.free = true;
      } else {
        if (crossed(on + h, true)) st.s = true;
        if (crossed(off + h, true)) st.s = false;
      }
    } else if (x1 < x0) {
      if (!st.negative && st.free) st = {st.s, true, false};  // a reversal after X_Free: negative rules
      if (st.negative) {
        if (crossed(off, false)) st.s = true, st.free = false;
        if (crossed(on, false)) st.s = false;
        if (crossed(on - h, false)) st.free = true;
      } else {
        if (crossed(off - h, false)) st.s = true;
        if (crossed(on - h, false)) st.s = false;
      }
    }
    return st.s;
  }

  int ba_ = 0, tracks_ = 0;
  std::array<int, 8> counts_{};
  std::array<TrackMode, 8> modes_{};
  std::array<TrackChain, 8> chain_{};
  std::array<std::int16_t, 8> prev_off_{};
  std::array<std::int64_t, 8> off_{};
  std::int64_t modulo_ = 0, period_ = 0, x_ = 0;
  std::int16_t prev_lo_ = 0;
  DeadTimeLead lead_;
  std::array<std::int64_t, 8> hyst_{};
  std::array<double, 8> xprev_{};
  std::array<Hysteresis, 56> hstate_{};
  bool first_ = true;
};

}  // namespace

std::unique_ptr<FastFunction> make_cam() {
  return std::make_unique<Cam>();
}

}  // namespace hil::controllers::amkasyn
