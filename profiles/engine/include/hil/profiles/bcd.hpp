// SPDX-License-Identifier: MIT
#pragma once
// Packed BCD words (8 nibbles, 32 bits) with the sign conventions of the manuals.

#include <cstdint>
#include <expected>
#include <string>

#include "hil/profiles/codec_error.hpp"

namespace hil::profiles {

enum class BcdSign {
  none,    ///< 8 digits, 0 … 99 999 999
  bit31,   ///< WF 725/726 §4.3: bit 31 = sign (1 = negative), bits 30..28 = 10^7 digit 0..7;
           ///< range ±79 999 999; "-24 537" = 0x80024537
  nibble,  ///< IP247 §6.2.7.2 AG values: top nibble 0 = positive, F = negative, 7 digits;
           ///< range ±9 999 999; "-120 000" = 0xF0120000
};

struct BcdFormat {
  int digits = 8;  ///< 1..8 digit nibbles counted from the least significant one
  BcdSign sign = BcdSign::none;
};

/// Largest magnitude the format carries (99 999 999, 79 999 999, 9 999 999, …).
[[nodiscard]] std::int64_t bcd_max_magnitude(const BcdFormat& f) noexcept;
/// Packs `v`. Fails with out_of_range when |v| exceeds bcd_max_magnitude or v < 0 unsigned.
[[nodiscard]] std::expected<std::uint32_t, CodecError> make_bcd(std::int64_t v, const BcdFormat& f);
/// Unpacks `word`. Fails with invalid_digit on a nibble > 9 (naming the nibble), and with
/// syntax when bits outside the format are set (e.g. a top nibble other than 0/F for `nibble`).
[[nodiscard]] std::expected<std::int64_t, CodecError> parse_bcd(std::uint32_t word, const BcdFormat& f);

}  // namespace hil::profiles
