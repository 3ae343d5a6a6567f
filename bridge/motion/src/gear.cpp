// SPDX-License-Identifier: MIT
// Coupling step 1: the electronic gear (exact rational ratio, transitions at a master position,
// ratio ramps over a master distance). The maths is in gear.hpp and docs/coupling.md.
#include "hil/motion/gear.hpp"

#include "hil/motion/coupling_fault.hpp"

namespace hil::motion {
namespace {

constexpr std::int64_t max_ramp = std::int64_t{1} << 30;

int sign(std::int64_t v) noexcept {
  return (v > 0) - (v < 0);
}

}  // namespace

Gear::Gear(GearRatio ratio) noexcept : ratio_(valid(ratio) ? ratio : GearRatio{}) {
  slope_ = ratio_.value();
}

void Gear::start(std::int64_t master_inc, std::int64_t slave_inc) noexcept {
  master_ = master_inc;
  whole_ = slave_inc;
  rem_ = 0;
  if (phase_ == GearPhase::ramping) {
    ratio_ = pending_.to;  // a ramp cut short: take its end ratio
    phase_ = GearPhase::steady;
  }
  if (phase_ == GearPhase::armed && pending_at_once_) pending_.at_master_inc = master_inc;  // "at once" = from here
  slope_ = ratio_.value();
}

std::error_code Gear::change(const GearTransition& t) noexcept {
  if (!valid(t.to) || t.ramp_master_inc < 0 || t.ramp_master_inc > max_ramp || phase_ == GearPhase::ramping)
    return make_error_code(CouplingFault::invalid);
  pending_ = t;
  pending_at_once_ = !pending_.at_master_inc;
  if (pending_at_once_) pending_.at_master_inc = master_;  // at once: from the last master position
  phase_ = GearPhase::armed;
  return {};
}

double Gear::frac() const noexcept {
  if (phase_ == GearPhase::ramping) return static_cast<double>(ramp_num_) / static_cast<double>(ramp_den_);
  return static_cast<double>(rem_) / static_cast<double>(ratio_.den);
}

void Gear::advance_steady(std::int64_t m) noexcept {
  const std::int64_t dm = m - master_;
  if (dm > -max_gear_term && dm < max_gear_term) {
    // |rem| < 2^31, |dm * num| < 2^62: fits int64 (the hot path).
    const std::int64_t t = rem_ + dm * ratio_.num;
    const std::int64_t q = floor_div(t, ratio_.den);
    whole_ += q;
    rem_ = t - q * ratio_.den;
  } else {
    const i128 t = static_cast<i128>(rem_) + static_cast<i128>(dm) * ratio_.num;
    const i128 q = floor_div(t, static_cast<i128>(ratio_.den));
    whole_ += static_cast<std::int64_t>(q);
    rem_ = static_cast<std::int64_t>(t - q * ratio_.den);
  }
  master_ = m;
}

void Gear::begin_ramp(std::int64_t at_master) noexcept {
  p_ = at_master;
  s0_whole_ = whole_;
  s0_rem_ = rem_;
  ell_ = 0;
  ramp_num_ = rem_;
  ramp_den_ = ratio_.den;
  phase_ = GearPhase::ramping;
}

void Gear::finish_ramp() noexcept {
  // Value at u = ell: whole + N/D; re-express the fraction over den(r1), rounded down.
  const GearRatio r0 = ratio_, r1 = pending_.to;
  const i128 l2 = 2 * static_cast<i128>(ell_);
  i128 n = static_cast<i128>(s0_rem_) * l2 * r1.den + static_cast<i128>(r0.num) * ell_ * l2 * r1.den +
           (static_cast<i128>(r1.num) * r0.den - static_cast<i128>(r0.num) * r1.den) * (static_cast<i128>(ell_) * ell_);
  i128 d = l2 * r0.den * r1.den;
  if (d < 0) {
    n = -n;
    d = -d;
  }
  const i128 q = floor_div(n, d);
  whole_ = s0_whole_ + static_cast<std::int64_t>(q);
  rem_ = static_cast<std::int64_t>(((n - q * d) * r1.den) / d);
  ratio_ = r1;
  master_ = p_ + ell_;
  phase_ = GearPhase::steady;
  slope_ = ratio_.value();
}

void Gear::eval_ramp(std::int64_t m) noexcept {
  const std::int64_t u = m - p_;
  if (ell_ == 0) {
    if (pending_.ramp_master_inc == 0) {  // a step: the new ratio from p_ on
      const GearRatio r1 = pending_.to;
      rem_ = static_cast<std::int64_t>((static_cast<i128>(s0_rem_) * r1.den) / ratio_.den);
      whole_ = s0_whole_;
      ratio_ = r1;
      master_ = p_;
      phase_ = GearPhase::steady;
      slope_ = ratio_.value();
      advance_steady(m);
      return;
    }
    if (u == 0) {  // the master has not moved yet: the ramp's direction is still open
      master_ = m;
      return;
    }
    ell_ = sign(u) * pending_.ramp_master_inc;
  }
  const GearRatio r0 = ratio_, r1 = pending_.to;
  if (u == 0 || sign(u) != sign(ell_)) {  // behind the ramp's start: still r0
    const i128 t = static_cast<i128>(s0_rem_) + static_cast<i128>(u) * r0.num;
    const i128 q = floor_div(t, static_cast<i128>(r0.den));
    whole_ = s0_whole_ + static_cast<std::int64_t>(q);
    ramp_num_ = t - q * r0.den;
    ramp_den_ = r0.den;
    slope_ = r0.value();
    master_ = m;
    return;
  }
  if ((u > 0 ? u : -u) >= (ell_ > 0 ? ell_ : -ell_)) {
    finish_ramp();
    advance_steady(m);
    return;
  }
  const i128 l2 = 2 * static_cast<i128>(ell_);
  i128 n = static_cast<i128>(s0_rem_) * l2 * r1.den + static_cast<i128>(r0.num) * u * l2 * r1.den +
           (static_cast<i128>(r1.num) * r0.den - static_cast<i128>(r0.num) * r1.den) * (static_cast<i128>(u) * u);
  i128 d = l2 * r0.den * r1.den;
  if (d < 0) {
    n = -n;
    d = -d;
  }
  const i128 q = floor_div(n, d);
  whole_ = s0_whole_ + static_cast<std::int64_t>(q);
  ramp_num_ = n - q * d;
  ramp_den_ = d;
  slope_ = r0.value() + (r1.value() - r0.value()) * static_cast<double>(u) / static_cast<double>(ell_);
  master_ = m;
}

double Gear::update(std::int64_t m) noexcept {
  switch (phase_) {
    case GearPhase::steady:
      advance_steady(m);
      break;
    case GearPhase::armed: {
      const std::int64_t p = *pending_.at_master_inc;
      const std::int64_t before = master_;
      const bool reached = before == p || (before < p && m >= p) || (before > p && m <= p);
      if (!reached) {
        advance_steady(m);
        break;
      }
      advance_steady(p);  // exact slave position at the master position p
      begin_ramp(p);
      if (before != p && pending_.ramp_master_inc > 0) ell_ = sign(m - before) * pending_.ramp_master_inc;
      eval_ramp(m);
      break;
    }
    case GearPhase::ramping:
      eval_ramp(m);
      break;
  }
  return slave_position();
}

}  // namespace hil::motion
