// SPDX-License-Identifier: MIT
#pragma once
// Why a value codec refused its input. Codecs are pure (value in, wire form or error out).

#include <string>

namespace hil::profiles {

struct CodecError {
  enum class Kind {
    syntax,         ///< text does not have the field's shape ("12a4", missing sign)
    out_of_range,   ///< value does not fit the wire format (too many digits, > 2^31-1, > 79 999 999)
    invalid_digit,  ///< a BCD nibble A..F where a digit 0..9 is required
    precision,      ///< more decimals than the format carries
  };
  Kind kind = Kind::syntax;
  std::string message;  ///< what was wrong and what is expected
};

}  // namespace hil::profiles
