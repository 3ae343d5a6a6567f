// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/calculator.hpp"

namespace hil::controllers::elg {

double ms_unit_deg(std::int64_t pulses_per_rev) noexcept {
  return 360.0 / (4.0 * static_cast<double>(pulses_per_rev));
}
double input_unit_deg(std::int64_t pulses_per_rev) noexcept {
  return 2.0 * ms_unit_deg(pulses_per_rev);
}
double pulses_for_resolution(double resolution_deg) noexcept {
  return 360.0 / (4.0 * resolution_deg);
}
double resolution_deg(double lines_per_rev, double gear_ku) noexcept {
  return 360.0 / (4.0 * lines_per_rev * gear_ku);
}
double max_axis_speed_rpm(double f_max_hz, std::int64_t pulses_per_rev) noexcept {
  return 60.0 * f_max_hz / static_cast<double>(pulses_per_rev);
}
double encoder_frequency_hz(double axis_rpm, std::int64_t pulses_per_rev) noexcept {
  return axis_rpm / 60.0 * static_cast<double>(pulses_per_rev);
}
double inc_step_deg(std::int64_t increments, double ms_deg) noexcept {
  return static_cast<double>(increments) * 2.0 * ms_deg;
}

}  // namespace hil::controllers::elg
