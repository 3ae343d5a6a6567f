// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/alarm.hpp"

#include <string>

namespace hil::controllers::elg {

std::string_view alarm_text(Alarm alarm) noexcept {
  const auto n = static_cast<int>(alarm);
  if (n >= 1840 && n <= 1843) return "STOP BEHIND REFERENCE CAMS";
  switch (alarm) {
    case Alarm::stop_behind_reference_cams:
      return "STOP BEHIND REFERENCE CAMS";
    case Alarm::program_speed_too_high:
      return "PROGRAM SPEED TOO HIGH";
    case Alarm::pc_data_channel_error:
      return "ERROR PC-ELG DATA CHANNEL";
    case Alarm::pc_datum_not_present:
      return "DATUM NOT PRESENT, PC-ELG DATA CHANNEL";
    case Alarm::emergency_off:
      return "EMERGENCY OFF";
    case Alarm::power_on_error:
      return "ELG - POWER ON ERROR";
    case Alarm::compensation_not_possible:
      return "ELG - COMPENSATION NOT POSSIBLE";
    case Alarm::partial_set_value_overflow:
      return "ELG - ERROR IN COMPUTATION OF PARTIAL SET VALUE";
    case Alarm::constants_error:
      return "ELG - ERROR IN COMPUTING ELG CONSTANTS";
    case Alarm::partial_set_value_too_high:
      return "ELG - PARTIAL SET VALUE TOO HIGH";
    case Alarm::partial_set_value_near_limit:
      return "ELG - PARTIAL SET VALUE CLOSE TO TOLERANCE LIMIT";
    case Alarm::gearing_not_permissible:
      return "ELG - GEARING FUNCTION NOT PERMISSIBLE";
    case Alarm::v24_not_permitted:
      return "ELG - OPERATION OF V.24 INTERFACE NOT PERMITTED";
    case Alarm::following_error_exceeded:
      return "ELG - MAX. FOLLOWING ERROR MONITORING VALUE EXCEEDED";
  }
  return "ELG - UNKNOWN ALARM";
}

namespace {
class Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "sinumerik-elg"; }
  std::string message(int value) const override { return std::string(alarm_text(static_cast<Alarm>(value))); }
};
}  // namespace

const std::error_category& elg_category() noexcept {
  static const Category category;
  return category;
}

}  // namespace hil::controllers::elg
