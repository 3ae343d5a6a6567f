// SPDX-License-Identifier: MIT
// SF FIPW (type 1, manual §3.2): function interpolator on the coupling layer's cam tables.
// The Y tables (equidistant over Xme or Te, linear: the SF interpolation) become periodic
// hil::motion::CamTables; hil::motion::CamCoupling does the cumulative continuation and the table
// switching at table ends; this class runs the operating modes' sequences:
//   BA 2 / 4      cyclic: Tab0 from START on, forever;
//   BA 26 / 132   each E1 0->1 edge runs Tab0 once from X = 0 at the edge, then stops;
//   BA 82 / 84    E1 edge clocks in: Tab0..Tab(m-1) once each, then clocked out;
//   BA 98 / 100   E1 = 1 clocks in: start tables Tab0..Tab(q-1), working table q repeated; E1 = 0
//                 clocks out through the stop tables Tab(q+1)..Tab(m-1), then rest.
// Clocking in (out) happens when X mod P <= start (stop) angle, else at the next zero passage
// ([inferred], digest §3.2.2); X is acquired from START on (X = master offset at START) and is not
// reset on clocking in. Output Y = table value x K / 2^n (rounded; the sum is scaled, so nothing
// drifts), plus the SAK lead. Printing mark control (fct bit0) and the external-master sync
// (fct bit2) are not implemented: START refuses them.
#include <cmath>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"
#include "hil/motion/cam.hpp"

