// SPDX-License-Identifier: MIT
// SF STDFKT (type 3, manual §3.4): VARSYNC (electronic gear with binary-selected or online ratio,
// on hil::motion::Gear: remainders carried, no drift) and DIGDREH (digital speed switch).
#include <cmath>

#include "hil/controllers/amkasyn/sf_types.hpp"

namespace hil::controllers::amkasyn {

int sak_factor(double id2_ms, double id104_rpm, bool external) noexcept {
  if (!(id2_ms > 0) || !(id104_rpm > 0)) return 0;
  const double base = 7680000.0 / id2_ms / id104_rpm;
  return static_cast<int>(std::floor(base + (external ? 256.0 : 128.0 * (1.0 + 1.0 / id2_ms)) + 1e-9));
}

std::int64_t sak_lead(std::int64_t y, std::int64_t y_prev, int sak) noexcept {
  if (sak == 0) return y;
  const std::int64_t n = static_cast<std::int64_t>(sak) * (y - y_prev);
  const std::int64_t lead = n >= 0 ? (n + 64) / 128 : -((-n + 64) / 128);
  return y + lead;
}

std::int64_t apply_sak(SfIo& io, int drive, std::int64_t y, std::int64_t y_prev, int sak) noexcept {
  const std::int64_t out = sak_lead(y, y_prev, sak);
  if (drive >= 0 && drive < 8)
    io.image.aw[static_cast<std::size_t>(drive)].sak_part = static_cast<std::int32_t>(out - y);
  return out;
}

namespace {

class StdFkt final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    fct_ = cmd.dl(0);
    ba_ = cmd.dl(1);
    if (fct_ == 2) {  // DIGDREH
      if (ba_ != 0) return start_error("DIGDREH", "DL1 BA", ba_, "must be 0 (unused)");
      n_e_ = cmd.dd(2);
      n_s_ = 0;
      prev_e2_ = io.e(2);
      return std::nullopt;
    }
    if (fct_ != 1) return start_error("STDFKT", "DL0 fct", fct_, "must be 1 VARSYNC or 2 DIGDREH");
    if (ba_ > 3) return start_error("VARSYNC", "DL1 BA", ba_, "must be 0..3");
    sak_ = cmd.dw(2);
    if (sak_ < 0) return start_error("VARSYNC", "DW2 SAK", sak_, "0 (off) or 1..32767");
    if (init.sink.address == 0) return start_error("VARSYNC", "sink address", 0, "VARSYNC needs a sink (SWQ1/SWQ2)");
    drive_ = sink_drive(init);
    if (ba_ == 3) {
      if (cmd.dw(3) != io.cycle_half_ms)
        return start_error("VARSYNC", "DW3 SF cycle time", cmd.dw(3), "must equal ID 2 (0.5 ms units)");
      word_ = cmd.dr(4) & ~1;  // odd addresses act as the next lower even one
      from_ew_ = cmd.dl(4) == 1;
      if (cmd.dl(4) > 1) return start_error("VARSYNC", "DL4 word attribute", cmd.dl(4), "0 MW or 1 EW");
    } else {
      for (std::size_t k = 0; k < 8; ++k) m_[k] = cmd.dw(4 + 2 * k);
    }
    encoder_ = hil::motion::EncoderInput(io.source.wide ? 32 : 16);
    const std::int64_t master = encoder_.update(static_cast<std::uint32_t>(io.source.value));
    ratio_ = initial_ratio(io);
    gear_ = hil::motion::Gear({ratio_, 10000});
    gear_.start(master, io.sink_now);
    y_prev_ = io.sink_now;
    prev_e1_ = io.e(1);
    if (ba_ == 1) io.a(1, false);
    return std::nullopt;
  }

  void step(SfIo& io) noexcept override {
    if (fct_ == 2) {
      step_digdreh(io);
      return;
    }
    const std::int64_t master = encoder_.update(static_cast<std::uint32_t>(io.source.value));
    const int m = select(io);
    if (m != ratio_) {
      ratio_ = m;
      (void)gear_.change({{m, 10000}, 0, {}});  // a step, from the last master position
    }
    gear_.update(master);
    const std::int64_t y = gear_.slave_inc();
    io.sink = static_cast<std::int32_t>(apply_sak(io, drive_, y, y_prev_, sak_));
    y_prev_ = y;
  }

 private:
  int initial_ratio(SfIo& io) const {
    switch (ba_) {
      case 0:
        return io.e(1) ? m_[1] : m_[0];
      case 2: {
        const int sel = (io.e(1) ? 1 : 0) | (io.e(2) ? 2 : 0);
        return sel == 3 ? m_[0] : m_[static_cast<std::size_t>(sel)];
      }
      case 3:
        return from_ew_ ? io.image.ew(word_) : io.image.mw(word_);
      default:
        return m_[0];
    }
  }

  int select(SfIo& io) {
    const bool e1 = io.e(1);
    int m = ratio_;
    switch (ba_) {
      case 0:  // level: E1 selects m1 / m2; A1 = E1
        m = e1 ? m_[1] : m_[0];
        io.a(1, e1);
        break;
      case 1:  // edge of E1 takes E2 (LSB)..E4 -> m1..m8; A1 acknowledges, 0 while E1 = 0
        if (e1 && !prev_e1_) {
          const int sel = (io.e(2) ? 1 : 0) | (io.e(3) ? 2 : 0) | (io.e(4) ? 4 : 0);
          m = m_[static_cast<std::size_t>(sel)];
          io.a(1, true);
        } else if (!e1) {
          io.a(1, false);
        }
        break;
      case 2: {  // E2E1: 00 m1, 01 m2, 10 m3, 11 unchanged
        const int sel = (e1 ? 1 : 0) | (io.e(2) ? 2 : 0);
        if (sel != 3) m = m_[static_cast<std::size_t>(sel)];
        break;
      }
      case 3:  // online ratio from MW/EW every cycle
        m = from_ew_ ? io.image.ew(word_) : io.image.mw(word_);
        break;
      default:
        break;
    }
    prev_e1_ = e1;
    return m;
  }

  void step_digdreh(SfIo& io) noexcept {
    // E1 enable, E2 start (edge), E3 stop (level, dominant); A1 = 1 while the output is 0.
    const bool e1 = io.e(1), e2 = io.e(2), e3 = io.e(3);
    if (!e1 || e3)
      n_s_ = 0;
    else if (e2 && !prev_e2_)
      n_s_ = n_e_;
    prev_e2_ = e2;
    io.sink = n_s_;
    io.a(1, n_s_ == 0);
  }

  int fct_ = 0, ba_ = 0, sak_ = 0, drive_ = -1;
  std::array<int, 8> m_{};
  int word_ = 0;
  bool from_ew_ = false;
  int ratio_ = 0;
  bool prev_e1_ = false, prev_e2_ = false;
  hil::motion::EncoderInput encoder_{16};
  hil::motion::Gear gear_{};
  std::int64_t y_prev_ = 0;
  std::int32_t n_e_ = 0, n_s_ = 0;
};

}  // namespace

std::unique_ptr<FastFunction> make_stdfkt() {
  return std::make_unique<StdFkt>();
}

}  // namespace hil::controllers::amkasyn
