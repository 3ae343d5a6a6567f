// SPDX-License-Identifier: MIT
#include "hil/controllers/io_address_clm.hpp"

#include <cctype>

#include <fmt/format.h>

namespace hil::controllers {
namespace {

bool digit(char c) noexcept {
  return c >= '0' && c <= '9';
}

}  // namespace

std::expected<ClmAddress, std::string> parse_clm_address(std::string_view text) {
  const auto fail = [&](std::string_view why) {
    return std::unexpected(fmt::format("'{}': {} (CLM address Ix.yy.z / Qx.yy.z / Mx.yy.z, e.g. I0.00.1)", text, why));
  };
  if (text.empty()) return fail("empty");
  const char type = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  if (type != 'I' && type != 'Q' && type != 'M') return fail("must start with I, Q or M");
  // Exact form: letter, one group digit, '.', two byte digits, '.', one bit digit.
  if (text.size() != 7) {
    if (text.size() == 6 && digit(text[1]) && text[2] == '.' && digit(text[3]) && text[4] == '.') {
      return fail("byte needs two digits (yy)");
    }
    return fail("wrong length");
  }
  if (!digit(text[1])) return fail("group x must be a digit");
  if (text[2] != '.' || text[5] != '.') return fail("'.' expected after x and after yy");
  if (!digit(text[3]) || !digit(text[4])) return fail("byte yy must be two digits");
  if (!digit(text[6])) return fail("bit z must be a digit");
  ClmAddress a;
  a.type = type;
  a.group = static_cast<std::uint8_t>(text[1] - '0');
  a.byte = static_cast<std::uint8_t>((text[3] - '0') * 10 + (text[4] - '0'));
  a.bit = static_cast<std::uint8_t>(text[6] - '0');
  if (a.byte >= clm_group_stride) return fail(fmt::format("byte yy must be 00..{}", clm_group_stride - 1));
  if (a.bit > 7) return fail("bit z must be 0..7");
  return a;
}

bool is_clm_unused(std::string_view text) noexcept {
  return text == "00.00.0" || text == "0.00.0";
}

std::string format_clm_address(const ClmAddress& a) {
  return fmt::format("{}{}.{:02}.{}", a.type, a.group, a.byte, a.bit);
}

std::optional<ClmAddress> to_clm_address(BitAddress a) noexcept {
  if (a.area == IoArea::data || a.bit > 7) return std::nullopt;
  const auto group = a.byte / clm_group_stride;
  if (group > clm_max_group) return std::nullopt;
  const char type = a.area == IoArea::input ? 'I' : a.area == IoArea::output ? 'Q' : 'M';
  return ClmAddress{type, static_cast<std::uint8_t>(group), static_cast<std::uint8_t>(a.byte % clm_group_stride),
                    a.bit};
}

}  // namespace hil::controllers
