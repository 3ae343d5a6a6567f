// SPDX-License-Identifier: MIT
#include "hil/stepdir/ip247_ramp.hpp"

#include <algorithm>
#include <cmath>

namespace hil::stepdir {

std::expected<Ip247Ramp, Ip247MdError> Ip247Ramp::make(const Ip247RampParams& p, std::int64_t min_period_ns) {
  if (!(p.f_max_hz >= 12.0 && p.f_max_hz <= 100'000.0)) return std::unexpected(Ip247MdError::max_frequency);
  if (!(p.f_ss_hz >= 1.0 && p.f_ss_hz <= 10'000.0)) return std::unexpected(Ip247MdError::start_stop_frequency);
  if (!(p.f_ss_hz < p.f_max_hz)) return std::unexpected(Ip247MdError::ramp_generation);
  if (!(p.accel_hz_per_s >= 20.0 && p.accel_hz_per_s < 2'600'000.0)) {
    return std::unexpected(Ip247MdError::frequency_increase);
  }
  Ip247Ramp r;
  r.p_ = p;
  r.big_f_ = (p.f_max_hz - p.f_ss_hz) / 0.95;
  r.tau_ = r.big_f_ / p.accel_hz_per_s;
  if (r.tau_ < 0.005 - 1e-12 || r.tau_ > 2.6 + 1e-12) return std::unexpected(Ip247MdError::frequency_increase);

  const auto cap = std::max(min_period_ns, static_cast<std::int64_t>(std::ceil(1e9 / p.f_max_hz)));
  const auto first = static_cast<std::int64_t>(std::ceil(1e9 / p.f_ss_hz));
  if (first <= cap) return std::unexpected(Ip247MdError::ramp_generation);  // fss not below the usable fmax
  std::int64_t t_ns = 0;
  for (;;) {
    const double f = r.frequency_at(static_cast<double>(t_ns) * 1e-9);
    const auto iv = std::max(cap, static_cast<std::int64_t>(std::ceil(1e9 / f)));
    r.table_.push_back(iv);
    if (iv == cap) break;
    t_ns += iv;
    // f(t) reaches fmax at t = tau ln 20 (about 3 tau <= 7.8 s); bounded well before this.
    if (r.table_.size() > 4'000'000) return std::unexpected(Ip247MdError::ramp_generation);
  }
  return r;
}

double Ip247Ramp::frequency_at(double t_s) const noexcept {
  return big_f_ * (1.0 - std::exp(-t_s / tau_)) + p_.f_ss_hz;
}

double Ip247Ramp::time_to_frequency(double f_v_hz) const noexcept {
  const double x = (f_v_hz - p_.f_ss_hz) / big_f_;
  if (x <= 0.0) return 0.0;
  return -tau_ * std::log(1.0 - x);
}

double Ip247Ramp::distance_steps(double t_s) const noexcept {
  return big_f_ * (t_s + tau_ * (std::exp(-t_s / tau_) - 1.0)) + p_.f_ss_hz * t_s;
}

std::size_t Ip247Ramp::index_for_period(std::int64_t period_ns) const noexcept {
  // The table is non-increasing: first element <= period_ns.
  auto it = std::partition_point(table_.begin(), table_.end(), [&](std::int64_t v) { return v > period_ns; });
  return it == table_.end() ? table_.size() - 1 : static_cast<std::size_t>(it - table_.begin());
}

}  // namespace hil::stepdir
