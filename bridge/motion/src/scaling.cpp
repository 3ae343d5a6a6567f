// SPDX-License-Identifier: MIT
// Step 1 of the axis maths: user units <-> drive increments, exact rational.
#include "hil/motion/scaling.hpp"

#include <cmath>
#include <limits>
#include <numeric>

namespace hil::motion {
namespace {

__extension__ typedef __int128 i128;

// round(q + f) half away from zero, where q is an integer and |f| < 2; saturates to int64.
std::int64_t round_sum(i128 q, double f) noexcept {
  const double fl = std::floor(f);
  const double frac = f - fl;  // [0, 1)
  const i128 base = q + static_cast<i128>(fl);
  i128 out = base;
  if (frac > 0.5 || (frac == 0.5 && base >= 0)) out = base + 1;
  constexpr i128 max = std::numeric_limits<std::int64_t>::max();
  constexpr i128 min = std::numeric_limits<std::int64_t>::min();
  if (out > max) return std::numeric_limits<std::int64_t>::max();
  if (out < min) return std::numeric_limits<std::int64_t>::min();
  return static_cast<std::int64_t>(out);
}

}  // namespace

Scaling::Scaling(Ratio ratio, bool rotary, double modulo) noexcept
    : num_(ratio.num > 0 ? ratio.num : 1), den_(ratio.den > 0 ? ratio.den : 1), rotary_(rotary), modulo_(modulo) {
  const std::int64_t g = std::gcd(num_, den_);
  num_ /= g;
  den_ /= g;
  inc_per_unit_ = static_cast<double>(num_) / static_cast<double>(den_);
  units_per_inc_ = static_cast<double>(den_) / static_cast<double>(num_);
  if (rotary_) {
    inc_per_turn_ = to_inc(modulo_);
    if (inc_per_turn_ <= 0) inc_per_turn_ = 1;
  }
}

std::int64_t Scaling::to_inc(double units) const noexcept {
  if (!std::isfinite(units)) return 0;
  constexpr double lim = 9.0e18;
  const double xi_d = std::trunc(units);
  if (std::fabs(xi_d) >= lim) {
    return units > 0 ? std::numeric_limits<std::int64_t>::max() : std::numeric_limits<std::int64_t>::min();
  }
  const auto xi = static_cast<std::int64_t>(xi_d);
  const double xf = units - xi_d;  // exact (Sterbenz)
  const i128 big = static_cast<i128>(xi) * num_;
  const i128 q = big / den_;
  const auto r = static_cast<std::int64_t>(big % den_);  // |r| < den
  // fractional increments: (r + xf*num) / den, |.| < 2
  const double f = (static_cast<double>(r) + xf * static_cast<double>(num_)) / static_cast<double>(den_);
  return round_sum(q, f);
}

std::int64_t Scaling::to_inc_fast(double units) const noexcept {
  return std::llround(units * inc_per_unit_);
}

double Scaling::to_units(std::int64_t inc) const noexcept {
  const i128 big = static_cast<i128>(inc) * den_;
  const i128 q = big / num_;
  const auto r = static_cast<std::int64_t>(big % num_);
  return static_cast<double>(q) + static_cast<double>(r) / static_cast<double>(num_);
}

std::int64_t Scaling::delta_to_inc(double distance, double& carry_inc) const noexcept {
  // Exact integer part via to_inc on the integer part of the distance; fraction via double.
  const double di = std::trunc(distance);
  if (!std::isfinite(distance) || std::fabs(di) >= 9.0e18) return 0;  // callers reject these first
  const double df = distance - di;
  const i128 big = static_cast<i128>(static_cast<std::int64_t>(di)) * num_;
  const i128 q = big / den_;
  const auto r = static_cast<std::int64_t>(big % den_);
  const double f = (static_cast<double>(r) + df * static_cast<double>(num_)) / static_cast<double>(den_) + carry_inc;
  const double fr = std::round(f);
  carry_inc = f - fr;
  return static_cast<std::int64_t>(q + static_cast<i128>(fr));
}

std::int64_t Scaling::wrap_inc(std::int64_t inc) const noexcept {
  if (!rotary_) return inc;
  std::int64_t w = inc % inc_per_turn_;
  if (w < 0) w += inc_per_turn_;
  return w;
}

double Scaling::display_units(std::int64_t inc) const noexcept {
  return to_units(wrap_inc(inc));
}

std::int64_t Scaling::rotary_step(std::int64_t from_inc, double target_units, int direction) const noexcept {
  const std::int64_t turn = inc_per_turn_;
  double m = std::fmod(target_units, modulo_);
  if (m < 0) m += modulo_;
  std::int64_t target = to_inc(m);
  if (target >= turn) target -= turn;
  std::int64_t step = target - wrap_inc(from_inc);  // in (-turn, turn)
  if (direction > 0) {
    if (step < 0) step += turn;
  } else if (direction < 0) {
    if (step > 0) step -= turn;
  } else {
    if (step < 0) step += turn;         // [0, turn)
    if (2 * step > turn) step -= turn;  // (-turn/2, turn/2]; a tie goes positive
  }
  return step;
}

}  // namespace hil::motion
