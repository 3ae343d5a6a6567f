// SPDX-License-Identifier: MIT
#pragma once
// Step/dir timing rules, named as LinuxCNC's stepgen names them (steplen, stepspace, dirsetup,
// dirhold; all ns) plus the IP247's polarity MD (active edge and idle level) and fmax.

#include <cstdint>
#include <expected>
#include <string_view>

#include "hil/stepdir/ip247_error.hpp"

namespace hil::stepdir {

/// IP247 polarity MD (§2.5.1.1): positive edge = step idle low, pulses high; negative edge =
/// idle high, pulses low.
enum class Polarity : std::uint8_t { positive_edge, negative_edge };

/// The manual quantises the pulse duration to 2 µs but does not say in which direction
/// (digest §1.2 [gap]); configurable, default `up`.
enum class PulseRounding : std::uint8_t { up, down };

struct StepTiming {
  std::int64_t step_len_ns = 2'000;    ///< step pulse length, active edge to trailing edge
  std::int64_t step_space_ns = 2'000;  ///< minimum trailing edge to next active edge
  std::int64_t dir_setup_ns = 5'000;   ///< minimum dir change to next active edge
  std::int64_t dir_hold_ns = 5'000;    ///< minimum previous trailing edge to dir change
  double max_freq_hz = 100'000.0;      ///< fmax (<= 100 kHz)
  Polarity polarity = Polarity::positive_edge;
  /// Logical dir level meaning "forward" (toward limit "Ende"). The manual's Fig. 2/7 with the
  /// level table is lost; default: high = forward for positive edge, low for negative edge.
  bool dir_forward_level = true;

  [[nodiscard]] bool step_idle_level() const noexcept { return polarity == Polarity::negative_edge; }
  [[nodiscard]] bool dir_level(int direction) const noexcept {
    return direction >= 0 ? dir_forward_level : !dir_forward_level;
  }
  /// Shortest allowed step period: max(ceil(1 s / fmax), step_len + step_space).
  [[nodiscard]] std::int64_t min_period_ns() const noexcept;
};

/// Check a timing set (MD error 2 for width/space vs period, 3 for fmax).
[[nodiscard]] std::expected<StepTiming, Ip247MdError> validate(const StepTiming& t) noexcept;

/// IP247 pulse duration: 1..31 µs entered, output in 2 µs steps (2*ceil or 2*floor, never 0).
/// Returns ns, or MD error 2 outside 1..31.
[[nodiscard]] std::expected<std::int64_t, Ip247MdError> quantise_pulse_us(int pulse_us, PulseRounding r) noexcept;

/// IP247-style timing: quantised pulse, space = pulse (so the period rule t_p <= T/2 holds at fmax),
/// dir setup/hold given. Checks t_p <= 1/(2 fmax) (MD error 2) and fmax (MD error 3).
[[nodiscard]] std::expected<StepTiming, Ip247MdError> make_ip247_timing(int pulse_us, PulseRounding r, double f_max_hz,
                                                                        Polarity p, std::int64_t dir_setup_ns,
                                                                        std::int64_t dir_hold_ns) noexcept;

}  // namespace hil::stepdir
