// SPDX-License-Identifier: MIT
// SF FIPW (type 1, manual §3.2) and XFIPW (type 9, §3.10): function interpolators on the coupling
// layer's cam tables. The tables (Y: equidistant over Xme or Te; XFIPW also XY: pairs with the
// period as the last X; linear: the SF interpolation) become periodic hil::motion::CamTables;
// hil::motion::CamCoupling does the cumulative continuation and the switching at table ends; this
// class runs the operating modes' sequences:
//   BA 2 / 4      cyclic: Tab0 from START on, forever;
//   BA 26 / 132   each E1 0->1 edge runs Tab0 once (XFIPW: DL7 times) from X = 0 at the edge;
//   BA 82 / 84    E1 edge clocks in: Tab0..Tab(m-1) once each (XFIPW: Tab q DL7 times), then out;
//   BA 98 / 100   E1 = 1 clocks in: start tables Tab0..Tab(q-1), working table q repeated; E1 = 0
//                 clocks out through the stop tables Tab(q+1)..Tab(m-1), then rest.
// Clocking in (out) happens when X mod P (the working table's position) <= start (stop) angle, else
// at the next zero passage ([inferred], digest §3.2.2); X is acquired from START on (X = master
// offset at START) and is not reset on clocking in. Output Y = table value x K / 2^n (rounded; the
// sum is scaled, so nothing drifts), plus the SAK lead.
// XFIPW adds: code + 1 = table set switch-over (sets of m tables from Tab0 on; E_SUEn / E_SU0..2,
// A_SUK; switched at movement start and at working-table zero passages, fct bit5: after every
// table), retriggering (fct bit4: an edge during a movement is stored and restarts it seamlessly
// at its end if E1 is still 1), A1 = A_Akt (0 while a movement runs) in the triggered modes, a
// signed master offset, "setting on" (fct bit3: the output is the table's own position, y(offset)
// at START, as READ VALUE computes it) and READ VALUE (code 6).
// Both: the external-master sync (fct bit2: X := master offset at the source's next zero pulse)
// and printing mark control (fct bit0, bit1 before/after SAK; marks from the zero-pulse latch of
// the 32-bit AZ message, corrections spread over the window [SK, SK+LK] of the working table; see
// printing_mark()). With both, the master zero pulse is the latch an SF COPY copies along with the
// second input's 32-bit AZ message into MD DR7 (ProcessImage::md_zero).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"
#include "hil/motion/cam.hpp"
#include "hil/motion/gear_ratio.hpp"

namespace hil::controllers::amkasyn {
namespace {

enum class Kind : std::uint8_t { cyclic, single, sequence, clocked };

class Interpolator final : public FastFunction {
 public:
  explicit Interpolator(bool extended) noexcept : x_(extended), name_(extended ? "XFIPW" : "FIPW") {}

  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    if (auto f = configure(cmd, init, io)) return f;
    encoder_ = hil::motion::EncoderInput(io.source.wide ? 32 : 16);
    const std::int64_t master = time_ ? 0 : encoder_.update(static_cast<std::uint32_t>(io.source.value));
    time_pos_ = 0;
    origin_ = master - offset_;  // X = master - origin_: the master offset angle at START
    read_inputs(io);
    set_ = 0;
    if (kind_ == Kind::cyclic) take_set();  // movement start = START in the cyclic modes
    const double raw0 = setting_on() ? raw_at(set_, offset_) : 0.0;
    base_ = setting_on() ? 0 : io.sink_now;
    cam_ = hil::motion::CamCoupling(nullptr);
    cam_.start(master, raw0);
    running_ = clock_out_ = working_ = stopping_ = retrigger_ = repeat_queued_ = stop_queued_ = false;
    prev_e1_ = io.e(1);
    plan_.clear();
    sync_wait_ = sync_;
    if (sync_) sync_seen_ = sync_latch(io).count;  // X is assigned at the next zero pulse
    if (kind_ == Kind::cyclic && !sync_wait_) {
      cam_.set_table(&table(set_, 0));
      cam_.start(master, raw0, motion::floor_mod(offset_, period(set_, 0)));
      running_ = true;
    }
    corr_total_ = corr_applied_ = corr_active_ = corr_pending_ = corr_at_start_ = 0.0;
    active_ = pending_ = have_start_ = in_work_prev_ = mark_in_period_ = dmr_ = false;
    marks_ = 0;
    mark_seen_ = io.image.az_zero[zch_].count;
    switches_seen_ = cam_.switches();
    queued_set_ = set_;
    y_prev_ = base_ + scale(raw0);
    outputs(io);
    return std::nullopt;
  }

