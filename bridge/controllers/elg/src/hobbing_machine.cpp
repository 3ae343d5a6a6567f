// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/hobbing_machine.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hil::controllers::elg {

motion::Ratio rotary_counts_per_degree(std::int64_t pulses_per_rev) noexcept {
  // 4 N counts per 360 deg, reduced.
  std::int64_t num = 4 * pulses_per_rev, den = 360;
  const std::int64_t g = std::gcd(num, den);
  return {num / g, den / g};
}

motion::Ratio linear_counts_per_mm(std::int64_t ms_nm) noexcept {
  std::int64_t num = 1000000, den = ms_nm;
  const std::int64_t g = std::gcd(num, den);
  return {num / g, den / g};
}

HobbingMachine::HobbingMachine(NcProgram program, HobbingConfig config, HobbingAxes axes)
    : config_(std::move(config)),
      axes_(axes),
      nc_(std::move(program)),
      pc_(config_.m_functions),
      gearbox_(config_.gearbox),
      ssfk_(config_.ssfk) {}

void HobbingMachine::move(const NcTargets& t, bool rapid, double feed_mm_per_s) {
  auto start = [&](motion::Axis* axis, const std::optional<double>& target) {
    if (axis == nullptr || !target) return;
    motion::Limits limits = axis->config().limits;
    limits.velocity = std::min(limits.velocity, rapid ? config_.rapid_mm_per_s : feed_mm_per_s);
    if (auto ec = axis->move_absolute(*target, motion::Direction::shortest, limits)) {
      error_ = "axis " + axis->config().name + ": " + ec.message();
    }
  };
  start(axes_.x, t.x);
  start(axes_.y, t.y);
  start(axes_.z, t.z);
}

bool HobbingMachine::in_position() const {
  for (const motion::Axis* axis : {axes_.x, axes_.y, axes_.z}) {
    if (axis != nullptr && axis->status().busy) return false;
  }
  return !pc_.read_in_disable();
}

NcTargets HobbingMachine::position() const {
  NcTargets p;
  if (axes_.x) p.x = axes_.x->status().command_position;
  if (axes_.y) p.y = axes_.y->status().command_position;
  if (axes_.z) p.z = axes_.z->status().command_position;
  return p;
}

void HobbingMachine::spindle(double rpm, int direction) {
  if (axes_.b == nullptr) return;
  const double deg_per_s = rpm * 6.0 * direction;
  const auto ec = direction == 0 || rpm == 0.0 ? axes_.b->stop() : axes_.b->move_velocity(deg_per_s);
  if (ec) error_ = "spindle B: " + ec.message();
}

void HobbingMachine::m_function(int m) {
  pc_.on_m_function(m);
}

void HobbingMachine::transfer_parameters() {
  // The PC passes the NC's R parameters to the ELG (5.1) whenever they change; refused while
  // coupled (Gearbox::set_input), so a change then waits for Gearing OFF.
  const double values[5] = {nc_.r(config_.r_z0), nc_.r(config_.r_z2), nc_.r(config_.r_ud_z), nc_.r(config_.r_ud_y),
                            nc_.r(config_.r_toler)};
  if (std::equal(std::begin(values), std::end(values), std::begin(last_r_))) return;
  if (gearbox_.status().coupled) {
    if (values[4] != last_r_[4] && values[4] > 0) gearbox_.set_tolerance(std::llround(values[4]));
    last_r_[4] = values[4];
    return;
  }
  GearInput in{static_cast<std::int32_t>(std::lround(values[0])), static_cast<std::int32_t>(std::lround(values[1])),
               Decimal5::from_double(values[2]), Decimal5::from_double(values[3])};
  gearbox_.set_input(in);
  if (values[4] > 0) gearbox_.set_tolerance(std::llround(values[4]));
  std::copy(std::begin(values), std::end(values), std::begin(last_r_));
}

