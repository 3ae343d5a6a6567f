// SPDX-License-Identifier: MIT
#pragma once
// Setting-up calculations of the ELG manual (13.3 encoder / resolution matching, 12.1 footnotes,
// 7.2 INC), as pure functions. `hilbridge profile calc sinumerik-elg` prints them.

#include <cstdint>

namespace hil::controllers::elg {

/// Measuring-system unit of a rotary axis, degrees per count: MS = 360 / (4 * N), N = MD 396* (12.1).
double ms_unit_deg(std::int64_t pulses_per_rev) noexcept;
/// Input-system unit: 1 unit = 2 MS = 180 / N degrees.
double input_unit_deg(std::int64_t pulses_per_rev) noexcept;
/// MD 396* for a wanted resolution A in degrees: N02 = 360 / (4 A) (13.3 (1), (2)).
double pulses_for_resolution(double resolution_deg) noexcept;
/// Resolution from the encoder and its gear: A = 360 / (4 I ku) (13.3 (1)); ku = n_pick-up / n_axis.
double resolution_deg(double lines_per_rev, double gear_ku) noexcept;
/// Highest axis speed in rpm the measuring circuit can count: n = 60 f_max / MD 396* (13.3 (3)),
/// f_max the input frequency limit per track in Hz (500 kHz; 800 kHz planned).
double max_axis_speed_rpm(double f_max_hz, std::int64_t pulses_per_rev) noexcept;
/// Encoder frequency per track in Hz at an axis speed: f = n/60 * MD 396*.
double encoder_frequency_hz(double axis_rpm, std::int64_t pulses_per_rev) noexcept;
/// INC step: dS = increments * 2 MS, in degrees (7.2).
double inc_step_deg(std::int64_t increments, double ms_deg) noexcept;

}  // namespace hil::controllers::elg
