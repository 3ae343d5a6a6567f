// SPDX-License-Identifier: MIT
#include "hil/controllers/clm14/address.hpp"

#include <fmt/format.h>

namespace hil::controllers::clm14 {

namespace {

bool digit(char c) {
  return c >= '0' && c <= '9';
}

std::optional<ByteAddress> byte_of(std::string_view t) {
  // "M2.02": type, source digit, '.', two byte digits
  if (t.size() != 5 || t[2] != '.' || !digit(t[1]) || !digit(t[3]) || !digit(t[4])) return std::nullopt;
  ByteAddress a;
  switch (t[0]) {
    case 'I':
      a.area = Area::input;
      break;
    case 'Q':
      a.area = Area::output;
      break;
    case 'M':
      a.area = Area::marker;
      break;
    default:
      return std::nullopt;
  }
  a.source = static_cast<std::uint8_t>(t[1] - '0');
  a.byte = static_cast<std::uint8_t>((t[3] - '0') * 10 + (t[4] - '0'));
  const int sources = a.area == Area::marker ? 7 : 3;
  const int bytes = a.area == Area::marker ? marker_bytes : io_bytes;
  if (a.source >= sources || a.byte >= bytes) return std::nullopt;
  return a;
}

}  // namespace

std::optional<ByteAddress> parse_byte(std::string_view t) noexcept {
  return byte_of(t);
}

std::optional<BitAddress> parse_bit(std::string_view t) noexcept {
  if (t.size() != 7 || t[5] != '.' || !digit(t[6])) return std::nullopt;
  auto b = byte_of(t.substr(0, 5));
  if (!b || t[6] > '7') return std::nullopt;
  return BitAddress{*b, static_cast<std::uint8_t>(t[6] - '0')};
}

OptionalBit parse_optional_bit(std::string_view t) noexcept {
  if (t == "00.00.0") return {std::nullopt, true};
  auto b = parse_bit(t);
  return {b, b.has_value()};
}

std::string to_string(const ByteAddress& a) {
  const char type = a.area == Area::input ? 'I' : a.area == Area::output ? 'Q' : 'M';
  return fmt::format("{}{}.{:02d}", type, a.source, a.byte);
}

std::string to_string(const BitAddress& a) {
  return fmt::format("{}.{}", to_string(a.byte), a.bit);
}

}  // namespace hil::controllers::clm14
