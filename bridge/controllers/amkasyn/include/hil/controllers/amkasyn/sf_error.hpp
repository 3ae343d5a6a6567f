// SPDX-License-Identifier: MIT
#pragma once
// SF commanding errors (MB 232 error bit, MB/MD 233 error number). The manual defers the numbers
// to "AMK-specific function blocks", which is not available; the values are the profile's
// catalogue `sf_status` (profiles/devices/amkasyn-sf/errors.yaml, hilbridge numbering).

#include <string>
#include <system_error>

namespace hil::controllers::amkasyn {

enum class SfError : int {
  none = 0,
  start_invalid = 1,         ///< START with invalid or out-of-range parameters (the SF stays in RESET)
  start_while_active = 2,    ///< START while SF-ACTIVE
  value_new_not_active = 3,  ///< VALUE NEW outside SF-ACTIVE (or not supported by the SF)
  xfipw_not_reset = 4,       ///< XFIPW: START / READ VALUE not in Reset
  xfipw_not_started = 5,     ///< XFIPW: VALUE NEW not started
  apsf_runtime = 6,          ///< APSF running time error
};
[[nodiscard]] const std::error_category& sf_category() noexcept;
inline std::error_code make_error_code(SfError e) noexcept {
  return {static_cast<int>(e), sf_category()};
}

/// A commanding error with the text that says which parameter and which rule.
struct SfFault {
  SfError code = SfError::none;
  std::string text;
};

}  // namespace hil::controllers::amkasyn

template <>
struct std::is_error_code_enum<hil::controllers::amkasyn::SfError> : std::true_type {};
