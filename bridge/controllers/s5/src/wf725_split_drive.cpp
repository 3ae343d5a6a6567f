// SPDX-License-Identifier: MIT
// WF 726 split drive (gantry) MD 27 / MD 29 (docs/wf725.md "Split drive"): the slave follows the
// master's set-point every run period, the actual values are compared every module cycle (25),
// a coupled start checks the slave (69/6B, 6A), MD 1/2/38/39 (6D) and the difference (25); data
// codes 30 (difference) and 31 (programmed shift).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/controllers/s5/wf725_controller.hpp"

namespace hil::controllers::s5 {

using namespace wf_db;

namespace {

bool axis_ok(motion::AxisState s) noexcept {
  return s != motion::AxisState::disabled && s != motion::AxisState::error;
}

bool axis_moving(const motion::AxisStatus& st) noexcept {
  return st.busy || st.state == motion::AxisState::moving || st.state == motion::AxisState::stopping;
}

constexpr double shift_epsilon_mm = 1e-6;  ///< relations closer than 1 nm need no shift move

}  // namespace

std::expected<void, std::string> wf725_couple_split_drive(std::span<Wf725Controller* const> axes) {
  const auto a =
      std::find_if(axes.begin(), axes.end(), [](const Wf725Controller* c) { return c->axis_letter() == 'A'; });
  if (a == axes.end()) return {};
  const auto md27 = (*a)->machine_data().integer(27);
  if (md27 == 0) return {};
  const char partner = wf725_split_partner(md27);
  const auto b = std::find_if(axes.begin(), axes.end(), [partner](const Wf725Controller* c) {
    return partner != 0 && c->axis_letter() == partner;
  });
  if (b == axes.end())
    return std::unexpected(
        partner == 0 ? fmt::format("MD 27 = {} of axis A couples no axes (0 none, 3 = A+B, 5 = A+C)", md27)
                     : fmt::format("MD 27 = {} of axis A couples A+{} (split drive), but the module has no axis {}",
                                   md27, partner, partner));
  return (*a)->couple_split_drive(**b);
}

std::expected<void, std::string> Wf725Controller::couple_split_drive(Wf725Controller& slave) {
  const auto md27 = md_.integer(27);
  const char partner = wf725_split_partner(md27);
  if (opt_.axis != 'A')
    return std::unexpected(fmt::format(
        "split drive: MD 27 is entered in axis A (it has no significance for B+C); axis {} cannot be the master",
        opt_.axis));
  if (md_.series != 726) return std::unexpected("split drive (MD 27/29) exists on the WF 726 only");
  if (partner == 0)
    return std::unexpected(fmt::format("MD 27 = {} of axis A couples no axes (0 none, 3 = A+B, 5 = A+C)", md27));
  if (&slave == this || slave.opt_.axis != partner)
    return std::unexpected(
        fmt::format("MD 27 = {} couples A+{}; axis {} is not that partner", md27, partner, slave.opt_.axis));
  if (!md_.closed_loop() || !slave.md_.closed_loop())
    return std::unexpected(fmt::format(
        "split drive A+{}: both axes must be closed loop (MD 4 = 1/2; MD 29 exists in closed loop only)", partner));
  if (md_.rotary() || slave.md_.rotary())
    return std::unexpected(fmt::format("split drive A+{}: both axes must be linear (MD 18 < 2)", partner));
  if (md_.integer(42) == 1 || slave.md_.integer(42) == 1)
    return std::unexpected(fmt::format(
        "split drive A+{}: no roller feed (MD 42 = 1 clears the actual value at every start; the split drive "
        "compares the actual values)",
        partner));
  if (split_ || split_master_ != nullptr || slave.split_ || slave.split_master_ != nullptr)
    return std::unexpected(fmt::format("split drive A+{}: an axis is coupled already", partner));
  if (axis_count() == 0 || slave.axis_count() == 0)
    return std::unexpected("split drive: bind the axes before coupling them");
  split_ = std::make_unique<Wf725SplitDrive>();
  split_->slave = &slave;
  split_->master_offset = offset_mm_;
  split_->slave_offset = slave.offset_mm_;
  slave.split_master_ = this;
  return {};
}

void Wf725Controller::split_detach() noexcept {
  if (split_ && split_->slave != nullptr) split_->slave->split_master_ = nullptr;
  split_.reset();
  if (split_master_ != nullptr) split_master_->split_.reset();
  split_master_ = nullptr;
}

bool Wf725Controller::split_monitoring() const noexcept {
  return opt_.split_monitoring_always || db_.bit(dw_enable, bit_split_monitoring);
}

std::optional<double> Wf725Controller::split_difference_um() const noexcept {
  const Wf725Controller* m = split_ ? this : split_master_;
  if (m == nullptr || !m->split_ || m->split_->slave == nullptr) return std::nullopt;
  const auto& sd = *m->split_;
  const double relation = sd.following ? sd.relation_mm() : sd.commanded_mm;
  return (sd.slave->machine_mm() - m->machine_mm() - relation) / um;
}

// ---- every run period, on the slave ----------------------------------------------------------

void Wf725Controller::split_drive_period(const CycleTime& cycle) noexcept {
  if (split_master_ == nullptr || !split_master_->split_) return;
  Wf725Controller& m = *split_master_;
  Wf725SplitDrive& sd = *m.split_;
  auto& sa = axis(0);
  const auto& ms = m.axis(0).status();
  const bool master_ok = axis_ok(ms.state);
  const bool slave_ready = traversing_ && submode_ == Submode::none && axis_ok(sa.status().state);
  if (!sd.engaged || !master_ok || !slave_ready) {
    if (sd.following && axis_ok(sa.status().state)) {
      // The master lost its drive: the gantry's other side stops at once; otherwise on its ramp.
      (void)(master_ok ? sa.stop() : sa.quick_stop());
    }
    sd.following = false;
    sd.shift_requested = false;  // a shift asked for while engaged is not run later
    sd.shift.clear();
    sd.trim_mm = 0.0;
    return;
  }
  const bool master_moving = axis_moving(ms);
  if (!sd.following) {
    if (!master_moving && !sd.shift_requested) return;  // the slave moves only when asked
    // Start following where the slave's command stands (no set-point step); a residual and the
    // programmed shift are ramped in by the superimposed move.
    const double relation = machine_command_mm() - m.machine_command_mm();
    sd.trim_mm = relation;
    sd.shift.clear();
    if (std::abs(sd.shift_target_mm - relation) > shift_epsilon_mm) {
      const auto& c = sa.config().limits;
      const double v = sd.shift_requested && sd.shift_feed > 0.0 ? std::min(sd.shift_feed, c.velocity) : c.velocity;
      (void)sd.shift.move_by(sd.shift_target_mm - relation, motion::Limits{v, c.acceleration, c.jerk});
    }
    sd.shift_requested = false;
    sd.following = true;
    sd.rest_periods = 0;
  } else {
    sd.shift.update(cycle.period);
  }
  if (!master_moving && !sd.shift.busy()) {
    // The master and the shift rest: one more period on the final set-point, then the slave
    // settles like after any move (standstill supervision, PEH).
    if (++sd.rest_periods > 1) {
      (void)sa.stop();
      sd.following = false;
      return;
    }
  } else {
    sd.rest_periods = 0;
  }
  sd.commanded_mm = sd.relation_mm();
  const auto& sc = sa.scaling();
  const double target = m.machine_command_mm() + sd.relation_mm() - offset_mm_;
  const double ipu = sc.inc_per_unit();
  if (sa.follow(sc.to_inc(target), (ms.command_velocity + sd.shift.velocity()) * ipu,
                (ms.command_acceleration + sd.shift.acceleration()) * ipu))
    sd.following = false;  // the slave refused (its fault): the master's cycle raises 6A
}

// ---- the master's cycle ----------------------------------------------------------------------

bool Wf725Controller::split_start(TimePoint now) {
  if (!split_ || !wf725_split_submode(submode_)) return true;
  auto& sd = *split_;
  Wf725Controller& s = *sd.slave;
  const std::string pair = fmt::format("split drive A+{}", s.opt_.axis);
  if (!s.traversing_ || s.submode_ != Submode::none) {
    s.raise_wf(0x69, now,
               fmt::format("{}: the slave axis is in submode {}, not \"0\"", pair,
                           s.traversing_ ? static_cast<int>(s.submode_) : -1));
    raise_wf(0x6B, now, fmt::format("{}: axis {} is not in submode \"0\"", pair, s.opt_.axis));
    return false;
  }
  if (s.errors().blocks_motion(0) || !axis_ok(s.axis(0).status().state)) {
    raise_wf(0x6A, now,
             fmt::format("{}: axis {} {}", pair, s.opt_.axis,
                         s.errors().blocks_motion(0) ? "has an error" : "has no drive enable (D 2.0)"));
    return false;
  }
  if (const int n = wf725_split_md_mismatch(md_, s.md_)) {
    raise_wf(0x6D, now,
             fmt::format("{}: MD {} is {} in A, {} in {}", pair, n, static_cast<double>(md_.get(n)),
                         static_cast<double>(s.md_.get(n)), s.opt_.axis));
    return false;
  }
  const auto md29 = md_.integer(29);
  if (split_monitoring() && md29 > 0) {
    const double d = *split_difference_um();
    if (std::abs(d) > static_cast<double>(md29)) {
      const auto text = fmt::format("{}: difference {:.0f} µm at the start, MD 29 = {} µm", pair, d, md29);
      raise_wf(0x25, now, text);
      s.raise_wf(0x25, now, text);
      return false;
    }
  }
  return true;
}

void Wf725Controller::split_cycle(TimePoint now) {
  if (split_master_ != nullptr && split_master_->split_) return split_compare(now);
  if (!split_ || split_->slave == nullptr) return;
  auto& sd = *split_;
  Wf725Controller& s = *sd.slave;
  const std::string pair = fmt::format("split drive A+{}", s.opt_.axis);
  const bool master_ok = axis_ok(axis(0).status().state), slave_ok = axis_ok(s.axis(0).status().state);
  const bool split_sub = traversing_ && wf725_split_submode(submode_);
  const bool slave_zero = s.traversing_ && s.submode_ == Submode::none;
  if (sd.following || (split_sub && job_ != Job::none)) {
    // The coupled function runs: the slave must stay in submode "0" and free of errors.
    if (!slave_zero) {
      if (!s.has_error(0x69)) s.raise_wf(0x69, now, pair + ": the slave axis left submode \"0\"");
      if (!has_error(0x6B)) raise_wf(0x6B, now, fmt::format("{}: axis {} left submode \"0\"", pair, s.opt_.axis));
      abort_job();
    } else if (s.errors().blocks_motion(0) || !slave_ok) {
      if (!has_error(0x6A)) raise_wf(0x6A, now, fmt::format("{}: error in axis {}", pair, s.opt_.axis));
      abort_job();
    }
  }
  sd.engaged = split_sub && slave_zero && master_ok && slave_ok && !s.errors().blocks_motion(0);
  if (!sd.following && (offset_mm_ != sd.master_offset || s.offset_mm_ != sd.slave_offset)) {
    // A new reference point or actual value on either axis: the programmed shift is cancelled
    // (the actual values are synchronized afresh).
    sd.shift_target_mm = sd.commanded_mm = 0.0;
    sd.master_offset = offset_mm_;
    sd.slave_offset = s.offset_mm_;
  }
}

void Wf725Controller::split_compare(TimePoint now) {
  // In the slave's cycle: both axes have updated in this period (the master's first), so the
  // actual values compared are of one instant.
  Wf725Controller& m = *split_master_;
  auto& sd = *m.split_;
  const double d = *split_difference_um();
  sd.last_difference_um = d;
  const auto md29 = m.md_.integer(29);
  if (!sd.engaged || !m.split_monitoring() || md29 <= 0) return;
  sd.max_difference_um = std::max(sd.max_difference_um, std::abs(d));
  if (std::abs(d) > static_cast<double>(md29) && !m.has_error(0x25)) {
    // MD 29: the motion is terminated on both axes (25 is a drive-off error of the catalogue).
    const auto text =
        fmt::format("split drive A+{}: actual values differ by {:.0f} µm, MD 29 = {} µm", opt_.axis, d, md29);
    m.abort_job();
    abort_job();
    m.raise_wf(0x25, now, text);
    raise_wf(0x25, now, text);
  }
}

bool Wf725Controller::split_data_code(std::uint16_t c, std::int32_t p1, std::int32_t p2, TimePoint now,
                                      std::int32_t& result) {
  if (c != code::split_difference && c != code::split_shift) return false;
  const auto d = split_difference_um();
  if (!d) {
    raise_io(113, now, fmt::format("data code {:X}: axis {} is in no split drive (MD 27 of axis A)", c, opt_.axis));
    return true;
  }
  if (c == code::split_difference) {
    // The difference of the last comparison (the slave's cycle: both actual values of one instant).
    const Wf725Controller* m = split_ ? this : split_master_;
    result = static_cast<std::int32_t>(std::llround(m->split_->last_difference_um));
    return true;
  }
  if (!split_) {
    raise_io(113, now, "data code 31: the programmed shift is given in axis A, the split drive's master");
    return true;
  }
  auto& sd = *split_;
  if (!sd.engaged) {
    raise_io(113, now,
             fmt::format("data code 31: split drive A+{} not engaged (axis A in set up, MDI, a program or buffer "
                         "submode, axis {} in submode \"0\", both drives enabled, no error)",
                         sd.slave->opt_.axis, sd.slave->opt_.axis));
    return true;
  }
  if (p2 <= 0) {
    raise_io(145, now, "data code 31: the feed of the shift (param 2) is 0");
    return true;
  }
  sd.shift_target_mm = static_cast<double>(p1) * um;
  sd.shift_feed = static_cast<double>(p2) / 100.0 / 60.0;
  if (sd.following) {
    const auto& lim = sd.slave->axis(0).config().limits;
    const double rest = sd.shift_target_mm - (sd.trim_mm + sd.shift.target());
    if (std::abs(rest) > shift_epsilon_mm)
      (void)sd.shift.move_by(rest, motion::Limits{std::min(sd.shift_feed, lim.velocity), lim.acceleration, lim.jerk});
  } else {
    sd.shift_requested = true;
  }
  return true;
}

}  // namespace hil::controllers::s5
