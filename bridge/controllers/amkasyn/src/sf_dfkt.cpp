// SPDX-License-Identifier: MIT
// SF DFKT (type 4, manual §3.5): output speed = table(input speed) x V (or V/V_N), with
// mirroring / clamping below 0, clamping / extrapolation above the table end, ratio and output
// limits, status bits, binary start/stop and strobed table/ratio switching, output table Tab7.
// Units: 32-bit speeds (absolute input, SWQ2 output) in 0.0001 rpm (digest §2); table values,
// n_end and the output limits in rpm.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"

namespace hil::controllers::amkasyn {
namespace {

class Dfkt final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb&, SfIo& io) override {
    ba_ = cmd.dl(1);
    if (ba_ > 7) return start_error("DFKT", "DL1 BA", ba_, "0..7 (bit0 angle growth, bit1 binary inputs, bit2 V/V_N)");
    tables_ = cmd.dw(4);
    if (tables_ < 0 || tables_ > 7) return start_error("DFKT", "DW4 number of speed tables", tables_, "0..7");
    for (int t = 0; t < tables_; ++t) {
      const DataBlock* tab = (*io.tables)[static_cast<std::size_t>(t)];
      if (!tab) return start_error("DFKT", "speed table DB", t, "Tab0..Tab(DW4-1) must exist");
      const int n = tab->dw(0) - 1;
      if (n < 2 || n > 127) return start_error("DFKT", "speed table DW0 points + 1", n + 1, "3..128");
      if (tab->dw(1) != 0) return start_error("DFKT", "speed table DW1", tab->dw(1), "must be 0");
    }
    if (auto f = take(cmd, true)) return f;
    cycle_ = cmd.dw(3);
    if ((ba_ & 1) && cycle_ != io.cycle_half_ms)
      return start_error("DFKT", "DW3 SF cycle time", cycle_, "must equal the SF cycle in the angle-growth mode");
    active_ = pending_active_;
    prev_lo_ = static_cast<std::int16_t>(io.source.value & 0xFFFF);
    running_ = (ba_ & 2) == 0;  // with binary inputs the slave waits for E1
    prev_e2_ = io.e(2);
    io.a(1, !running_);
    io.a(2, false);
    return std::nullopt;
  }

  std::optional<SfFault> value_new(const DataBlock& cmd, SfIo&) override { return take(cmd, false); }

  void reset(SfIo& io) noexcept override {
    io.sink = 0;  // RESET stops the driven axis; the sink is released
    io.a(1, true);
  }

  void step(SfIo& io) noexcept override {
    // Input speed in rpm.
    double n_in = 0.0;
    if (ba_ & 1) {
      const auto lo = static_cast<std::int16_t>(io.source.value & 0xFFFF);
      const auto d = static_cast<std::int16_t>(static_cast<std::uint16_t>(lo - prev_lo_));
      prev_lo_ = lo;
      n_in = static_cast<double>(d) * 120000.0 / (static_cast<double>(resolution_) * cycle_);
    } else {
      n_in = static_cast<double>(io.source.value) / 10000.0;
    }
    if (ba_ & 2) {
      running_ = io.e(1);
      const bool e2 = io.e(2);
      if (e2 && !prev_e2_) {  // strobe: table selection E3 (LSB).. and the VALUE NEW factors
        int sel = (io.e(3) ? 1 : 0) | (io.e(4) ? 2 : 0);
        if (tables_ > 3 && io.e(5)) sel |= 4;
        active_ = sel <= tables_ ? sel : active_;
        mul_ = pending_mul_;
        div_ = pending_div_;
        io.a(2, true);
      } else if (!e2 && prev_e2_) {
        io.a(2, false);
      }
      prev_e2_ = e2;
    }
    int status = 0;
    double out = 0.0;
    const double v = static_cast<double>(mul_) / static_cast<double>(div_);
    if (active_ == 0) {
      out = n_in * v;
    } else {
      const DataBlock& tab = *(*io.tables)[static_cast<std::size_t>(active_ - 1)];
      double vn = 1.0;
      if (ba_ & 4) vn = point(tab, tab.dw(0) - 2) / static_cast<double>(n_end_);
      out = lookup(tab, n_in, status) * v / (vn != 0.0 ? vn : 1.0);
    }
    // Ratio out/in limits, then the output speed limits.
    if (n_in != 0.0) {
      const double ratio = out / n_in;
      const double hi = static_cast<double>(ratio_max_) / ratio_div_, lo = static_cast<double>(ratio_min_) / ratio_div_;
      if (ratio > hi) {
        out = hi * n_in;
        status |= 1;
      } else if (ratio < lo) {
        out = lo * n_in;
        status |= 2;
      }
    }
    if (out > out_max_) {
      out = out_max_;
      status |= 4;
    } else if (out < out_min_) {
      out = out_min_;
      status |= 8;
    }
    if (!running_) out = 0.0;
    io.a(1, !running_);
    io.sink = static_cast<std::int32_t>(std::llround(out * 10000.0));
    last_out_rpm_ = out;
    // Output table Tab7 (semaphore DR0 = 1: the user is reading, no update).
    if (DataBlock* t7 = (*io.tables)[7]; t7 && t7->dr(0) == 0) {
      t7->set_dw(1, status);
      t7->set_dw(2, mul_);
      t7->set_dw(3, div_);
    }
    status_ = status;
  }

