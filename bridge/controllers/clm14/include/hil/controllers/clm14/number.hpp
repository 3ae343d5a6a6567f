// SPDX-License-Identifier: MIT
#pragma once
// CLM1.4 numbers (manual §5.6, digest clm14.md §3.6): every variable holds sign, 8 integer and
// 6 decimal digits ("+12345678.123456"). The model keeps them exact as integer millionths, so
// MAT arithmetic, CVT's BCD digits and the command-field checks agree to the last digit.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hil::controllers::clm14 {

/// Value in millionths (1.0 = 1'000'000).
using Micro = std::int64_t;

inline constexpr Micro micro_one = 1'000'000;
/// Largest variable magnitude: 99999999.999999.
inline constexpr Micro variable_max = 99'999'999'999'999;

/// Parse "+123456.789", "-0.5", "20", "1,5" (',' = '.'); at most 6 decimals and 8 integer
/// digits after dropping leading zeros. nullopt when malformed.
[[nodiscard]] std::optional<Micro> parse_micro(std::string_view text) noexcept;
/// "+12345678.123456" (the variable format of status replies and V telegrams).
[[nodiscard]] std::string format_variable(Micro v);
/// "+123456.789" / "-00012.345": sign, `int_digits`, '.', `frac_digits` (truncated toward zero).
[[nodiscard]] std::string format_fixed(Micro v, int int_digits, int frac_digits, bool sign = true);

/// Micro value of a length in IU (rounded to the nearest millionth).
[[nodiscard]] Micro to_micro(double v) noexcept;
[[nodiscard]] constexpr double to_double(Micro v) noexcept {
  return static_cast<double>(v) / 1e6;
}

}  // namespace hil::controllers::clm14