  std::optional<SfFault> value_new(const DataBlock& cmd, SfIo& io) override {
    if (!x_) return FastFunction::value_new(cmd, io);
    if (auto f = printing_mark_parameters(cmd)) return f;  // XFIPW: the printing mark parameters only
    if (pm_) configure_printing_mark(cmd);
    return std::nullopt;
  }

  std::expected<std::int32_t, SfFault> read_value(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    if (!x_) return FastFunction::read_value(cmd, init, io);
    if (auto f = configure(cmd, init, io)) return std::unexpected(*f);
    return static_cast<std::int32_t>(scale(raw_at(0, offset_)));
  }

  void step(SfIo& io) noexcept override {
    std::int64_t master = 0;
    if (time_) {
      time_pos_ += io.cycle_half_ms;
      master = time_pos_;
    } else {
      master = encoder_.update(static_cast<std::uint32_t>(io.source.value));
    }
    read_inputs(io);
    const bool e1 = io.e(1);
    const bool rising = e1 && !prev_e1_;
    prev_e1_ = e1;
    if (sync_wait_) {  // external-master sync: X := master offset angle at the master's zero pulse
      const ZeroPulseLatch& z = sync_latch(io);
      if (z.count == sync_seen_) {
        io.sink = static_cast<std::int32_t>(y_prev_);  // nothing moves before the sync
        return;
      }
      // The pulse's distance back from now, in the counts of the input that saw it.
      const std::int32_t now = sync_md_ >= 0 ? io.image.md(sync_md_) : io.source.value;
      origin_ = master_at(master, now, z.position) - offset_;
      sync_wait_ = false;
      if (kind_ == Kind::cyclic) {
        cam_.set_table(&table(set_, 0));
        cam_.start(master, cam_.slave_position(), motion::floor_mod(master - origin_, period(set_, 0)));
        switches_seen_ = cam_.switches();
        running_ = true;
      }
    }
    const std::int64_t x = master - origin_;
    switch (kind_) {
      case Kind::single:
        if (rising && !running_) {  // X = 0 at the edge
          take_set();
          cam_.set_table(&table(set_, 0));
          cam_.start(master, cam_.slave_position(), 0);
          switches_seen_ = cam_.switches();
          plan_ = first_plan();
          stop_queued_ = retrigger_ = false;
          running_ = true;
        } else if (rising && (fct_ & 16)) {
          retrigger_ = true;
        }
        break;
      case Kind::sequence:
        if (rising && !running_)
          clock_in(master, x);
        else if (rising && (fct_ & 16))
          retrigger_ = true;
        break;
      case Kind::clocked:
        if (e1 && !running_) clock_in(master, x);
        if (running_ && !e1) clock_out_ = true;
        if (running_ && e1 && clock_out_ && plan_.empty() && !stopping_) clock_out_ = false;
        break;
      case Kind::cyclic:
        if (set_change() && !cam_.switch_pending()) queue(desired_, 0, {});
        break;
    }
    if (running_ && kind_ != Kind::cyclic) feed_plan(master, e1);
    cam_.update(master);
    if (cam_.switches() != switches_seen_) {
      switches_seen_ = cam_.switches();
      set_ = queued_set_;
      repeat_queued_ = stop_queued_ = false;
    }
    if (running_ && cam_.table() == nullptr && !cam_.switch_pending()) running_ = false;  // clocked out
    const std::int64_t y = base_ + scale(cam_.slave_position());
    if (pm_) printing_mark(io, master);
    const auto corr = static_cast<std::int64_t>(std::llround(corr_total_ + corr_applied_));
    if (before_sak_) {  // fct bit1: the correction before the SAK
      io.sink = static_cast<std::int32_t>(apply_sak(io, drive_, y + corr, y_prev_, sak_));
      y_prev_ = y + corr;
    } else {
      io.sink = static_cast<std::int32_t>(apply_sak(io, drive_, y, y_prev_, sak_) + corr);
      y_prev_ = y;
    }
    outputs(io);
  }

