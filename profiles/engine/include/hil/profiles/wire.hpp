// SPDX-License-Identifier: MIT
#pragma once
// A parameter value's wire form and back: CLM telegram field text ("03000 10.0"), WF 725/726 BCD
// and binary words, S5 data-word images (IP247 MD DB, AMKASYN blocks), SINUMERIK tape values.

#include <cstdint>
#include <expected>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hil/profiles/field_value.hpp"
#include "hil/profiles/profile.hpp"

namespace hil::profiles {

struct WireImage {
  std::string text;                     ///< text form as sent ("03000 10.0", "8002 4537")
  std::vector<std::uint16_t> words;     ///< word image, high word first (word devices)
  std::optional<std::uint32_t> bcd;     ///< WF 725/726 "decimal" (BCD) format
  std::optional<std::uint32_t> binary;  ///< WF 725/726 binary (two's complement) format
  /// Multi-line human form for the CLI.
  [[nodiscard]] std::string describe() const;
};

/// A field's user-facing value from text: numbers ("1.5", "-24537", "0x1F"), I/O addresses,
/// hex digits, bit names ("K|S|J") or numbers for bit fields, choice numbers.
[[nodiscard]] std::expected<FieldValue, std::string> parse_field_input(const FieldSpec& f, std::string_view text);
/// All fields from whitespace-separated user text ("3000 10"); reserved fields may be omitted.
[[nodiscard]] std::expected<ParamValue, std::string> parse_value_input(const ParamVariant& v, std::string_view text);
/// User-facing text of a value ("3000 10", "I1.00.0 +100 0").
[[nodiscard]] std::string value_text(const ParamVariant& v, const ParamValue& value);

/// Field text exactly as on the wire for text encodings ("+123456.789", "I1.00.0").
[[nodiscard]] std::expected<std::string, std::string> make_field_text(const FieldSpec& f, const FieldValue& v);
/// Field from its wire text; strict about width-independent shape, lenient about padding.
[[nodiscard]] std::expected<FieldValue, std::string> parse_field_text(const FieldSpec& f, std::string_view text);

/// Encodes `value` of `variant` per the profile's wire spec.
[[nodiscard]] std::expected<WireImage, std::string> encode_value(const Profile& p, const ParamVariant& variant,
                                                                 const ParamValue& value);
/// Decodes a wire form: text fields, "8002 4537" / "BCD 80024537" / "HEX FFFFA027" for bcd_binary,
/// hex words "0000 1388" for word encodings.
[[nodiscard]] std::expected<ParamValue, std::string> decode_wire(const Profile& p, const ParamVariant& variant,
                                                                 std::string_view wire);

}  // namespace hil::profiles
