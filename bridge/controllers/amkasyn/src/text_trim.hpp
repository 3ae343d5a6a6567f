// SPDX-License-Identifier: MIT
#pragma once
// Internal: the one whitespace trim of the AMKASYN text readers (STEP 5 AWL, DB listings, analog
// schedules), so that a line ending in CR or a tab reads the same in each.

#include <cctype>
#include <string_view>

namespace hil::controllers::amkasyn::detail {

[[nodiscard]] inline std::string_view trim(std::string_view t) noexcept {
  while (!t.empty() && std::isspace(static_cast<unsigned char>(t.front()))) t.remove_prefix(1);
  while (!t.empty() && std::isspace(static_cast<unsigned char>(t.back()))) t.remove_suffix(1);
  return t;
}

}  // namespace hil::controllers::amkasyn::detail