 private:
  // ------------------------------------------------------------------ commanding DB and tables
  std::optional<SfFault> configure(const DataBlock& cmd, const InitDb& init, SfIo& io) {
    fct_ = cmd.dl(0);
    if (fct_ & ~(x_ ? 0x3F : 0x07))
      return start_error(name_, "DL0 fct", fct_,
                         x_ ? "bits 0..5" : "bits 0..2 (printing mark, before SAK, external sync)");
    // Printing mark control with the external sync: the master zero pulse comes on a second input
    // that an SF COPY (lower number) copies into MD DR7 (counter and its zero-pulse latch).
    sync_md_ = (fct_ & 5) == 5 ? cmd.dr(7) : -1;
    if (sync_md_ >= 0 && (sync_md_ > 124 || sync_md_ % 4 != 0))
      return start_error(name_, "DR7 MD addr. ext. sync.", sync_md_,
                         "0..124, a multiple of 4 (printing mark control with the external sync)");
    const int ba = cmd.dl(1);
    set_switch_ = x_ && ba % 2 == 1;
    switch (set_switch_ ? ba - 1 : ba) {
      case 2:
      case 4:
        kind_ = Kind::cyclic;
        break;
      case 26:
      case 132:
        kind_ = Kind::single;
        break;
      case 82:
      case 84:
        kind_ = Kind::sequence;
        break;
      case 98:
      case 100:
        kind_ = Kind::clocked;
        break;
      default:
        return start_error(name_, "DL1 BA", ba,
                           x_ ? "2, 26, 82, 98 (distance) or 4, 132, 84, 100 (time), + 1 with table set switch-over"
                              : "2, 26, 82, 98 (distance) or 4, 132, 84, 100 (time)");
    }
    const int mode = set_switch_ ? ba - 1 : ba;
    time_ = mode == 4 || mode == 132 || mode == 84 || mode == 100;
    sak_ = cmd.dw(2);
    if (sak_ < 0) return start_error(name_, "DW2 SAK", sak_, "0 (off) or 1..32767");
    if (cmd.dw(3) != io.cycle_half_ms)
      return start_error(name_, "DW3 SF cycle time", cmd.dw(3), "must equal ID 2 (0.5 ms units)");
    const int m = cmd.dw(4), q = cmd.dw(5);
    if (m < 1 || m > 8) return start_error(name_, "DW4 total table number", m, "1..8");
    if ((kind_ == Kind::cyclic || kind_ == Kind::single) && m != 1)
      return start_error(name_, "DW4 total table number", m, "must be 1 in this BA");
    if (q < 0 || q > m - 1 || (kind_ != Kind::clocked && q != 0))
      return start_error(name_, "DW5 start table number", q, "0..m-1 (BA 98/100), else 0");
    shift_ = cmd.dw(6);
    if (shift_ < 0 || shift_ > 15) return start_error(name_, "DW6 division exponent", shift_, "0..15");
    k_ = cmd.dd(8);
    if (k_ < -32768 || k_ > 32767) return start_error(name_, "DD8 multiplication factor", k_, "-2^15..2^15-1");
    cycles_ = x_ ? std::max(1, static_cast<int>(cmd.dl(7))) : 1;
    if (init.sink.address == 0) return start_error(name_, "sink address", 0, "the interpolator needs a sink");
    pm_ = (fct_ & 1) != 0;
    sync_ = (fct_ & 4) != 0;
    if ((pm_ || sync_) &&
        (init.source.address != 0 || init.source.offset < 16 || init.source.offset > 22 || init.source.offset % 2 != 0))
      return start_error(name_, "source offset", init.source.offset,
                         "printing mark control and the external sync need the 32-bit AZ message (address 0, offset "
                         "16/18/20/22) with its zero pulse");
    zch_ = static_cast<std::size_t>((init.source.offset - 16) / 2 % 4);
    if (pm_ && (time_ || set_switch_ || (!x_ && kind_ != Kind::cyclic && kind_ != Kind::clocked)))
      return start_error(
          name_, "DL1 BA", ba,
          x_ ? "printing mark control only in BA 2, 26, 82, 98" : "printing mark control only in BA 2 or 98");
    drive_ = sink_drive(init);
    m_ = m;
    q_ = q;
    int n_db = m;
    if (set_switch_) {
      n_db = 0;
      while (n_db < 8 && (*io.tables)[static_cast<std::size_t>(n_db)]) ++n_db;
      if (n_db == 0 || n_db % m != 0)
        return start_error(name_, "table DBs given at FB 207", n_db,
                           "consecutive from Tab0, a multiple of the total table number DW4 (one set = m tables)");
    }
    sets_ = n_db / m;
    tables_.clear();
    for (int t = 0; t < n_db; ++t) {
      const DataBlock* db = (*io.tables)[static_cast<std::size_t>(t)];
      if (!db) return start_error(name_, "table DB", t, "Tab0..Tab(m-1) must exist");
      auto table = parse_table(*db, t, cmd, io.cycle_half_ms);
      if (!table) return table.error();
      tables_.push_back(std::move(*table));
    }
    offset_ = cmd.dw(12);
    start_angle_ = cmd.dw(14);
    stop_angle_ = cmd.dw(16);
    for (int s = 0; s < sets_; ++s) {
      const std::int64_t p0 = period(s, 0), pw = period(s, q_);
      const bool signed_offset = x_ && !time_;
      if (offset_ >= p0 || offset_ <= -p0 || (!signed_offset && offset_ < 0))
        return start_error(name_, "DW12 master offset angle", offset_,
                           signed_offset ? "-(Xme-1)..Xme-1 of the first table" : "0..Xme-1 / Te-1 of the first table");
      if (start_angle_ < 0 || start_angle_ >= p0)
        return start_error(name_, "DW14 start angle", start_angle_, "0..P-1 of the first table");
      if (stop_angle_ < 0 || stop_angle_ >= pw)
        return start_error(name_, "DW16 stop angle", stop_angle_, "0..P-1 of the working table");
    }
    if (auto f = printing_mark_parameters(cmd)) return f;
    if (pm_) configure_printing_mark(cmd);
    return std::nullopt;
  }

