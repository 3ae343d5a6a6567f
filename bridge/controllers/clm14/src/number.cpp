// SPDX-License-Identifier: MIT
#include "hil/controllers/clm14/number.hpp"

#include <fmt/format.h>

#include <cmath>

namespace hil::controllers::clm14 {

std::optional<Micro> parse_micro(std::string_view t) noexcept {
  if (t.empty()) return std::nullopt;
  bool neg = false;
  if (t.front() == '+' || t.front() == '-') {
    neg = t.front() == '-';
    t.remove_prefix(1);
  }
  Micro ip = 0, fp = 0;
  int int_digits = 0, frac_digits = 0;
  bool point = false;
  for (char c : t) {
    if (c == '.' || c == ',') {
      if (point) return std::nullopt;
      point = true;
      continue;
    }
    if (c < '0' || c > '9') return std::nullopt;
    if (point) {
      if (++frac_digits > 6) return std::nullopt;
      fp = fp * 10 + (c - '0');
    } else {
      if (int_digits > 0 || c != '0') ++int_digits;
      if (int_digits > 8) return std::nullopt;
      ip = ip * 10 + (c - '0');
    }
  }
  if (int_digits == 0 && frac_digits == 0 && t.find('0') == std::string_view::npos) return std::nullopt;
  for (int i = frac_digits; i < 6; ++i) fp *= 10;
  const Micro v = ip * micro_one + fp;
  return neg ? -v : v;
}

std::string format_fixed(Micro v, int int_digits, int frac_digits, bool sign) {
  const bool neg = v < 0;
  const auto mag = static_cast<std::uint64_t>(neg ? -v : v);
  std::uint64_t div = 1;
  for (int i = frac_digits; i < 6; ++i) div *= 10;
  const std::uint64_t scaled = mag / div;
  std::uint64_t fdiv = 1;
  for (int i = 0; i < frac_digits; ++i) fdiv *= 10;
  std::string s = sign ? (neg ? "-" : "+") : "";
  s += fmt::format("{:0{}}", scaled / fdiv, int_digits);
  if (frac_digits > 0) s += fmt::format(".{:0{}}", scaled % fdiv, frac_digits);
  return s;
}

std::string format_variable(Micro v) {
  return format_fixed(v, 8, 6);
}

Micro to_micro(double v) noexcept {
  return static_cast<Micro>(std::llround(v * 1e6));
}

}  // namespace hil::controllers::clm14
