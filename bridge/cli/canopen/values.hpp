// SPDX-License-Identifier: MIT
#pragma once
// SDO value types of the CLI (CiA 309-3 names: b, i8..i64, u8..u64, x8..x64, r32, r64, vs, os,
// d, and `hex` as in `modbus` and the profiles: unsigned in hex, the object's width; docs/cli.md):
// text <-> little-endian bytes. Pure.

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <vector>

namespace hil::cli::canopen_cli {

[[nodiscard]] bool is_value_type(std::string_view type) noexcept;
[[nodiscard]] std::string value_types_help();
/// Encode `text` as `type`; the error names the type and the accepted range.
[[nodiscard]] std::expected<std::vector<std::uint8_t>, std::string> encode_value(std::string_view type,
                                                                                 std::string_view text);
/// Format `bytes` as `type` (empty type: hex bytes, plus the unsigned value when 1..8 bytes).
[[nodiscard]] std::string format_value(std::string_view type, const std::vector<std::uint8_t>& bytes);
/// "0x6041:0", "6041:0", "0x1018:1" -> index, sub.
[[nodiscard]] std::expected<std::pair<std::uint16_t, std::uint8_t>, std::string> parse_object(std::string_view text);

}  // namespace hil::cli::canopen_cli
