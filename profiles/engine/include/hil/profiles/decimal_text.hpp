// SPDX-License-Identifier: MIT
#pragma once
// Fixed-width decimal text fields, as in the CLM1.4 telegram data ("+123456.789", "0010.00000",
// "03000") and the manuals' "±6.3"-style notation.

#include <expected>
#include <string>
#include <string_view>

#include "hil/profiles/codec_error.hpp"
#include "hil/profiles/decimal.hpp"

namespace hil::profiles {

struct DecimalTextFormat {
  enum class Sign {
    none,    ///< no sign character; negative values are rejected
    always,  ///< '+' or '-' always written (and required when parsing strictly)
  };
  Sign sign = Sign::none;
  int int_digits = 1;   ///< zero-padded integer digits
  int frac_digits = 0;  ///< digits after '.'

  /// "+6.3" (sign, 6 integer, 3 decimals), "4.5", "5" (5-digit integer), "±5.3" (same as "+5.3").
  [[nodiscard]] static std::expected<DecimalTextFormat, std::string> parse(std::string_view spec);
  [[nodiscard]] std::string to_string() const;  ///< inverse of parse
  [[nodiscard]] std::size_t width() const noexcept;
  /// Largest magnitude the field can carry, e.g. 999999.999 for "+6.3".
  [[nodiscard]] Decimal max_magnitude() const noexcept;
};

/// Writes `v` zero-padded to the exact field width. Fails with out_of_range when the integer part
/// has too many digits, precision when `v` has more decimals than the field, out_of_range for a
/// negative value in an unsigned field.
[[nodiscard]] std::expected<std::string, CodecError> make_decimal_text(const Decimal& v, const DecimalTextFormat& f);

/// Reads a field. Accepts ',' for '.', fewer integer digits than the width (the devices pad, but
/// operators type "1.5"), and a missing '+' on signed fields. Rejects too many digits or decimals,
/// a sign on an unsigned field, and any other character.
[[nodiscard]] std::expected<Decimal, CodecError> parse_decimal_text(std::string_view text, const DecimalTextFormat& f);

}  // namespace hil::profiles