  // Printing mark control (digest §3.2.4 [inferred]): s = Y_end(working table) / format length;
  // the mark's expected slave position in the working table Xm_cmd = s ((FL - ((SD - SS) mod FL))
  // mod FL); valid within s x DW23 (0 = anywhere); F from DR27; the correction window [SK, SK+LK].
  void configure_printing_mark(const DataBlock& cmd) {
    const double fl = cmd.dw(18);
    work_lift_ = static_cast<double>(scale(table(0, q_).lift()));
    const double sc = work_lift_ / fl;
    const std::int64_t sd = cmd.dd(20), ss = cmd.dw(22);
    const std::int64_t f = static_cast<std::int64_t>(fl);
    xm_cmd_ = std::round(sc * static_cast<double>(motion::floor_mod(f - motion::floor_mod(sd - ss, f), f)));
    valid_ = sc * cmd.dw(23);
    const std::int64_t p = period(0, q_);
    sk_ = cmd.dw(24);
    lk_ = cmd.dw(25);
    if (sk_ == 0 && lk_ == 0) {
      sk_ = p * 3 / 4;
      lk_ = p / 8;
    }
    md_ = cmd.dw(26);
    const int k = cmd.dr(27);
    weight_ = k == 0 ? 1.0 : k < 32 ? std::ldexp(1.0, -k) : k == 32 ? 0.0 : -std::ldexp(1.0, -(k - 128));
    every_ = std::max(1, static_cast<int>(cmd.dl(27)));
    before_sak_ = (fct_ & 2) != 0;
  }

