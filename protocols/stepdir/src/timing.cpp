// SPDX-License-Identifier: MIT
#include "hil/stepdir/timing.hpp"

#include <algorithm>
#include <cmath>

namespace hil::stepdir {

std::int64_t StepTiming::min_period_ns() const noexcept {
  const auto by_freq = static_cast<std::int64_t>(std::ceil(1e9 / max_freq_hz));
  return std::max(by_freq, step_len_ns + step_space_ns);
}

std::expected<StepTiming, Ip247MdError> validate(const StepTiming& t) noexcept {
  if (!(t.max_freq_hz >= 12.0 && t.max_freq_hz <= 100'000.0)) return std::unexpected(Ip247MdError::max_frequency);
  if (t.step_len_ns <= 0 || t.step_space_ns < 0 || t.dir_setup_ns < 0 || t.dir_hold_ns < 0) {
    return std::unexpected(Ip247MdError::pulse_duration);
  }
  const auto period = static_cast<std::int64_t>(std::floor(1e9 / t.max_freq_hz));
  if (t.step_len_ns + t.step_space_ns > period) return std::unexpected(Ip247MdError::pulse_duration);
  return t;
}

std::expected<std::int64_t, Ip247MdError> quantise_pulse_us(int pulse_us, PulseRounding r) noexcept {
  if (pulse_us < 1 || pulse_us > 31) return std::unexpected(Ip247MdError::pulse_duration);
  const int q = r == PulseRounding::up ? 2 * ((pulse_us + 1) / 2) : std::max(2, 2 * (pulse_us / 2));
  return std::int64_t{q} * 1000;
}

std::expected<StepTiming, Ip247MdError> make_ip247_timing(int pulse_us, PulseRounding r, double f_max_hz, Polarity p,
                                                          std::int64_t dir_setup_ns,
                                                          std::int64_t dir_hold_ns) noexcept {
  auto len = quantise_pulse_us(pulse_us, r);
  if (!len) return std::unexpected(len.error());
  StepTiming t;
  t.step_len_ns = *len;
  t.step_space_ns = *len;
  t.dir_setup_ns = dir_setup_ns;
  t.dir_hold_ns = dir_hold_ns;
  t.max_freq_hz = f_max_hz;
  t.polarity = p;
  t.dir_forward_level = p == Polarity::positive_edge;
  return validate(t);
}

}  // namespace hil::stepdir
