// SPDX-License-Identifier: MIT
#include "hil/profiles/db_integer_text.hpp"

#include <charconv>

namespace hil::profiles {

std::optional<std::int64_t> parse_db_integer(std::string_view t) noexcept {
  bool neg = false;
  if (!t.empty() && (t.front() == '+' || t.front() == '-')) {
    neg = t.front() == '-';
    t.remove_prefix(1);
  }
  int base = 10;
  if (t.starts_with("0x") || t.starts_with("0X")) {
    base = 16;
    t.remove_prefix(2);
  } else if (!t.empty() && (t.back() == 'h' || t.back() == 'H')) {
    base = 16;
    t.remove_suffix(1);
  }
  // from_chars takes no sign of its own here: "+-5" and "0x-5" are refused.
  if (t.empty() || t.front() == '-' || t.front() == '+') return std::nullopt;
  std::int64_t v = 0;
  const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v, base);
  if (ec != std::errc{} || p != t.data() + t.size()) return std::nullopt;
  return neg ? -v : v;
}

}  // namespace hil::profiles