  std::expected<hil::motion::CamTable, SfFault> parse_table(const DataBlock& db, int t, const DataBlock& cmd,
                                                            int cycle_half_ms) const {
    auto bad = [&](const char* field, long long v, const char* rule) {
      return std::unexpected(
          SfFault{SfError::start_invalid, fmt::format("{}: Tab{} {} = {}: {}", name_, t, field, v, rule)});
    };
    const std::int64_t period_max = time_ ? 32767LL * cycle_half_ms : 32767;
    const std::int64_t period_min = time_ ? 1 : 50;
    hil::motion::CamTableSpec spec;
    spec.periodic = true;
    if (db.dw(1) == 0) {  // Y table over DD10
      const int n = db.dw(0) - 1;
      if (n < 2 || n > (x_ ? 2000 : 127)) return bad("DW0 points + 1", n + 1, x_ ? "3..2001" : "3..128");
      const std::int64_t p = cmd.dd(10);
      if (p < period_min || p > period_max)
        return std::unexpected(start_error(name_, time_ ? "DD10 cycle time Te" : "DD10 increments per revolution Xme",
                                           p, time_ ? "1..32767 x SF cycle time (0.5 ms units)" : "50..32767"));
      if (db.dd(2) != 0) return bad("DD2 first value", db.dd(2), "must be 0");
      for (int i = 0; i < n; ++i) {
        const std::int64_t y = db.dd(static_cast<std::size_t>(2 + 2 * i));
        if (i > 0 && std::llabs(y - db.dd(static_cast<std::size_t>(2 * i))) >= 32768)
          return bad("value difference", y - db.dd(static_cast<std::size_t>(2 * i)), "|Y[i+1] - Y[i]| < 32768");
        spec.points.push_back({static_cast<double>(p) * i / (n - 1), static_cast<double>(y)});
      }
      spec.points.back().x = static_cast<double>(p);  // exactly the period
    } else if (db.dw(1) == 1 && x_) {                 // XY table: X_i = DD(4i-2), Y_i = DD(4i)
      const int n = db.dw(0) - 1;
      if (n < 2 || n > 999) return bad("DW0 points + 1", n + 1, "3..1000 (XY table)");
      for (int i = 1; i <= n; ++i) {
        const std::int64_t xi = db.dd(static_cast<std::size_t>(4 * i - 2)), yi = db.dd(static_cast<std::size_t>(4 * i));
        if (i == 1 && (xi != 0 || yi != 0)) return bad("DD2/DD4 first pair", xi != 0 ? xi : yi, "X1 = Y1 = 0");
        if (i > 1) {
          const std::int64_t xp = db.dd(static_cast<std::size_t>(4 * i - 6)),
                             yp = db.dd(static_cast<std::size_t>(4 * i - 4));
          if (xi <= xp) return bad("X value", xi, "X values must increase strictly");
          if (std::llabs(yi - yp) >= 32768) return bad("value difference", yi - yp, "|Y[i+1] - Y[i]| < 32768");
        }
        spec.points.push_back({static_cast<double>(xi), static_cast<double>(yi)});
      }
      const auto p = static_cast<std::int64_t>(spec.points.back().x);
      if (p < period_min || p > period_max)
        return bad("last X (the period)", p, time_ ? "1..32767 x SF cycle time" : "50 <= Xme <= 32767");
    } else {
      return bad("DW1 table form", db.dw(1), x_ ? "0 (Y table) or 1 (XY table)" : "0 (FIPW has Y tables only)");
    }
    auto table = hil::motion::CamTable::make(spec);
    if (!table)
      return std::unexpected(SfFault{SfError::start_invalid, fmt::format("{}: Tab{}: {}", name_, t, table.error())});
    return std::move(*table);
  }

  // XFIPW VALUE NEW: DW18..DL27, checked as at START (they act only with printing mark control).
  std::optional<SfFault> printing_mark_parameters(const DataBlock& cmd) const {
    if (!x_ && !pm_) return std::nullopt;  // FIPW: used only with printing mark control
    const int format = cmd.dw(18);
    if (format < 0 || (pm_ && format == 0))
      return start_error(name_, "DW18 format length", format, pm_ ? "1..32767 (printing mark control)" : "0..32767");
    if (pm_ && !tables_.empty()) {
      const std::int64_t p = period(0, q_);
      if (cmd.dw(24) < 0 || cmd.dw(24) > p)
        return start_error(name_, "DW24 start angle correction range", cmd.dw(24), "0..Xme");
      if (cmd.dw(25) < 0 || cmd.dw(25) > p - cmd.dw(24))
        return start_error(name_, "DW25 length correction range", cmd.dw(25), "0..Xme - SK");
    }
    if (cmd.dd(20) < 0) return start_error(name_, "DD20 printing mark sensor distance", cmd.dd(20), "0..2^31-1");
    if (cmd.dw(22) < 0 || (format > 0 && cmd.dw(22) >= format))
      return start_error(name_, "DW22 synchronous point shift", cmd.dw(22), "0..format length-1");
    if (cmd.dw(23) < 0 || cmd.dw(23) > format / 2)
      return start_error(name_, "DW23 valid range", cmd.dw(23), "0..format length/2");
    const int md = cmd.dw(26);
    if (md != 0 && (md < 4 || md > 124 || md % 4 != 0))
      return start_error(name_, "DW26 MD address correction value", md, "0 or 4, 8, ..., 124");
    const int k = cmd.dr(27);
    if (k > 32 && (k < 128 || k > 159)) return start_error(name_, "DR27 correction weighting", k, "0..32 or 128..159");
    return std::nullopt;
  }

