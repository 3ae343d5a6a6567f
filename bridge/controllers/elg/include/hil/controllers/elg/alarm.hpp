// SPDX-License-Identifier: MIT
#pragma once
// SINUMERIK System 3 ELG alarms raised by the gearbox model (manual 06.85, ch. 11 and 12.3;
// digest shared/seeds/sinumerik-elg.md §10). The enum values are the manual's alarm numbers.

#include <cstdint>
#include <string_view>
#include <system_error>

namespace hil::controllers::elg {

enum class Alarm : std::uint16_t {
  stop_behind_reference_cams = 1840,    ///< 184*: REF stopped between cam and zero mark (+ axis index)
  emergency_off = 2000,                 ///< PC outputs EMERGENCY OFF
  program_speed_too_high = 2035,        ///< JOG/INC/REF set speed above MD 280* (coupling OFF)
  power_on_error = 2200,                ///< constants cannot be computed (MD 252*, 396*, 170, 5020/5021)
  compensation_not_possible = 2201,     ///< partial set value too high for FE compensation
  partial_set_value_overflow = 2202,    ///< overflow computing the partial set value
  constants_error = 2203,               ///< Z2 = 0, N02 = 0 with Z0 != 0, constants too large
  partial_set_value_too_high = 2205,    ///< partial set value beyond the limit: clamped
  partial_set_value_near_limit = 2206,  ///< pre-warning for 2205
  gearing_not_permissible = 2207,       ///< Gearing ON without computed constants / approach condition
  v24_not_permitted = 2214,             ///< Data Start while coupled
  following_error_exceeded = 2215,      ///< C following error > max(MD 169, R40) while monitored
  pc_data_channel_error = 3016,         ///< PC-ELG data channel: wrong code, value too high, dimension
  pc_datum_not_present = 3018,          ///< PC-ELG data channel: unknown MD/SD number
};

/// The manual's alarm text (12.3), upper case as on the VDU.
std::string_view alarm_text(Alarm alarm) noexcept;

/// Alarms that only POWER ON RESET clears (2200; 132* is axis hardware, not modelled here).
constexpr bool needs_power_on_reset(Alarm alarm) noexcept {
  return alarm == Alarm::power_on_error;
}

/// `std::error_category` "sinumerik-elg": value = alarm number, message = the manual's text.
const std::error_category& elg_category() noexcept;
inline std::error_code make_error_code(Alarm alarm) noexcept {
  return {static_cast<int>(alarm), elg_category()};
}

}  // namespace hil::controllers::elg

template <>
struct std::is_error_code_enum<hil::controllers::elg::Alarm> : std::true_type {};
