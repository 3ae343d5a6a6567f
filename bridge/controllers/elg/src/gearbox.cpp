// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/gearbox.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "edge.hpp"

namespace hil::controllers::elg {
namespace {
__extension__ typedef __int128 i128;  // exact index arithmetic (GCC/Clang)
using detail::rising;
}  // namespace

Gearbox::Gearbox(GearboxConfig config) : config_(config), setup_(config.setup) {
  r40_ = config_.fe_tolerance_min;
  status_.fe_limit = r40_;
}

bool Gearbox::has_alarm(Alarm alarm) const noexcept {
  return std::find(alarms_.begin(), alarms_.end(), alarm) != alarms_.end();
}

void Gearbox::raise(Alarm alarm) {
  if (!has_alarm(alarm)) alarms_.push_back(alarm);
  status_.alarm = true;
}

bool Gearbox::set_input(const GearInput& input) {
  if (status_.coupled) return false;
  const bool changed = input.z0 != input_.z0 || input.z2 != input_.z2 || input.ud_z.e5 != input_.ud_z.e5 ||
                       input.ud_y.e5 != input_.ud_y.e5;
  input_ = input;
  if (changed && config_.clear_computed_on_parameter_change) {
    constants_.reset();
    status_.computed = false;
  }
  return true;
}

bool Gearbox::set_tolerance(std::int64_t r40) {
  if (r40 < config_.fe_tolerance_min || r40 > 10000) return false;
  r40_ = r40;
  status_.fe_limit = std::max(config_.fe_tolerance_min, r40_);
  return true;
}

void Gearbox::power_on_reset() {
  alarms_.clear();
  constants_.reset();
  status_ = GearboxStatus{};
  status_.fe_limit = std::max(config_.fe_tolerance_min, r40_);
  stopped_ = false;
  indexing_ = false;
  ezt_base_valid_ = false;
  index_count_ = 0;
  hae_offset_ = 0.0;
  setup_ = SetupModes(config_.setup);  // the reference point is lost with the power
  setup_moved_c_ = false;
}

void Gearbox::on_compute() {
  // Recalculation only while the coupling is disengaged (3.2).
  if (status_.coupled) return;
  auto k = compute_constants(input_, config_.md);
  if (!k) {
    raise(k.error());
    constants_.reset();
    status_.computed = false;
    return;
  }
  constants_ = *k;
  status_.computed = true;
}

void Gearbox::engage(const AxisFeedback& axes, bool single_pitch) {
  // Preconditions of 4.1; violation: 2207, partial set value 0.
  // A setting-up motion of C still under way is no approach condition either (decision).
  const bool approach_ok = std::llabs(axes.c_following_error) <= config_.gearing_on_tolerance && !setup_.moving();
  if (!constants_ || has_alarm(Alarm::power_on_error) || has_alarm(Alarm::constants_error) || !approach_ok) {
    raise(Alarm::gearing_not_permissible);
    return;
  }
  // Positions latched at engagement (digest §2.6): set values are relative to this instant. C's
  // own reference is its set value (actual + following error), not the actual value, so a
  // standing following error never shifts the index position from gap to gap.
  const std::int64_t c0 = indexing_ ? status_.c_set : axes.c + axes.c_following_error;
  linkage_ = Linkage(*constants_, axes.b, axes.z, axes.y, c0, !single_pitch);
  setup_moved_c_ = false;
  indexing_ = false;
  hae_offset_ = 0.0;
  hae_target_ = 0;
  status_.coupled = true;
  status_.c_mode = CMode::follow;
  status_.c_set = c0;
  last_c_set_ = c0;
}

void Gearbox::disengage() {
  status_.coupled = false;
  status_.contact_closed = true;  // re-closes when the coupling is switched off (5.2)
  status_.hae = HaeState::idle;
  status_.tooth_gap_reached = false;
  status_.c_mode = CMode::hold;
  // Relative indexing: the next pitch counts from where the coupling left C. On the grid (the
  // default) the pitches count from the position EZT was selected at, so a residual of the
  // differential term (a feed axis settling a count short) never accumulates from gap to gap.
  if (ezt_base_valid_ && !config_.index_on_grid) {
    index_base_ = status_.c_set;
    index_count_ = 0;
  }
}

const GearboxStatus& Gearbox::step(const Signals& s, const AxisFeedback& axes) {
  // RESET clears reset alarms only with the coupling OFF (11.1); 2200 needs POWER ON RESET.
  if (rising(s.reset, last_.reset) && !status_.coupled) {
    std::erase_if(alarms_, [](Alarm a) { return !needs_power_on_reset(a); });
    stopped_ = false;
    status_.contact_closed = true;
    setup_.abort();
  }
  if (s.emergency_off) {
    raise(Alarm::emergency_off);
    stopped_ = true;
  }
  if (rising(s.data_start, last_.data_start) && status_.coupled) raise(Alarm::v24_not_permitted);
  if (rising(s.compute, last_.compute)) on_compute();

  // EZT selection: the tooth counter starts at 1; needs the constants (4.3).
  if (s.single_pitch && !last_.single_pitch) {
    if (!constants_) {
      raise(Alarm::gearing_not_permissible);
    } else {
      status_.tooth = 1;
      index_count_ = 0;
      index_base_ = status_.coupled ? status_.c_set : axes.c + axes.c_following_error;
      ezt_base_valid_ = true;
    }
  }
  if (!s.single_pitch && last_.single_pitch) {
    status_.tooth = 0;
    ezt_base_valid_ = false;
  }

  if (s.gearing_off) {
    if (status_.coupled) disengage();
  } else if (rising(s.gearing_on, last_.gearing_on) && !status_.coupled) {
    engage(axes, s.single_pitch && ezt_base_valid_);
  }

  if (status_.coupled) {
    run_coupled(s, axes);
    (void)setup_.step(s.panel, status_.c_set, axes.c, axes.c_in_position, true, true);
  } else {
    run_indexing(s, axes);
    run_setup(s, axes);
  }
  status_.referenced = setup_.referenced();
  status_.c_offset = setup_.offset();
  monitor_following_error(s, axes);
  if (stopped_) status_.c_mode = CMode::stop;
  status_.alarm = !alarms_.empty();
  last_ = s;
  return status_;
}

void Gearbox::run_coupled(const Signals& s, const AxisFeedback& axes) {
  run_hae(s, axes);
  auto c = linkage_.c_set(axes.b, axes.z, axes.y);
  if (!c) {
    // 2202: the maximum permissible partial set value is output while the overflow lasts.
    raise(c.error());
    status_.c_set = last_c_set_ + last_partial_;
  } else {
    const std::int64_t wanted = *c + static_cast<std::int64_t>(std::llround(hae_offset_));
    std::int64_t partial = wanted - last_c_set_;
    const std::int64_t limit = config_.max_partial_counts;
    if (limit > 0) {
      if (std::llabs(partial) > limit) {
        raise(Alarm::partial_set_value_too_high);
        partial = partial > 0 ? limit : -limit;
      } else if (std::llabs(partial) * 10 >= limit * 9) {
        raise(Alarm::partial_set_value_near_limit);
      }
    }
    status_.c_set = last_c_set_ + partial;
    last_partial_ = partial;
  }
  last_c_set_ = status_.c_set;
  status_.c_mode = CMode::follow;
}

void Gearbox::run_indexing(const Signals& s, const AxisFeedback& axes) {
  if (!ezt_base_valid_ || !constants_) {
    status_.c_mode = indexing_ ? CMode::position : CMode::hold;
    return;
  }
  if (indexing_) {
    if (axes.c_in_position && axes.c + axes.c_following_error == status_.c_set) {
      indexing_ = false;
      status_.c_mode = CMode::hold;
    }
    return;
  }
  const bool plus = rising(s.index_plus, last_.index_plus);
  const bool minus = rising(s.index_minus, last_.index_minus);
  if (plus == minus) return;
  // One pitch = N02/Z2 pulses = 4*N02/Z2 counts, exact over any number of indexes.
  index_count_ += plus ? 1 : -1;
  const auto& p = constants_->pitch;
  const i128 offset = static_cast<i128>(index_count_) * p.num;
  const std::int64_t counts =
      static_cast<std::int64_t>(offset >= 0 ? offset / p.den : -((-offset + p.den - 1) / p.den));
  status_.c_set = index_base_ + counts;
  status_.c_mode = CMode::position;
  indexing_ = true;
  setup_moved_c_ = false;
  const std::int32_t z2 = input_.z2;
  status_.tooth += plus ? 1 : -1;
  if (status_.tooth > z2) status_.tooth = 1;
  if (status_.tooth < 1) status_.tooth = z2;
}

void Gearbox::run_setup(const Signals& s, const AxisFeedback& axes) {
  // JOG/INC/REF of C with the coupling OFF (ch. 7); an index under way or the STOP reaction
  // holds them (the EMERGENCY OFF of this cycle included).
  const bool blocked = stopped_ || s.emergency_off || indexing_;
  if (auto alarm = setup_.step(s.panel, axes.c + axes.c_following_error, axes.c, axes.c_in_position, false, blocked))
    raise(*alarm);
  status_.setup_step = false;
  if (indexing_) return;
  const auto& cmd = setup_.command();
  switch (cmd.kind) {
    case SetupCommand::Kind::none:
      // After a JOG/INC/REF motion the set value follows C while it stops and stands (its own
      // command), until an index or the coupling takes C again.
      if (setup_moved_c_) status_.c_set = axes.c + axes.c_following_error;
      status_.c_mode = CMode::hold;
      status_.c_velocity = 0.0;
      break;
    case SetupCommand::Kind::velocity:
      setup_moved_c_ = true;
      status_.c_mode = CMode::velocity;
      status_.c_velocity = cmd.velocity_counts_per_s;
      status_.c_set = axes.c + axes.c_following_error;
      break;
    case SetupCommand::Kind::position:
      setup_moved_c_ = true;
      status_.c_mode = CMode::position;
      status_.c_set = cmd.target;
      status_.c_velocity = cmd.velocity_counts_per_s;
      status_.setup_step = true;
      break;
  }
}

void Gearbox::run_hae(const Signals& s, const AxisFeedback& axes) {
  (void)axes;
  if (!s.hae) {
    status_.hae = HaeState::idle;
    status_.tooth_gap_reached = false;
    status_.actual_value_transferred = false;
    return;
  }
  if (status_.hae == HaeState::idle) status_.hae = HaeState::approach;
  status_.actual_value_transferred = s.transfer_actual && status_.actual_value_transferred;
  // INC motion of the operator, superimposed on the coupling: dS = n * 2 MS (7.2).
  // With the mode switch at INC the panel's selector gives n (7.2); else the configured n.
  const std::int64_t n = s.panel.mode == PanelMode::inc ? s.panel.inc_factor : config_.inc_increments;
  const std::int64_t step = n * 2;
  if (status_.hae == HaeState::approach || status_.hae == HaeState::one_point) {
    if (rising(s.inc_plus, last_.inc_plus)) hae_target_ += step;
    if (rising(s.inc_minus, last_.inc_minus)) hae_target_ -= step;
    if (rising(s.transfer_actual, last_.transfer_actual)) {
      const auto flank = static_cast<std::int64_t>(std::llround(hae_offset_));
      status_.actual_value_transferred = true;
      if (status_.hae == HaeState::approach) {
        p1_ = flank;
        status_.hae = HaeState::one_point;
      } else {
        hae_target_ = p1_ + (flank - p1_) / 2;  // (P1 + P2) / 2
        status_.hae = HaeState::centring;
      }
    }
  }
  // The superimposed offset moves at MD 170 (1/1000 rpm of C).
  const double counts_per_cycle = static_cast<double>(config_.md.hae_speed) / 1000.0 / 60.0 * 4.0 *
                                  static_cast<double>(config_.md.n02) * config_.cycle_s;
  const double error = static_cast<double>(hae_target_) - hae_offset_;
  if (std::abs(error) <= counts_per_cycle) {
    hae_offset_ = static_cast<double>(hae_target_);
    if (status_.hae == HaeState::centring) {
      status_.hae = HaeState::gap_reached;
      status_.tooth_gap_reached = true;
    }
  } else {
    hae_offset_ += error > 0 ? counts_per_cycle : -counts_per_cycle;
  }
}

void Gearbox::monitor_following_error(const Signals& s, const AxisFeedback& axes) {
  status_.fe_limit = std::max(config_.fe_tolerance_min, r40_);
  // Monitoring acts only while COUPLING ON and A67.1 (5.2); equal to the limit is still inside.
  if (status_.coupled && s.fe_monitor && std::llabs(axes.c_following_error) > status_.fe_limit) {
    status_.contact_closed = false;
    raise(Alarm::following_error_exceeded);
  }
}

}  // namespace hil::controllers::elg
