// SPDX-License-Identifier: MIT
#pragma once
// One S5 data-block value as the manuals write it in their DB listings: decimal (KF/KD, with an
// optional sign) or hexadecimal as "0x1F" or "1Fh" (KH). The AMKASYN SF parameter sets of the
// profiles and the AMKASYN table DBs read their values with it.

#include <cstdint>
#include <optional>
#include <string_view>

namespace hil::profiles {

/// "+120", "-5", "0x1F", "1Fh" -> the integer; nothing on any other text or on 64-bit overflow.
[[nodiscard]] std::optional<std::int64_t> parse_db_integer(std::string_view text) noexcept;

}  // namespace hil::profiles
