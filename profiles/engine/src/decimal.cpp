// SPDX-License-Identifier: MIT
#include "hil/profiles/decimal.hpp"
#include "int128.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdlib>

namespace hil::profiles {
namespace {

constexpr int kMaxScale = 18;

detail::i128 pow10_i128(int n) {
  detail::i128 r = 1;
  for (int i = 0; i < n; ++i) r *= 10;
  return r;
}

}  // namespace

std::expected<Decimal, std::string> Decimal::rescaled(int new_scale) const {
  if (new_scale < 0 || new_scale > kMaxScale) return std::unexpected(fmt::format("scale {} out of 0..18", new_scale));
  if (new_scale == scale) return *this;
  if (units == 0) return Decimal{0, new_scale, minus_zero};
  detail::i128 u = units;
  if (new_scale > scale) {
    u *= pow10_i128(new_scale - scale);
  } else {
    const detail::i128 d = pow10_i128(scale - new_scale);
    if (u % d != 0) return std::unexpected(fmt::format("{} has more than {} decimals", to_string(), new_scale));
    u /= d;
  }
  if (u > INT64_MAX || u < INT64_MIN) return std::unexpected(fmt::format("{} is too large", to_string()));
  return Decimal{static_cast<std::int64_t>(u), new_scale};
}

std::expected<std::int64_t, std::string> Decimal::to_integer() const {
  auto r = rescaled(0);
  if (!r) return std::unexpected(fmt::format("{} is not an integer", to_string()));
  return r->units;
}

long double Decimal::to_long_double() const noexcept {
  long double v = static_cast<long double>(units);
  for (int i = 0; i < scale; ++i) v /= 10.0L;
  return v;
}

std::string Decimal::to_string() const {
  // Strip trailing zero decimals for the shortest exact text.
  std::int64_t u = units;
  int s = scale;
  while (s > 0 && u % 10 == 0) {
    u /= 10;
    --s;
  }
  const bool neg = u < 0;
  const detail::u128 mag =
      neg ? static_cast<detail::u128>(-static_cast<detail::i128>(u)) : static_cast<detail::u128>(u);
  std::string digits = fmt::format("{}", static_cast<unsigned long long>(mag));
  if (s > 0) {
    if (static_cast<int>(digits.size()) <= s) digits.insert(0, static_cast<std::size_t>(s + 1) - digits.size(), '0');
    digits.insert(digits.size() - static_cast<std::size_t>(s), 1, '.');
  }
  return neg || (units == 0 && minus_zero) ? "-" + digits : digits;
}

bool Decimal::is_multiple_of(const Decimal& step) const {
  const int s = std::max(scale, step.scale);
  const detail::i128 a = static_cast<detail::i128>(units) * pow10_i128(s - scale);
  const detail::i128 b = static_cast<detail::i128>(step.units) * pow10_i128(s - step.scale);
  if (b == 0) return true;
  return a % b == 0;
}

std::strong_ordering operator<=>(const Decimal& a, const Decimal& b) noexcept {
  const int s = std::max(a.scale, b.scale);
  const detail::i128 x = static_cast<detail::i128>(a.units) * pow10_i128(s - a.scale);
  const detail::i128 y = static_cast<detail::i128>(b.units) * pow10_i128(s - b.scale);
  return x <=> y;
}

std::expected<Decimal, std::string> parse_decimal(std::string_view text) {
  std::string_view t = text;
  while (!t.empty() && (t.front() == ' ' || t.front() == '\t')) t.remove_prefix(1);
  while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.remove_suffix(1);
  if (t.empty()) return std::unexpected(std::string("empty number"));
  bool neg = false;
  if (t.front() == '+' || t.front() == '-') {
    neg = t.front() == '-';
    t.remove_prefix(1);
  }
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) {
    std::uint64_t v = 0;
    auto [p, ec] = std::from_chars(t.data() + 2, t.data() + t.size(), v, 16);
    if (ec != std::errc{} || p != t.data() + t.size() || v > static_cast<std::uint64_t>(INT64_MAX))
      return std::unexpected(fmt::format("'{}' is not a hex number", text));
    const auto s = static_cast<std::int64_t>(v);
    return Decimal{neg ? -s : s, 0};
  }
  detail::i128 u = 0;
  int scale = 0;
  bool seen_point = false;
  int digits = 0;
  for (char c : t) {
    if (c == '.' || c == ',') {
      if (seen_point) return std::unexpected(fmt::format("'{}' has two decimal points", text));
      seen_point = true;
      continue;
    }
    if (c == '_' || c == '\'') continue;  // digit group separators: 1_000_000
    if (c < '0' || c > '9') return std::unexpected(fmt::format("'{}' is not a number", text));
    u = u * 10 + (c - '0');
    if (u > static_cast<detail::i128>(INT64_MAX)) return std::unexpected(fmt::format("'{}' is too large", text));
    ++digits;
    if (seen_point) ++scale;
    if (scale > kMaxScale) return std::unexpected(fmt::format("'{}' has too many decimals", text));
  }
  if (digits == 0) return std::unexpected(fmt::format("'{}' is not a number", text));
  const auto s = static_cast<std::int64_t>(u);
  return Decimal{neg ? -s : s, scale, neg && s == 0};
}

}  // namespace hil::profiles