  // The master zero pulse: the FIPW source's own, or (with printing mark control) MD DR7's.
  [[nodiscard]] const ZeroPulseLatch& sync_latch(const SfIo& io) const noexcept {
    return sync_md_ >= 0 ? io.image.md_zero[static_cast<std::size_t>(sync_md_ / 4)] : io.image.az_zero[zch_];
  }

  // The master position at a latched counter value (32-bit source: the difference to now).
  [[nodiscard]] static std::int64_t master_at(std::int64_t master, std::int32_t raw_now,
                                              std::int32_t latched) noexcept {
    return master -
           static_cast<std::int32_t>(static_cast<std::uint32_t>(raw_now) - static_cast<std::uint32_t>(latched));
  }

  // One cycle of printing mark control, while the working table runs: the period start at each
  // working-table zero passage, the correction window, the marks of the zero-pulse latch.
  void printing_mark(SfIo& io, std::int64_t master) noexcept {
    const auto& work = table(set_, q_);
    const bool in_work = cam_.table() == &work;
    const double tp = cam_.table_position();
    if (!in_work) {
      if (in_work_prev_) {  // left the working table: keep what was applied, drop the rest
        corr_total_ += corr_applied_;
        corr_applied_ = 0.0;
        active_ = pending_ = false;
      }
      in_work_prev_ = false;
      mark_seen_ = io.image.az_zero[zch_].count;
      return;
    }
    // A zero passage of the working table: entered (a switch) or one more period forwards.
    if (!in_work_prev_ || cam_.switches() != pm_switches_ || cam_.periods() > pm_periods_) {
      if (have_start_) {
        if (!mark_in_period_ && md_) io.image.set_md(md_, 0);
        dmr_ = mark_in_period_;
      }
      mark_in_period_ = false;
      if (active_) corr_total_ += corr_active_;
      active_ = false;
      corr_applied_ = 0.0;
      if (pending_) {
        corr_active_ = corr_pending_;
        active_ = true;
        pending_ = false;
      }
      corr_at_start_ = corr_total_;
      have_start_ = true;
    }
    in_work_prev_ = true;
    pm_switches_ = cam_.switches();
    pm_periods_ = cam_.periods();
    if (active_) {
      const double f = lk_ > 0 ? std::clamp((tp - static_cast<double>(sk_)) / static_cast<double>(lk_), 0.0, 1.0)
                               : (tp >= static_cast<double>(sk_) ? 1.0 : 0.0);
      corr_applied_ = corr_active_ * f;
      if (f >= 1.0) {
        corr_total_ += corr_active_;
        corr_applied_ = 0.0;
        active_ = false;
      }
    }
    const ZeroPulseLatch& z = io.image.az_zero[zch_];
    if (z.count == mark_seen_) return;
    mark_seen_ = z.count;
    const double tp_mark = tp - static_cast<double>(master - master_at(master, io.source.value, z.position));
    if (tp_mark < 0.0) return;  // before this period: not a mark of the working table
    // The slave's travel in this period up to the mark, against the expected mark position.
    const double fb = static_cast<double>(scale(work.value(tp_mark))) + corr_total_ + corr_applied_ - corr_at_start_;
    double dxm = std::fmod(fb - xm_cmd_, work_lift_);
    if (dxm >= work_lift_ / 2) dxm -= work_lift_;
    if (dxm < -work_lift_ / 2) dxm += work_lift_;
    if (valid_ > 0 && std::fabs(dxm) > valid_) return;  // outside the valid range
    mark_in_period_ = true;
    if (md_) io.image.set_md(md_, std::llround(dxm));
    if (++marks_ % every_ != 0) return;
    const double c = weight_ * dxm;
    if (!active_ && tp < static_cast<double>(sk_)) {  // the window of this period is still ahead
      corr_active_ = c;
      active_ = true;
    } else {
      corr_pending_ = c;
      pending_ = true;
    }
  }

