// SPDX-License-Identifier: MIT
#pragma once
// An exact decimal number: value = units × 10^-scale. Parameter values, ranges and steps are
// kept exact so that "0010.00000", a BCD word and a range check agree to the last digit.

#include <compare>
#include <cstdint>
#include <expected>
#include <string>
#include <string_view>

namespace hil::profiles {

struct Decimal {
  std::int64_t units = 0;  ///< signed mantissa
  int scale = 0;           ///< number of decimals (0..18)
  /// A zero written with a minus sign ("-00000.000"). Equal to zero in every comparison, but a
  /// signed text field writes it back with its '-' (the CLM1.4 keeps it: `A125 -00000.000$7B`).
  bool minus_zero = false;

  [[nodiscard]] static Decimal from_int(std::int64_t v) noexcept { return {v, 0}; }
  /// The same value with `new_scale` decimals; fails (nullopt-like) when digits would be lost
  /// or the mantissa would overflow.
  [[nodiscard]] std::expected<Decimal, std::string> rescaled(int new_scale) const;
  /// Exact integer value, when scale digits are all zero.
  [[nodiscard]] std::expected<std::int64_t, std::string> to_integer() const;
  [[nodiscard]] long double to_long_double() const noexcept;
  /// Shortest exact text: "-24537", "0.234", "10".
  [[nodiscard]] std::string to_string() const;
  /// True when this value is an integer multiple of `step` (step > 0).
  [[nodiscard]] bool is_multiple_of(const Decimal& step) const;

  friend std::strong_ordering operator<=>(const Decimal& a, const Decimal& b) noexcept;
  friend bool operator==(const Decimal& a, const Decimal& b) noexcept { return (a <=> b) == 0; }
};

/// Parses "-24537", "+0010.00000", "1,5" (comma accepted as decimal point), "0x1F" (hex integer).
/// Pure; error text names the offending input.
[[nodiscard]] std::expected<Decimal, std::string> parse_decimal(std::string_view text);

}  // namespace hil::profiles
