// SPDX-License-Identifier: MIT
#pragma once
// Bit fields: named single bits and multi-bit groups inside a word (WF 725/726 MD 41 check mask,
// SINUMERIK MD 5002/5020/564*, AMKASYN function codes).

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <vector>

#include "hil/profiles/codec_error.hpp"

namespace hil::profiles {

struct BitDef {
  std::string name;    ///< "K", "unit_input_system"
  unsigned first = 0;  ///< least significant bit number
  unsigned width = 1;  ///< number of bits
  std::string meaning;
};

struct BitFieldFormat {
  unsigned bits = 16;          ///< word width
  std::vector<BitDef> fields;  ///< non-overlapping
  bool allow_unnamed = false;  ///< false: a set bit outside every field is an error
};

struct BitValue {
  std::string name;
  std::uint64_t value = 0;
  friend bool operator==(const BitValue&, const BitValue&) = default;
};

/// Packs named values. Fails on an unknown name or a value wider than its field.
[[nodiscard]] std::expected<std::uint64_t, CodecError> make_bit_field(const std::vector<BitValue>& values,
                                                                      const BitFieldFormat& f);
/// Splits `word` into every field's value (in definition order). Fails when bits above `bits`
/// or (unless allow_unnamed) bits outside every field are set.
[[nodiscard]] std::expected<std::vector<BitValue>, CodecError> parse_bit_field(std::uint64_t word,
                                                                               const BitFieldFormat& f);
/// "K|S|J" or "unit_input=2,unit_measuring=2" → values; inverse of bit_field_text.
[[nodiscard]] std::expected<std::vector<BitValue>, CodecError> parse_bit_field_text(std::string_view text,
                                                                                    const BitFieldFormat& f);
/// Names of the set single bits joined by '|', groups as name=value; "0" when nothing is set.
[[nodiscard]] std::string bit_field_text(const std::vector<BitValue>& values, const BitFieldFormat& f);

}  // namespace hil::profiles
