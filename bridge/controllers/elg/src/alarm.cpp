// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/alarm.hpp"

#include <string>

namespace hil::controllers::elg {

std::string_view alarm_text(Alarm alarm) noexcept {
  switch (alarm) {
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