namespace hil::controllers::amkasyn {
namespace {

class Fipw final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    const int fct = cmd.dl(0);
    if (fct != 0)
      return SfFault{SfError::start_invalid,
                     fmt::format("FIPW: DL0 fct = {}: printing mark control (bit0/bit1) and the external-master "
                                 "sync (bit2) are not implemented by hilbridge; use 0",
                                 fct)};
    ba_ = cmd.dl(1);
    switch (ba_) {
      case 2:
      case 26:
      case 82:
      case 98:
        time_ = false;
        break;
      case 4:
      case 132:
      case 84:
      case 100:
        time_ = true;
        break;
      default:
        return start_error("FIPW", "DL1 BA", ba_, "2, 26, 82, 98 (distance) or 4, 132, 84, 100 (time)");
    }
    sak_ = cmd.dw(2);
    if (sak_ < 0) return start_error("FIPW", "DW2 SAK", sak_, "0 (off) or 1..32767");
    if (cmd.dw(3) != io.cycle_half_ms)
      return start_error("FIPW", "DW3 SF cycle time", cmd.dw(3), "must equal ID 2 (0.5 ms units)");
    const int m = cmd.dw(4), q = cmd.dw(5);
    if (m < 1 || m > 8) return start_error("FIPW", "DW4 total table number", m, "1..8");
    const bool single = ba_ == 2 || ba_ == 4 || ba_ == 26 || ba_ == 132;
    if (single && m != 1) return start_error("FIPW", "DW4 total table number", m, "must be 1 in this BA");
    if (q < 0 || q > m - 1 || ((ba_ != 98 && ba_ != 100) && q != 0))
      return start_error("FIPW", "DW5 start table number", q, "0..m-1 (BA 98/100), else 0");
    if ((ba_ == 98 || ba_ == 100) && q > m - 1) return start_error("FIPW", "DW5", q, "q <= m - 1");
    shift_ = cmd.dw(6);
    if (shift_ < 0 || shift_ > 15) return start_error("FIPW", "DW6 division exponent", shift_, "0..15");
    k_ = cmd.dd(8);
    if (k_ < -32768 || k_ > 32767) return start_error("FIPW", "DD8 multiplication factor", k_, "-2^15..2^15-1");
    period_ = cmd.dd(10);
    if (!time_ && (period_ < 50 || period_ > 32767))
      return start_error("FIPW", "DD10 increments per revolution Xme", period_, "50..32767");
    if (time_ && (period_ < 1 || period_ > 32767LL * io.cycle_half_ms))
      return start_error("FIPW", "DD10 cycle time Te", period_, "1..32767 x SF cycle time (0.5 ms units)");
    const int offset = cmd.dw(12);
    start_angle_ = cmd.dw(14);
    stop_angle_ = cmd.dw(16);
    if (offset < 0 || offset >= period_)
      return start_error("FIPW", "DW12 master offset angle", offset, "0..Xme-1 / Te-1");
    if (start_angle_ < 0 || start_angle_ >= period_)
      return start_error("FIPW", "DW14 start angle", start_angle_, "0..P-1");
    if (stop_angle_ < 0 || stop_angle_ >= period_) return start_error("FIPW", "DW16 stop angle", stop_angle_, "0..P-1");
    if (init.sink.address == 0) return start_error("FIPW", "sink address", 0, "FIPW needs a sink");
    tables_.clear();
    for (int t = 0; t < m; ++t) {
      const DataBlock* db = (*io.tables)[static_cast<std::size_t>(t)];
      if (!db) return start_error("FIPW", "table DB", t, "Tab0..Tab(m-1) must exist");
      const int n = db->dw(0) - 1;
      if (n < 2 || n > 127) return start_error("FIPW", "table DW0 points + 1", n + 1, "3..128");
      if (db->dw(1) != 0) return start_error("FIPW", "table DW1 form", db->dw(1), "0 (FIPW has Y tables only)");
      if (db->dd(2) != 0) return start_error("FIPW", "table DD2 first value", db->dd(2), "must be 0");
      hil::motion::CamTableSpec spec;
      spec.periodic = true;
      for (int i = 0; i < n; ++i) {
        const std::int32_t y = db->dd(static_cast<std::size_t>(2 + 2 * i));
        if (i > 0 && std::llabs(static_cast<long long>(y) - db->dd(static_cast<std::size_t>(2 * i))) >= 32768)
          return start_error("FIPW", "table value difference",
                             static_cast<long long>(y) - db->dd(static_cast<std::size_t>(2 * i)),
                             "|Y[i+1] - Y[i]| < 32768");
        spec.points.push_back({static_cast<double>(period_) * i / (n - 1), static_cast<double>(y)});
      }
      spec.points.back().x = static_cast<double>(period_);  // exactly the period
      auto table = hil::motion::CamTable::make(spec);
      if (!table) return SfFault{SfError::start_invalid, fmt::format("FIPW: Tab{}: {}", t, table.error())};
      tables_.push_back(std::move(*table));
    }
    m_ = m;
    q_ = q;
    encoder_ = hil::motion::EncoderInput(io.source.wide ? 32 : 16);
    const std::int64_t master = time_ ? 0 : encoder_.update(static_cast<std::uint32_t>(io.source.value));
    time_pos_ = 0;
    origin_ = master - offset;  // X = master - origin_: the master offset angle at START
    base_ = io.sink_now;
    y_prev_ = base_;
    cam_ = hil::motion::CamCoupling(nullptr);
    cam_.start(master, 0.0);
    running_ = false;
    clock_out_ = false;
    prev_e1_ = io.e(1);
    plan_.clear();
    if (ba_ == 2 || ba_ == 4) {
      cam_.set_table(&tables_[0]);
      cam_.start(master, 0.0, offset);
      running_ = true;
    }
    return std::nullopt;
  }

