// SPDX-License-Identifier: MIT
#pragma once
// Fixed-point words: engineering value = raw × lsb, lsb a rational number. Covers the manuals'
// formats such as AMKASYN Kp (raw 512 = 2.0, lsb 1/256), ratios (10000 = 1.0, lsb 1/10000),
// SINUMERIK units (0.01 s^-1) and CLM IU scalings.

#include <cstdint>
#include <expected>
#include <string>

#include "hil/profiles/codec_error.hpp"
#include "hil/profiles/decimal.hpp"
#include "hil/profiles/twos_complement.hpp"

namespace hil::profiles {

struct FixedPointFormat {
  TwosComplementFormat word{16, true};
  std::int64_t lsb_num = 1;  ///< lsb = lsb_num / lsb_den (both > 0)
  std::int64_t lsb_den = 1;

  /// "1/256", "0.0001", "10" → lsb.
  [[nodiscard]] static std::expected<FixedPointFormat, std::string> parse_lsb(std::string_view lsb,
                                                                              TwosComplementFormat word);
};

/// raw = round(v / lsb), half away from zero. Fails with out_of_range when raw does not fit the word.
[[nodiscard]] std::expected<std::int64_t, CodecError> make_fixed_point(const Decimal& v, const FixedPointFormat& f);
/// value = raw × lsb, exact when representable with ≤ 12 decimals (else rounded to 12).
[[nodiscard]] std::expected<Decimal, CodecError> parse_fixed_point(std::int64_t raw, const FixedPointFormat& f);

}  // namespace hil::profiles
