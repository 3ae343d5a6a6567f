// SPDX-License-Identifier: MIT
// SF FIPZ (type 2, manual §3.3): time-function interpolator with binary-selected profiles.
// BA 16: a 0->1 edge on Ek starts Tab(k-1) with its cycle time; BA 17: a 0->1 edge on E1 starts
// the table selected by E2 (LSB), E3, E4 (MSB). Each run starts at t = 0 and adds its travel to
// the slave (relative moves, [inferred]); it ends at t = Te. Y = table x K / 2^n (K 1..32767).
// An edge while a table runs is ignored (the manual is silent; decision in docs/amkasyn.md).
// Tables run on hil::motion::CamTable (linear: the SF interpolation) over a TimeMaster.
#include <cmath>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"
#include "hil/motion/cam.hpp"

namespace hil::controllers::amkasyn {
namespace {

class Fipz final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    if (cmd.dl(0) != 0) return start_error("FIPZ", "DL0 fct", cmd.dl(0), "must be 0");
    ba_ = cmd.dl(1);
    if (ba_ != 16 && ba_ != 17) return start_error("FIPZ", "DL1 BA", ba_, "16 (Ek starts Tab k-1) or 17 (E1 + E2..E4)");
    sak_ = cmd.dw(2);
    if (sak_ < 0) return start_error("FIPZ", "DW2 SAK", sak_, "0 (off) or 1..32767");
    if (cmd.dw(3) != io.cycle_half_ms)
      return start_error("FIPZ", "DW3 SF cycle time", cmd.dw(3), "must equal ID 2 (0.5 ms units)");
    const int m = cmd.dw(4);
    if (m < 1 || m > 8) return start_error("FIPZ", "DW4 total table number", m, "1..8");
    shift_ = cmd.dw(6);
    if (shift_ < 0 || shift_ > 15) return start_error("FIPZ", "DW6 division exponent", shift_, "0..15");
    k_ = cmd.dd(8);
    if (k_ < 1 || k_ > 32767) return start_error("FIPZ", "DD8 multiplication factor", k_, "+1..+32767");
    if (init.sink.address == 0) return start_error("FIPZ", "sink address", 0, "FIPZ needs a sink");
    drive_ = sink_drive(init);
    tables_.clear();
    for (int t = 0; t < m; ++t) {
      const int te = cmd.dw(static_cast<std::size_t>(10 + t));
      if (te < 1) return start_error("FIPZ", "cycle time of a table in use (DW10 + table)", te, "1..32767 x 0.5 ms");
      const DataBlock* db = (*io.tables)[static_cast<std::size_t>(t)];
      if (!db) return start_error("FIPZ", "table DB", t, "Tab0..Tab(DW4-1) must exist");
      const int n = db->dw(0) - 1;
      if (n < 2 || n > 127) return start_error("FIPZ", "table DW0 points + 1", n + 1, "3..128");
      if (db->dw(1) != 0) return start_error("FIPZ", "table DW1 form", db->dw(1), "0 (Y table)");
      if (db->dd(2) != 0) return start_error("FIPZ", "table DD2 first value", db->dd(2), "must be 0");
      hil::motion::CamTableSpec spec;  // non-periodic: the slave holds at the end of the run
      for (int i = 0; i < n; ++i) {
        const std::int32_t y = db->dd(static_cast<std::size_t>(2 + 2 * i));
        if (i > 0 && std::llabs(static_cast<long long>(y) - db->dd(static_cast<std::size_t>(2 * i))) >= 32768)
          return start_error("FIPZ", "table value difference",
                             static_cast<long long>(y) - db->dd(static_cast<std::size_t>(2 * i)),
                             "|Y[i+1] - Y[i]| < 32768");
        spec.points.push_back({static_cast<double>(te) * i / (n - 1), static_cast<double>(y)});
      }
      spec.points.back().x = te;
      auto table = hil::motion::CamTable::make(spec);
      if (!table) return SfFault{SfError::start_invalid, fmt::format("FIPZ: Tab{}: {}", t, table.error())};
      tables_.push_back(std::move(*table));
    }
    base_ = io.sink_now;
    y_prev_ = base_;
    raw_done_ = 0.0;
    time_ = 0;
    running_ = false;
    prev_in_ = io.in;
    cam_ = hil::motion::CamCoupling(nullptr);
    cam_.start(0, 0.0);
    return std::nullopt;
  }

  void step(SfIo& io) noexcept override {
    time_ += io.cycle_half_ms;
    const auto rising = static_cast<std::uint8_t>(io.in & ~prev_in_);
    prev_in_ = io.in;
    if (!running_) {
      std::optional<std::size_t> t;
      if (ba_ == 16) {
        for (std::size_t k = 0; k < 8 && !t; ++k)
          if ((rising >> k) & 1) t = k;
      } else if (rising & 1) {
        t = static_cast<std::size_t>((io.e(2) ? 1 : 0) | (io.e(3) ? 2 : 0) | (io.e(4) ? 4 : 0));
      }
      if (t && *t < tables_.size()) {
        raw_done_ = cam_.slave_position();
        cam_.set_table(&tables_[*t]);
        cam_.start(time_ - io.cycle_half_ms, raw_done_, 0);  // t = 0 at this cycle's start
        running_ = true;
      }
    }
    cam_.update(time_);
    if (running_ && cam_.table_position() >= cam_.table()->length()) {
      running_ = false;  // the run ended at Te: hold there
      const double end = cam_.slave_position();
      cam_.set_table(nullptr);
      cam_.start(time_, end);
    }
    const double raw = cam_.slave_position() * static_cast<double>(k_) / static_cast<double>(1 << shift_);
    const std::int64_t y = base_ + std::llround(raw);
    io.sink = static_cast<std::int32_t>(apply_sak(io, drive_, y, y_prev_, sak_));
    y_prev_ = y;
  }

 private:
  int ba_ = 16, sak_ = 0, drive_ = -1, shift_ = 0;
  std::int64_t k_ = 1;
  std::vector<hil::motion::CamTable> tables_;
  hil::motion::CamCoupling cam_{nullptr};
  std::int64_t time_ = 0, base_ = 0, y_prev_ = 0;
  double raw_done_ = 0.0;
  bool running_ = false;
  std::uint8_t prev_in_ = 0;
};

}  // namespace

std::unique_ptr<FastFunction> make_fipz() {
  return std::make_unique<Fipz>();
}

}  // namespace hil::controllers::amkasyn