  void step(SfIo& io) noexcept override {
    std::int64_t master = 0;
    if (time_) {
      time_pos_ += io.cycle_half_ms;
      master = time_pos_;
    } else {
      master = encoder_.update(static_cast<std::uint32_t>(io.source.value));
    }
    const bool e1 = io.e(1);
    const bool rising = e1 && !prev_e1_;
    prev_e1_ = e1;
    const std::int64_t x = master - origin_;
    const std::int64_t xm = ((x % period_) + period_) % period_;
    switch (ba_) {
      case 26:
      case 132:
        if (rising && !running_) {  // X = 0 at the edge, one run, then stop
          cam_.set_table(&tables_[0]);
          cam_.start(master, cam_.slave_position(), 0);
          cam_.queue({nullptr, {}});
          running_ = true;
        }
        break;
      case 82:
      case 84:
      case 98:
      case 100:
        if (e1 && !running_ && (rising || ba_ == 98 || ba_ == 100)) clock_in(master, xm);
        if ((ba_ == 98 || ba_ == 100) && running_ && !e1) clock_out_ = true;
        if ((ba_ == 98 || ba_ == 100) && running_ && e1 && clock_out_ && plan_.empty()) clock_out_ = false;
        break;
      default:
        break;
    }
    if (running_ && ba_ != 2 && ba_ != 4) feed_plan(master, xm);
    cam_.update(master);
    if (running_ && cam_.table() == nullptr && !cam_.switch_pending()) running_ = false;  // clocked out
    const double raw = cam_.slave_position() * static_cast<double>(k_) / static_cast<double>(1 << shift_);
    const std::int64_t y = base_ + std::llround(raw);
    io.sink = static_cast<std::int32_t>(sak_lead(y, y_prev_, sak_));
    y_prev_ = y;
  }

 private:
  // Clock in: at once when X mod P is inside the start window, else at the next zero passage.
  void clock_in(std::int64_t master, std::int64_t xm) {
    plan_.clear();
    for (int t = 1; t < ((ba_ == 98 || ba_ == 100) ? q_ + 1 : m_); ++t) plan_.push_back(t);
    if (xm <= start_angle_) {
      cam_.set_table(&tables_[0]);
      cam_.start(master, cam_.slave_position(), xm);
    } else {
      cam_.set_table(nullptr);
      cam_.queue({&tables_[0], master + (period_ - xm)});
    }
    clock_out_ = false;
    stopping_ = false;
    working_ = (ba_ == 98 || ba_ == 100) && q_ == 0;
    running_ = true;
  }

  // Queue the next table when none is pending: the sequence's next table, the working table
  // again (periodic: no switch needed), the stop tables, or the stop.
  void feed_plan(std::int64_t master, std::int64_t xm) {
    if (cam_.switch_pending() || cam_.table() == nullptr) return;
    if (!plan_.empty()) {
      const int t = plan_.front();
      plan_.erase(plan_.begin());
      cam_.queue({&tables_[static_cast<std::size_t>(t)], {}});
      if ((ba_ == 98 || ba_ == 100) && t == q_) working_ = true;
      return;
    }
    const bool clocked = ba_ == 98 || ba_ == 100;
    if (!clocked || stopping_) {  // auto stop / the last stop table ran: stop at its end
      stopping_ = false;
      cam_.queue({nullptr, {}});  // auto stop at the end of the last table
      return;
    }
    if (!working_ || !clock_out_) return;  // the working table repeats
    // Clock out: through the stop tables, from the working table's end or inside the stop window.
    std::optional<std::int64_t> at;
    if (xm <= stop_angle_) at = master;
    for (int t = q_ + 1; t < m_; ++t) plan_.push_back(t);
    working_ = false;
    if (plan_.empty()) {
      cam_.queue({nullptr, at});
    } else {
      const int t = plan_.front();
      plan_.erase(plan_.begin());
      cam_.queue({&tables_[static_cast<std::size_t>(t)], at});
      stopping_ = true;
    }
  }

  int ba_ = 0, sak_ = 0, shift_ = 0, m_ = 1, q_ = 0;
  std::int64_t k_ = 1, period_ = 1;
  int start_angle_ = 0, stop_angle_ = 0;
  bool time_ = false, running_ = false, clock_out_ = false, working_ = false, stopping_ = false, prev_e1_ = false;
  std::vector<hil::motion::CamTable> tables_;
  std::vector<int> plan_;
  hil::motion::CamCoupling cam_{nullptr};
  hil::motion::EncoderInput encoder_{16};
  std::int64_t time_pos_ = 0, origin_ = 0, base_ = 0, y_prev_ = 0;
};

}  // namespace

std::unique_ptr<FastFunction> make_fipw() {
  return std::make_unique<Fipw>();
}

}  // namespace hil::controllers::amkasyn