 private:
  static double point(const DataBlock& tab, int k) {  // k = 0.. (point k+1 sits in DD2(k+1), low word)
    return static_cast<std::int16_t>(tab.uw(static_cast<std::size_t>(2 * (k + 1))));
  }
  [[nodiscard]] double table_pos(const DataBlock& tab, double n, int& status) const {
    const int N = tab.dw(0) - 1;
    const double h = static_cast<double>(n_end_) / (N - 1);
    if (n > n_end_) {
      status |= 16;
      if (above_ == 0) return point(tab, N - 1);
      return point(tab, N - 1) + (point(tab, N - 1) - point(tab, N - 2)) * (n - n_end_) / h;
    }
    const int i = std::min(static_cast<int>(n / h), N - 2);
    return point(tab, i) + (point(tab, i + 1) - point(tab, i)) * (n - i * h) / h;
  }
  [[nodiscard]] double lookup(const DataBlock& tab, double n, int& status) const {
    if (n >= 0) return table_pos(tab, n, status);
    status |= 32;
    if (below_ == 2) return -table_pos(tab, -n, status);
    return point(tab, 0);
  }

  std::optional<SfFault> take(const DataBlock& cmd, bool at_start) {
    const int active = cmd.dw(5);
    if (active < 0 || active > tables_) return start_error("DFKT", "DW5 active table", active, "0 (none) .. DW4");
    const int div = cmd.dw(6), mul = cmd.dw(8);
    if (div < 1) return start_error("DFKT", "DW6 division factor", div, "1..32767");
    const int res = cmd.uw(10);
    if ((ba_ & 1) && res < 1) return start_error("DFKT", "DW10 input encoder resolution", res, "1..65535");
    const int n_end = cmd.dw(11);
    if (n_end < 1) return start_error("DFKT", "DW11 input speed final value", n_end, "1..32767 rpm");
    const int out_max = cmd.dw(12), out_min = cmd.dw(14);
    if (out_max < 0) return start_error("DFKT", "DW12 max output speed", out_max, "0..32767 rpm");
    if (out_min > 0) return start_error("DFKT", "DW14 min output speed", out_min, "-32767..0 rpm");
    const int rdiv = cmd.dw(20);
    if (rdiv < 1) return start_error("DFKT", "DW20 ratio division factor", rdiv, "1..32767");
    const int below = cmd.dw(22), above = cmd.dw(23);
    if (below != 0 && below != 2)
      return start_error("DFKT", "DW22 continuation below", below, "0 limit or 2 mirroring");
    if (above != 0 && above != 1)
      return start_error("DFKT", "DW23 continuation above", above, "0 limit or 1 extrapolation");
    // With binary inputs the table is switched by the strobe and the factors wait for it.
    if (at_start || (ba_ & 2) == 0) pending_active_ = active;
    if (!at_start && (ba_ & 2) == 0) active_ = active;
    pending_div_ = div;
    pending_mul_ = mul;
    if (at_start || (ba_ & 2) == 0) {
      div_ = div;
      mul_ = mul;
    }
    resolution_ = res;
    n_end_ = n_end;
    out_max_ = out_max;
    out_min_ = out_min;
    ratio_max_ = cmd.dw(16);
    ratio_min_ = cmd.dw(18);
    ratio_div_ = rdiv;
    below_ = below;
    above_ = above;
    return std::nullopt;
  }

  int ba_ = 0, tables_ = 0, active_ = 0, pending_active_ = 0;
  int mul_ = 1, div_ = 1, pending_mul_ = 1, pending_div_ = 1;
  int resolution_ = 1, n_end_ = 1, out_max_ = 0, out_min_ = 0;
  int ratio_max_ = 0, ratio_min_ = 0, ratio_div_ = 1, below_ = 0, above_ = 0, cycle_ = 2;
  std::int16_t prev_lo_ = 0;
  bool running_ = false, prev_e2_ = false;
  int status_ = 0;
  double last_out_rpm_ = 0.0;
};

}  // namespace

std::unique_ptr<FastFunction> make_dfkt() {
  return std::make_unique<Dfkt>();
}

}  // namespace hil::controllers::amkasyn
