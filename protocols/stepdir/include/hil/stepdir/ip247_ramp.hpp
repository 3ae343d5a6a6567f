// SPDX-License-Identifier: MIT
#pragma once
// The IP247 exponential ramp (manual §2.5.3.7, digest §2.4):
//   f(t) = F (1 - e^(-t/tau)) + f_ss,   F = (f_max - f_ss) / 0.95,   tau = F / a
// The move jumps to f_ss, accelerates along f(t) until the commanded frequency, and decelerates
// along the mirrored curve down to f_ss, then stops at once.
//
// The ramp table holds the step intervals of the acceleration: interval k (between step k and
// step k+1) = ceil(1 s / f(t_k)) ns, t_0 = 0, t_{k+1} = t_k + interval k (the timer reloads with the
// frequency of the moment, as the module's timer does). So the first interval is exactly 1/f_ss,
// and the table ends at the first interval <= the shortest allowed period (fmax and the pulse rule).
// Pure; built once at configuration time.

#include <cstddef>
#include <cstdint>
#include <expected>
#include <span>
#include <vector>

#include "hil/stepdir/ip247_error.hpp"

namespace hil::stepdir {

struct Ip247RampParams {
  double f_max_hz = 5'000.0;         ///< MD n+5/6
  double f_ss_hz = 200.0;            ///< MD n+7/8
  double accel_hz_per_s = 50'000.0;  ///< MD n+9/10 "frequency increase" a; mHz/ms == Hz/s
};

class Ip247Ramp {
 public:
  /// Validate (MD errors 3, 6, 16, 22) and build the table. `min_period_ns` is the shortest step
  /// period the timing rules allow (StepTiming::min_period_ns()).
  [[nodiscard]] static std::expected<Ip247Ramp, Ip247MdError> make(const Ip247RampParams& p,
                                                                   std::int64_t min_period_ns);

  [[nodiscard]] const Ip247RampParams& params() const noexcept { return p_; }
  [[nodiscard]] double big_f_hz() const noexcept { return big_f_; }  ///< F
  [[nodiscard]] double tau_s() const noexcept { return tau_; }

  /// f(t) by the formula (t in s from the start of acceleration).
  [[nodiscard]] double frequency_at(double t_s) const noexcept;
  /// Time to reach f_v: -tau ln(1 - (f_v - f_ss)/F) (the manual prints f_v/F; see docs).
  [[nodiscard]] double time_to_frequency(double f_v_hz) const noexcept;
  /// Steps covered by acceleration in [0, t]: F (t + tau (e^(-t/tau) - 1)) + f_ss t (the manual's
  /// distance integral, in steps; = braking distance from f(t)).
  [[nodiscard]] double distance_steps(double t_s) const noexcept;

  /// Interval k of the acceleration (ns); k beyond the table gives the last (shortest) interval.
  [[nodiscard]] std::int64_t interval_ns(std::size_t k) const noexcept {
    return k < table_.size() ? table_[k] : table_.back();
  }
  [[nodiscard]] std::span<const std::int64_t> table() const noexcept { return table_; }
  /// First index whose interval is <= period_ns (the index where the commanded speed is reached).
  [[nodiscard]] std::size_t index_for_period(std::int64_t period_ns) const noexcept;

 private:
  Ip247RampParams p_;
  double big_f_ = 0.0;
  double tau_ = 0.0;
  std::vector<std::int64_t> table_;
};

}  // namespace hil::stepdir