  // ------------------------------------------------------------------------------- sequencing
  [[nodiscard]] const hil::motion::CamTable& table(int set, int t) const noexcept {
    return tables_[static_cast<std::size_t>(set * m_ + t)];
  }
  [[nodiscard]] std::int64_t period(int set, int t) const noexcept {
    return static_cast<std::int64_t>(table(set, t).length());
  }
  [[nodiscard]] bool setting_on() const noexcept { return x_ && (fct_ & 8) != 0; }
  [[nodiscard]] std::int64_t scale(double raw) const noexcept {
    return std::llround(raw * static_cast<double>(k_) / static_cast<double>(1 << shift_));
  }
  // The table position (unscaled) of X = `x` from the 0 point of the set's first table.
  [[nodiscard]] double raw_at(int set, std::int64_t x) const noexcept {
    const auto& t = table(set, 0);
    const std::int64_t p = period(set, 0);
    const std::int64_t k = (x - motion::floor_mod(x, p)) / p;
    return static_cast<double>(k) * t.lift() + t.value(static_cast<double>(motion::floor_mod(x, p)));
  }

  // Table set inputs: without a start bit (cyclic) E1 = E_SUEn, E2.. = E_SU0..; with one
  // E2 = E_SUEn, E3.. = E_SU0.. (only as many select bits as the sets need).
  void read_inputs(const SfIo& io) noexcept {
    if (!set_switch_) return;
    const int first = kind_ == Kind::cyclic ? 1 : 2;
    enable_ = io.e(first);
    const int bits = sets_ <= 1 ? 0 : sets_ <= 2 ? 1 : sets_ <= 4 ? 2 : 3;
    int sel = 0;
    for (int b = 0; b < bits; ++b) sel |= io.e(first + 1 + b) ? 1 << b : 0;
    desired_ = sel < sets_ ? sel : -1;  // a selection beyond the sets is not taken
  }
  [[nodiscard]] bool set_change() const noexcept { return set_switch_ && enable_ && desired_ >= 0 && desired_ != set_; }
  void take_set() noexcept {
    if (set_change()) set_ = desired_;
    queued_set_ = set_;
  }
  // The set the next table comes from: a switch at a working-table zero passage, or after every
  // table with fct bit5.
  [[nodiscard]] int next_set(bool working_repeat) const noexcept {
    return set_change() && (working_repeat || (fct_ & 32)) ? desired_ : set_;
  }
  void queue(int set, int t, std::optional<std::int64_t> at) noexcept {
    cam_.queue({&table(set, t), at});
    queued_set_ = set;
  }

  // The tables after the first one of a movement.
  [[nodiscard]] std::vector<int> first_plan() const {
    std::vector<int> p;
    switch (kind_) {
      case Kind::single:
        p.assign(static_cast<std::size_t>(cycles_ - 1), 0);
        break;
      case Kind::sequence:
        for (int t = 1; t < q_; ++t) p.push_back(t);
        for (int c = q_ == 0 ? 1 : 0; c < cycles_; ++c) p.push_back(q_);
        for (int t = q_ + 1; t < m_; ++t) p.push_back(t);
        break;
      case Kind::clocked:
        for (int t = 1; t <= q_; ++t) p.push_back(t);
        break;
      case Kind::cyclic:
        break;
    }
    return p;
  }

  // A stored edge (fct bit4): the next movement starts at the end of this one, seamlessly.
  void restart() {
    retrigger_ = stop_queued_ = false;
    plan_ = first_plan();
    queue(set_change() ? desired_ : set_, 0, {});
  }

  // Clock in: at once when X mod P is inside the start window, else at the next zero passage.
  void clock_in(std::int64_t master, std::int64_t x) {
    take_set();
    plan_ = first_plan();
    const std::int64_t p = period(set_, 0);
    const std::int64_t xm = motion::floor_mod(x, p);
    if (xm <= start_angle_) {
      cam_.set_table(&table(set_, 0));
      cam_.start(master, cam_.slave_position(), xm);
      switches_seen_ = cam_.switches();
    } else {
      cam_.set_table(nullptr);
      queue(set_, 0, master + (p - xm));
    }
    clock_out_ = stopping_ = repeat_queued_ = stop_queued_ = retrigger_ = false;
    working_ = kind_ == Kind::clocked && q_ == 0;
    running_ = true;
  }

