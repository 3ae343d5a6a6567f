// SPDX-License-Identifier: MIT
#pragma once
// N-bit two's complement words (WF 725/726 "binary" MD format, IP247 DD/KF, AMKASYN DW/DD).

#include <cstdint>
#include <expected>

#include "hil/profiles/codec_error.hpp"

namespace hil::profiles {

struct TwosComplementFormat {
  int bits = 32;          ///< 8, 16, 32 or 64
  bool is_signed = true;  ///< false: plain unsigned word of `bits` bits
};

/// Encodes `v`; out_of_range when it does not fit (e.g. 2^31 in a signed 32-bit word).
[[nodiscard]] std::expected<std::uint64_t, CodecError> make_twos_complement(std::int64_t v,
                                                                            const TwosComplementFormat& f);
/// Decodes `word`; syntax error when bits above `bits` are set.
[[nodiscard]] std::expected<std::int64_t, CodecError> parse_twos_complement(std::uint64_t word,
                                                                            const TwosComplementFormat& f);

}  // namespace hil::profiles
