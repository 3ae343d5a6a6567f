// SPDX-License-Identifier: MIT
// CLM1.4 flying cutoff (axis 1, Ax00 mode 5; manual §7.12, §5.7 LML/LMK/LMR/EOS; digest §5.11,
// §5.12) on the coupling layer. The material runs under master encoder 1; a length instruction
// arms a gear engage of the carriage at the exact ratio "same speed as the material", ramped over
// the master travel L = r·v²/a in which the carriage reaches the material speed at A108, and
// started at the master position that puts the cut where the program wants it:
//
//   in sync, the material point under the tool is  P = m_s + L/2 - x0   (x0 = carriage at the
//   start, in master counts), so  m_s = P_cut - L/2 + x0,  P_cut = last cut + length.
//
// The instruction proceeds when the ratio ramp has ended (synchronous); the tool program runs;
// EOS ends the coupling and the carriage returns home (position 0) at A106 (× a VEO override).
// LMK/LMR move the cut to "raster + offset distance" when Raster 1 (I0.01.7) sees a mark between
// de-sync and the start of the ramp (once per instruction). Everything is in master counts, so
// the cut lengths are exact to one count of C000 whatever the material speed does.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/controllers/clm14/controller.hpp"

namespace hil::controllers::clm14 {

bool Controller::flying_cutoff() const noexcept {
  return settings_ok_ && settings_.axes[0].mode == 5;
}

double Controller::last_cut_point() const noexcept {
  return static_cast<double>(cut_.last_cut) * me_iu_per_count();
}

void Controller::end_cutoff() {
  if (follow_[0].active && !follow_[0].fol) end_coupling(1, true);
  const auto cuts = cut_.cuts;
  const auto last = cut_.last_cut;  // shown (cut.last) until the next cut
  cut_ = Cutoff{};
  cut_.cuts = cuts;
  cut_.last_cut = last;
}

namespace {

/// The carriage's commanded position in CLM coordinates (IU): the coupling's set-point, so the
/// cut point is the planned one, not the one the drive's following error shifts.
double carriage_command(const AxisFeedback& fb, double inc_per_iu, double offset) {
  return static_cast<double>(fb.command_inc) / inc_per_iu + offset;
}

}  // namespace

std::int64_t Controller::cutoff_ramp() const {
  // The carriage reaches the material speed v at A108 (ACC/Ax09 ‰) over the master travel
  // L = r·v²/a (even, so L/2 is exact; at least 2 counts).
  const auto ratio = follow_ratio(1, micro_one);
  const double r = ratio ? std::abs(ratio->value()) : 1.0;
  const double v = std::abs(me1_.velocity);
  const double acc = limits_for(1, settings_.axes[0].vmax).acceleration * inc_per_iu(1);
  const double l = std::min(r * v * v / acc, static_cast<double>(std::int64_t{1} << 30));
  return std::max<std::int64_t>(2, 2 * static_cast<std::int64_t>(std::ceil(l / 2.0)));
}

bool Controller::arm_cutoff_engage() {
  auto& a = axes_[0];
  auto& f = follow_[0];
  const auto ratio = follow_ratio(1, micro_one);
  if (!ratio) return false;
  const double x0 = carriage_command(a.fb, inc_per_iu(1), a.base + a.sac) / me_iu_per_count();
  const std::int64_t ms = cut_.cut_at - cut_.ramp / 2 + std::llround(x0);
  // A sync point the material has passed already (the carriage came home late) syncs at once:
  // that part is longer than programmed [decided].
  const auto ec =
      ms > me1_.count ? f.coupling.gear().engage(*ratio, cut_.ramp, ms) : f.coupling.gear().engage(*ratio, cut_.ramp);
  return !ec;
}

void Controller::step_cutoff() {
  if (!flying_cutoff()) return;
  step_cutoff_inputs();
  if (!master_available() || error_ != 0) return;
  auto& a = axes_[0];
  auto& f = follow_[0];
  // The first Raster 1 edge since de-sync (EOS); a mark while in sync is not a new part's.
  // A138 field 2: 0 = the raster's level (the profile's default), 1 = its rising edge [decided order]
  const bool in = image_.bit(sys::raster1);
  const bool mark = settings_.axes[0].raster_edge ? in && !cut_.raster_last : in;
  if (mark && cut_.phase != Cutoff::Phase::synchronous && !cut_.raster) cut_.raster = me1_.count;
  cut_.raster_last = in;
  if (cut_.phase == Cutoff::Phase::armed && f.active && f.coupling.gear().phase() == motion::GearPhase::armed &&
      !cut_.inhibited && !cut_.at_once) {
    bool rearm = false;
    if (cut_.registration && !cut_.raster_used && cut_.raster) {
      cut_.raster_used = true;
      cut_.cut_at = *cut_.raster + cut_.registration_offset;
      rearm = true;
    }
    // The material speed changed before the ramp began: the ramp follows it (its start moves so
    // that the cut stays where it was planned).
    const std::int64_t ramp = cutoff_ramp();
    if (std::abs(ramp - cut_.ramp) > std::max<std::int64_t>(2, cut_.ramp / 100)) {
      cut_.ramp = ramp;
      rearm = true;
    }
    if (rearm) (void)arm_cutoff_engage();
  }
  const auto& as = settings_.axes[0];
  if (cut_.phase == Cutoff::Phase::inhibited && (!as.reverse_inhibit_input || image_.bit(*as.reverse_inhibit_input)) &&
      !a.fb.busy)
    command_return(false);  // reverse optimisation is off while reverse inhibit acts (§7.12)
  step_optimised_return();
  if (cut_.phase == Cutoff::Phase::returning && !cut_.braking && !a.feeding) {
    cut_.phase = Cutoff::Phase::idle;
    cut_.return_acceleration = 0.0;
  }
}

Controller::Flow Controller::exec_cutoff(int t, Task& k, const Instruction& in) {
  const auto bad = [&](std::string why) {
    fail(t, static_cast<int>(ClmError::invalid_program_command), std::move(why));
    return Flow::halt;
  };
  if (!flying_cutoff()) return bad(fmt::format("{} needs axis 1 in flying cutoff mode (A100 mode 5)", mnemonic(in.op)));
  if (t != 1) return bad("the flying cutoff program runs in task 1");
  if (!master_available())
    return bad(settings_.me1.used() ? "the flying cutoff needs master encoder 1: none is attached"
                                    : "the flying cutoff needs master encoder 1 (C002 = 0: not used)");
  auto& a = axes_[0];
  auto& f = follow_[0];
  const double ipc = me_iu_per_count();
  if (in.op == Op::eos) {
    if (cut_.pending_error != 0) {
      // the end of the rapid-stop (A136) / max-stroke (A137) program: 0 V and its error
      const int code = cut_.pending_error;
      cutoff_stop(code, fmt::format("flying cutoff: {} (the program at line {:04d} ended with EOS)",
                                    code == static_cast<int>(ClmError::rapid_stop) ? "rapid stop (A136)"
                                                                                   : "maximum stroke (A137)",
                                    k.pc));
      return Flow::halt;
    }
    if (cut_.phase != Cutoff::Phase::synchronous) return Flow::next;  // nothing in sync [decided]
    end_coupling(1, false);                                           // the return move re-plans from the coupled state
    const auto& in_inhibit = settings_.axes[0].reverse_inhibit_input;
    if (in_inhibit && !image_.bit(*in_inhibit)) {
      a.port->stop();  // Ax35: decelerate and wait for the input
      cut_.phase = Cutoff::Phase::inhibited;
      return Flow::next;
    }
    command_return(true);
    return error_ == 0 ? Flow::next : Flow::halt;
  }
  auto ax = integer(in.n[0], t, 1, 1);
  if (!ax) return Flow::halt;
  if (t == 1 && k.pc > 0) cutoff_length_line_ = k.pc;  // A138: the next entry may start before it
  if (k.pc == 0) return bad(fmt::format("{} must not be at line 0000", mnemonic(in.op)));
  if (k.phase == 1) {
    const auto& g = f.coupling.gear();
    if (!(f.active && g.phase() == motion::GearPhase::steady && g.ratio().num != 0)) return Flow::wait;
    // Synchronous: the material point under the tool is the cut - the coupling's last master
    // position and the carriage set-point it gave for it.
    const double x = f.coupling.output().position / inc_per_iu(1) + a.base + a.sac;
    cut_.last_cut = g.master_inc() - std::llround(x / ipc);
    cut_.phase = Cutoff::Phase::synchronous;
    cut_.raster.reset();
    ++cut_.cuts;
    return Flow::next;
  }
  if (cut_.phase == Cutoff::Phase::synchronous) {
    fail(t, static_cast<int>(ClmError::missing_eos),
         fmt::format("{} while the carriage is synchronous: the processing program ends without EOS", mnemonic(in.op)));
    return Flow::halt;
  }
  if (cut_.phase == Cutoff::Phase::returning || cut_.phase == Cutoff::Phase::inhibited) return Flow::wait;
  // The part length and, for LMK/LMR, the distance from a raster to the cut.
  auto l1 = length(in.n[1], t);
  if (!l1) return Flow::halt;
  double nominal = to_double(*l1);
  const bool crop = cut_.crop && settings_.axes[0].crop_length > 0.0;
  cut_.crop = false;
  double registration = 0.0;
  if (in.op == Op::lml) {
    nominal += settings_.axes[0].tool_width;
  } else {
    auto l2 = length(in.n[2], t);
    if (!l2) return Flow::halt;
    registration = to_double(*l2);
    if (in.op == Op::lmr) {
      auto b = length(in.n[3], t);
      if (!b) return Flow::halt;
      const LmrGeometry g = lmr_geometry(nominal, registration, to_double(*b));
      // Without a mark the next mark is where the geometry expects it: previous cut - offset
      // + raster distance, and the cut one offset distance later = previous cut + mark distance.
      registration = g.offset;
    }
  }
  if (crop) nominal = settings_.axes[0].crop_length;  // A142: this part is the crop length [decided]
  if (nominal <= 0.0 || registration < 0.0)
    return bad(fmt::format("{}: the length must be > 0 and the offset distance >= 0", mnemonic(in.op)));
  const auto ratio = follow_ratio(1, micro_one);
  if (!ratio || ratio->num == 0) return bad("flying cutoff: no gear ratio between master encoder 1 and axis 1");
  const double x0 = carriage_command(a.fb, inc_per_iu(1), a.base + a.sac) / ipc;
  if (!cut_.have_last) {
    // The first part is measured from where the material stands under the tool now, or with
    // indexing (A134 i = 1) from the last manual cut: the material fed since then is subtracted
    // from the first length, and more than the length is error 3A.
    const std::int64_t under = me1_.count - std::llround(x0);
    if (settings_.axes[0].indexing && manual_cut_) {
      const double fed = static_cast<double>(under - *manual_cut_) * ipc;
      if (fed > nominal) {
        fail(t, static_cast<int>(ClmError::index_length),
             fmt::format("indexing: {:.3f} IU of material fed since the manual cut exceed the length {:.3f} IU", fed,
                         nominal));
        return Flow::halt;
      }
      cut_.last_cut = *manual_cut_;
    } else {
      cut_.last_cut = under;
    }
    manual_cut_.reset();
    cut_.have_last = true;
  }
  cut_.part = std::llround(nominal / ipc);
  cut_.cut_at = cut_.last_cut + cut_.part;
  cut_.registration = in.op != Op::lml;
  cut_.registration_offset = std::llround(registration / ipc);
  cut_.raster_used = false;
  if (cut_.registration && cut_.raster) {
    cut_.cut_at = *cut_.raster + cut_.registration_offset;
    cut_.raster_used = true;
  }
  cut_.ramp = cutoff_ramp();
  f.coupling = motion::Coupling("CLM flying cutoff", slave_limits(1));
  f.coupling.use(motion::Coupling::Law::gear);
  f.coupling.start(me1_.count, a.fb.command_inc);
  cut_.at_once = false;
  if (cut_.inhibited) {
    // A133: no sync until Immediate cut; the gear stays at ratio 0
  } else if (cut_.immediate) {
    cut_.immediate = false;  // A134 pressed while the carriage stood home: sync now
    cut_.at_once = true;
    if (f.coupling.gear().engage(*ratio, cut_.ramp)) return bad("flying cutoff: the engage ramp was refused");
  } else if (!arm_cutoff_engage()) {
    return bad("flying cutoff: the engage ramp was refused");
  }
  a.has_target = a.feeding = a.held = a.pending = a.con = false;
  f.active = true;
  f.fol = false;
  cut_.phase = Cutoff::Phase::armed;
  k.phase = 1;
  return Flow::wait;
}

}  // namespace hil::controllers::clm14