  // Queue the next table when none is pending: the sequence's next table, the working table
  // again (periodic: no switch needed unless the set changes), the stop tables, or the stop.
  void feed_plan(std::int64_t master, bool e1) {
    if (cam_.table() == nullptr) return;
    if (stop_queued_) {  // the movement ends with this table: a stored edge restarts it at the end
      if (retrigger_ && e1) restart();
      return;
    }
    if (cam_.switch_pending() && !(repeat_queued_ && clock_out_)) return;
    if (!plan_.empty() && !repeat_queued_) {
      const int t = plan_.front();
      plan_.erase(plan_.begin());
      const bool repeat = t == q_ && cam_.table() == &table(set_, q_);
      queue(next_set(repeat), t, {});
      if (kind_ == Kind::clocked && t == q_) working_ = true;
      return;
    }
    if (kind_ != Kind::clocked || stopping_) {  // the movement's last table runs: stop (or retrigger) at its end
      if (stopping_ && kind_ == Kind::clocked) {
        stopping_ = false;
        cam_.queue({nullptr, {}});
        return;
      }
      if (retrigger_ && e1) {
        restart();
        return;
      }
      cam_.queue({nullptr, {}});
      stop_queued_ = true;
      return;
    }
    if (!working_) return;
    if (!clock_out_) {  // the working table repeats; a set switch-over at its zero passage
      if (set_change() && !repeat_queued_) {
        queue(desired_, q_, {});
        repeat_queued_ = true;
      }
      return;
    }
    // Clock out: through the stop tables, from the working table's end or inside the stop window.
    std::optional<std::int64_t> at;
    if (cam_.table_position() <= static_cast<double>(stop_angle_)) at = master;
    for (int t = q_ + 1; t < m_; ++t) plan_.push_back(t);
    working_ = repeat_queued_ = false;
    if (plan_.empty()) {
      cam_.queue({nullptr, at});
    } else {
      const int t = plan_.front();
      plan_.erase(plan_.begin());
      queue(next_set(false), t, at);
      stopping_ = true;
    }
  }

  void outputs(SfIo& io) const noexcept {
    if (!x_) return;
    const bool suk = set_switch_ && enable_ && desired_ == set_;
    if (kind_ == Kind::cyclic) {
      if (set_switch_) io.a(1, suk);  // A1 = A_SUK
      if (pm_) io.a(1, dmr_);         // A1 = A_Dmr
      return;
    }
    io.a(1, !running_);  // A_Akt: 0 while a movement runs
    if (set_switch_) io.a(2, suk);
    if (pm_) io.a(2, dmr_);  // A2 = A_Dmr
  }

  const bool x_;
  const char* name_;
  Kind kind_ = Kind::cyclic;
  int fct_ = 0, sak_ = 0, drive_ = -1, shift_ = 0, m_ = 1, q_ = 0, cycles_ = 1, sets_ = 1;
  std::int64_t k_ = 1;
  int offset_ = 0, start_angle_ = 0, stop_angle_ = 0;
  bool set_switch_ = false, time_ = false;
  bool running_ = false, clock_out_ = false, working_ = false, stopping_ = false, prev_e1_ = false;
  bool retrigger_ = false, repeat_queued_ = false, stop_queued_ = false, enable_ = false;
  // external sync and printing mark control
  bool pm_ = false, sync_ = false, sync_wait_ = false, before_sak_ = false;
  std::size_t zch_ = 0;
  int sync_md_ = -1;
  std::uint32_t sync_seen_ = 0, mark_seen_ = 0;
  double work_lift_ = 1.0, xm_cmd_ = 0.0, valid_ = 0.0, weight_ = 1.0;
  std::int64_t pm_switches_ = 0, pm_periods_ = 0;
  std::int64_t sk_ = 0, lk_ = 0;
  int md_ = 0, every_ = 1, marks_ = 0;
  double corr_total_ = 0.0, corr_applied_ = 0.0, corr_active_ = 0.0, corr_pending_ = 0.0, corr_at_start_ = 0.0;
  bool active_ = false, pending_ = false, have_start_ = false, in_work_prev_ = false, mark_in_period_ = false,
       dmr_ = false;
  int set_ = 0, desired_ = -1, queued_set_ = 0;
  std::int64_t switches_seen_ = 0;
  std::vector<hil::motion::CamTable> tables_;
  std::vector<int> plan_;
  hil::motion::CamCoupling cam_{nullptr};
  hil::motion::EncoderInput encoder_{16};
  std::int64_t time_pos_ = 0, origin_ = 0, base_ = 0, y_prev_ = 0;
};

}  // namespace

std::unique_ptr<FastFunction> make_fipw() {
  return std::make_unique<Interpolator>(false);
}

std::unique_ptr<FastFunction> make_xfipw() {
  return std::make_unique<Interpolator>(true);
}

}  // namespace hil::controllers::amkasyn
