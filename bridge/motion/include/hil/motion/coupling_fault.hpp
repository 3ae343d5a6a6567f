// SPDX-License-Identifier: MIT
#pragma once
// Faults of a coupled slave (category "coupling"). The values are hilbridge's own numbers; the
// device layers (AMKASYN SF, CLM1.4 FOL, SINUMERIK ELG) map them onto their manuals' codes.

#include <system_error>

namespace hil::motion {

enum class CouplingFault : int {
  none = 0,
  velocity_limit = 1,      ///< the coupling demands a slave velocity above the slave's limit
  acceleration_limit = 2,  ///< ... an acceleration above the slave's limit
  following_error = 3,     ///< |slave actual - coupling command| above the coupling window
  invalid = 4,             ///< bad ratio, table or transition (rejected, nothing changed)
};
[[nodiscard]] const std::error_category& coupling_category() noexcept;
inline std::error_code make_error_code(CouplingFault f) noexcept {
  return {static_cast<int>(f), coupling_category()};
}

}  // namespace hil::motion

template <>
struct std::is_error_code_enum<hil::motion::CouplingFault> : std::true_type {};