void HobbingMachine::step(const hil::CycleTime& cycle) noexcept {
  now_s_ = hil::to_seconds(cycle.now.time_since_epoch());
  if (started_) nc_.step(now_s_, *this);
  transfer_parameters();
  AxisFeedback fb;
  if (axes_.b) fb.b = axes_.b->status().position_inc;
  if (axes_.z) fb.z = axes_.z->status().position_inc;
  if (axes_.y) fb.y = axes_.y->status().position_inc;
  const auto& cs = axes_.c->status();
  fb.c = cs.position_inc - ssfk_comp_;  // the ELG works in SSFK-compensated coordinates
  fb.c_following_error = cs.command_inc - cs.position_inc;
  fb.c_in_position = !cs.busy;
  const std::size_t alarms_before = gearbox_.alarms().size();
  const std::int64_t previous_set = gearbox_.status().c_set;
  const GearboxStatus& st = gearbox_.step(pc_.signals(), fb);
  pc_.after_step(st, gearbox_.alarms().size() > alarms_before);

  if (st.coupled && !was_coupled_) {
    ++couplings_;
    latched_b_ = fb.b;
    latched_z_ = fb.z;
    latched_y_ = fb.y;
    latched_c_ = st.c_set;
  }
  const double period_s = hil::to_seconds(cycle.period);
  // SSFK (ssfk.hpp): the compensation at C's set position, once C is referenced.
  {
    const std::int64_t here = fb.c + fb.c_following_error;
    const bool positioned = st.c_mode == CMode::follow || st.c_mode == CMode::position;
    const std::int64_t at = positioned ? st.c_set : here;
    const double moving = st.c_mode == CMode::follow     ? static_cast<double>(st.c_set - previous_set)
                          : st.c_mode == CMode::position ? static_cast<double>(st.c_set - here)
                          : st.c_mode == CMode::velocity ? st.c_velocity
                                                         : 0.0;
    if (moving != 0.0) ssfk_direction_ = moving > 0 ? 1 : -1;
    ssfk_comp_ = ssfk_.active() && st.referenced ? ssfk_.compensation(at + st.c_offset, ssfk_direction_) : 0;
  }
  const auto& ratio = axes_.c->config().inc_per_unit;
  auto to_deg = [&](double counts) { return counts * static_cast<double>(ratio.den) / static_cast<double>(ratio.num); };
  switch (st.c_mode) {
    case CMode::follow: {
      // The first coupled cycle starts from standstill: the set value before it may be a stale one
      // of a setting-up motion, not a speed.
      const double v = period_s > 0 && was_coupled_ ? static_cast<double>(st.c_set - previous_set) / period_s : 0.0;
      if (auto ec = axes_.c->follow(st.c_set + ssfk_comp_, v, 0.0)) error_ = "table C: " + ec.message();
      indexing_ = false;
      setup_motion_ = false;
      break;
    }
    case CMode::velocity:
      // JOG / REF: issued again only when the speed changes (override, rapid key, cam).
      if (!setup_motion_ || st.c_velocity != issued_velocity_) {
        const auto ec = st.c_velocity == 0.0 ? (cs.busy ? axes_.c->stop() : std::error_code{})
                                             : axes_.c->move_velocity(to_deg(st.c_velocity));
        if (ec) error_ = "table C: " + ec.message();
        issued_velocity_ = st.c_velocity;
        setup_motion_ = true;
      }
      indexing_ = false;
      break;
    case CMode::position:
      if (st.setup_step) {
        // INC: the step's target at MD 300* x override; 0 % holds C until the override rises.
        if (!setup_motion_ || st.c_set != issued_target_ || st.c_velocity != issued_velocity_) {
          std::error_code ec;
          if (st.c_velocity == 0.0) {
            if (cs.busy) ec = axes_.c->stop();
          } else {
            motion::Limits limits = axes_.c->config().limits;
            limits.velocity = std::min(limits.velocity, to_deg(st.c_velocity));
            ec = axes_.c->move_absolute(axes_.c->scaling().to_units(st.c_set + ssfk_comp_), motion::Direction::shortest,
                                        limits);
          }
          if (ec) error_ = "table C: " + ec.message();
          issued_target_ = st.c_set;
          issued_velocity_ = st.c_velocity;
          setup_motion_ = true;
        }
        break;
      }
      if (!indexing_) {
        const double deg = axes_.c->scaling().to_units(st.c_set + ssfk_comp_);
        motion::Limits limits = axes_.c->config().limits;
        limits.velocity = std::min(limits.velocity, config_.index_speed_deg_per_s);
        if (auto ec = axes_.c->move_absolute(deg, motion::Direction::shortest, limits))
          error_ = "table C: " + ec.message();
        indexing_ = true;
      }
      break;
    case CMode::stop:
      if (cs.busy) axes_.c->quick_stop();
      indexing_ = false;
      setup_motion_ = false;
      break;
    case CMode::hold:
      if (was_coupled_ || (setup_motion_ && cs.busy)) axes_.c->stop();
      indexing_ = false;
      setup_motion_ = false;
      break;
  }
  if (st.coupled) {
    // The linkage equation in degrees on the actual B, Z, Y values, against the ELG's set value.
    const auto& md = config_.gearbox.md;
    const auto& in = gearbox_.input();
    const double ms_c = 360.0 / (4.0 * static_cast<double>(md.n02));
    const double ms_b = md.n00 > 0 ? 360.0 / (4.0 * static_cast<double>(md.n00)) : 0.0;
    const bool cutter = !pc_.signals().single_pitch;
    const double phi =
        (cutter ? static_cast<double>(fb.b - latched_b_) * ms_b * in.z0 / in.z2 : 0.0) +
        static_cast<double>(fb.z - latched_z_) * static_cast<double>(md.ms_z_nm) * 1e-6 * in.ud_z.value() / in.z2 +
        static_cast<double>(fb.y - latched_y_) * static_cast<double>(md.ms_y_nm) * 1e-6 * in.ud_y.value() / in.z2;
    linkage_error_ = static_cast<double>(st.c_set) - (static_cast<double>(latched_c_) + phi / ms_c);
    worst_linkage_error_ = std::max(worst_linkage_error_, std::abs(linkage_error_));
    c_linkage_error_deg_ = (static_cast<double>(fb.c - latched_c_) - phi / ms_c) * ms_c;
  } else {
    linkage_error_ = 0.0;
    c_linkage_error_deg_ = 0.0;
  }
  was_coupled_ = st.coupled;
}

}  // namespace hil::controllers::elg
