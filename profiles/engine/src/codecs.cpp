// SPDX-License-Identifier: MIT
// The pure value codecs: decimal text fields, packed BCD, two's complement, bit fields, fixed point.
#include <fmt/format.h>

#include <charconv>
#include <cstdlib>

#include "hil/profiles/bcd.hpp"
#include "hil/profiles/bit_field.hpp"
#include "hil/profiles/decimal_text.hpp"
#include "hil/profiles/fixed_point.hpp"
#include "hil/profiles/twos_complement.hpp"
#include "int128.hpp"

namespace hil::profiles {
namespace {

CodecError err(CodecError::Kind k, std::string m) {
  return CodecError{k, std::move(m)};
}

std::int64_t pow10_i64(int n) {
  std::int64_t r = 1;
  for (int i = 0; i < n; ++i) r *= 10;
  return r;
}

}  // namespace

// ---- decimal text ---------------------------------------------------------------------------

std::expected<DecimalTextFormat, std::string> DecimalTextFormat::parse(std::string_view spec) {
  DecimalTextFormat f;
  std::string_view s = spec;
  if (s.starts_with("+") || s.starts_with("-")) {
    f.sign = Sign::always;
    s.remove_prefix(1);
  } else if (s.starts_with("\xC2\xB1")) {  // '±' in UTF-8
    f.sign = Sign::always;
    s.remove_prefix(2);
  }
  const auto dot = s.find('.');
  const std::string_view ip = s.substr(0, dot);
  const std::string_view fp = dot == std::string_view::npos ? std::string_view{} : s.substr(dot + 1);
  auto num = [](std::string_view t, int& out) {
    if (t.empty()) return false;
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
    return ec == std::errc{} && p == t.data() + t.size();
  };
  if (!num(ip, f.int_digits) || f.int_digits < 0 || f.int_digits > 17)
    return std::unexpected(fmt::format("bad decimal field format '{}': expected e.g. '+6.3', '4.5' or '5'", spec));
  if (dot != std::string_view::npos && (!num(fp, f.frac_digits) || f.frac_digits < 0 || f.frac_digits > 17))
    return std::unexpected(fmt::format("bad decimal field format '{}': expected e.g. '+6.3', '4.5' or '5'", spec));
  if (f.int_digits + f.frac_digits > 18 || f.int_digits + f.frac_digits == 0)
    return std::unexpected(fmt::format("decimal field format '{}' must have 1..18 digits", spec));
  return f;
}

std::string DecimalTextFormat::to_string() const {
  std::string s = sign == Sign::always ? "+" : "";
  s += std::to_string(int_digits);
  if (frac_digits > 0) s += "." + std::to_string(frac_digits);
  return s;
}

std::size_t DecimalTextFormat::width() const noexcept {
  return static_cast<std::size_t>(int_digits + frac_digits + (frac_digits > 0 ? 1 : 0) +
                                  (sign == Sign::always ? 1 : 0));
}

Decimal DecimalTextFormat::max_magnitude() const noexcept {
  return Decimal{pow10_i64(int_digits + frac_digits) - 1, frac_digits};
}

std::expected<std::string, CodecError> make_decimal_text(const Decimal& v, const DecimalTextFormat& f) {
  auto r = v.rescaled(f.frac_digits);
  if (!r)
    return std::unexpected(err(CodecError::Kind::precision, fmt::format("{} has more than {} decimals for field {}",
                                                                        v.to_string(), f.frac_digits, f.to_string())));
  // A signed field keeps the sign of a zero as written ("-00000.000"); an unsigned one has none.
  const bool neg = r->units < 0 || (r->minus_zero && f.sign == DecimalTextFormat::Sign::always);
  if (r->units < 0 && f.sign == DecimalTextFormat::Sign::none)
    return std::unexpected(err(CodecError::Kind::out_of_range,
                               fmt::format("{} is negative; field {} is unsigned", v.to_string(), f.to_string())));
  const std::uint64_t mag =
      r->units < 0 ? static_cast<std::uint64_t>(-(r->units + 1)) + 1u : static_cast<std::uint64_t>(r->units);
  if (mag > static_cast<std::uint64_t>(f.max_magnitude().units))
    return std::unexpected(
        err(CodecError::Kind::out_of_range, fmt::format("{} does not fit field {} (at most {})", v.to_string(),
                                                        f.to_string(), f.max_magnitude().to_string())));
  std::string digits = fmt::format("{:0{}}", mag, f.int_digits + f.frac_digits);
  if (f.frac_digits > 0) digits.insert(digits.size() - static_cast<std::size_t>(f.frac_digits), 1, '.');
  if (f.int_digits == 0 && f.frac_digits > 0 && digits.front() != '.') digits.insert(0, 1, '.');
  if (f.sign == DecimalTextFormat::Sign::always) digits.insert(0, 1, neg ? '-' : '+');
  return digits;
}

std::expected<Decimal, CodecError> parse_decimal_text(std::string_view text, const DecimalTextFormat& f) {
  std::string_view t = text;
  if (t.empty())
    return std::unexpected(err(CodecError::Kind::syntax, fmt::format("empty field; expected {}", f.to_string())));
  bool neg = false;
  if (t.front() == '+' || t.front() == '-') {
    if (f.sign == DecimalTextFormat::Sign::none && t.front() == '-')
      return std::unexpected(
          err(CodecError::Kind::out_of_range, fmt::format("'{}': field {} is unsigned", text, f.to_string())));
    neg = t.front() == '-';
    t.remove_prefix(1);
  }
  int int_digits = 0, frac_digits = 0;
  bool point = false;
  std::int64_t u = 0;
  for (char c : t) {
    if (c == '.' || c == ',') {
      if (point)
        return std::unexpected(err(CodecError::Kind::syntax, fmt::format("'{}' has two decimal points", text)));
      point = true;
      continue;
    }
    if (c < '0' || c > '9')
      return std::unexpected(
          err(CodecError::Kind::syntax,
              fmt::format("'{}' is not a decimal field {} (character '{}')", text, f.to_string(), c)));
    (point ? frac_digits : int_digits)++;
    if (int_digits + frac_digits > 18)
      return std::unexpected(err(CodecError::Kind::out_of_range, fmt::format("'{}' has too many digits", text)));
    u = u * 10 + (c - '0');
  }
  if (int_digits + frac_digits == 0)
    return std::unexpected(err(CodecError::Kind::syntax, fmt::format("'{}' has no digits", text)));
  if (point && frac_digits == 0 && f.frac_digits == 0)
    return std::unexpected(
        err(CodecError::Kind::syntax, fmt::format("'{}': field {} is an integer", text, f.to_string())));
  if (frac_digits > f.frac_digits)
    return std::unexpected(err(CodecError::Kind::precision, fmt::format("'{}' has {} decimals; field {} has {}", text,
                                                                        frac_digits, f.to_string(), f.frac_digits)));
  // Leading zeros beyond the width are harmless; significant digits are not.
  Decimal d{neg ? -u : u, frac_digits, neg && u == 0};
  auto r = d.rescaled(f.frac_digits);
  if (!r) return std::unexpected(err(CodecError::Kind::out_of_range, r.error()));
  const std::int64_t mag = r->units < 0 ? -r->units : r->units;
  if (mag > f.max_magnitude().units)
    return std::unexpected(
        err(CodecError::Kind::out_of_range, fmt::format("'{}' does not fit field {}", text, f.to_string())));
  return *r;
}

// ---- BCD ------------------------------------------------------------------------------------

std::int64_t bcd_max_magnitude(const BcdFormat& f) noexcept {
  switch (f.sign) {
    case BcdSign::none:
      return pow10_i64(f.digits) - 1;
    case BcdSign::bit31:
      return 8 * pow10_i64(f.digits - 1) - 1;  // top digit 0..7
    case BcdSign::nibble:
      return pow10_i64(f.digits - 1) - 1;
  }
  return 0;
}

std::expected<std::uint32_t, CodecError> make_bcd(std::int64_t v, const BcdFormat& f) {
  if (f.digits < 1 || f.digits > 8)
    return std::unexpected(err(CodecError::Kind::syntax, "BCD format needs 1..8 digits"));
  if (f.sign == BcdSign::bit31 && f.digits != 8)
    return std::unexpected(err(CodecError::Kind::syntax, "the bit-31 sign needs 8 BCD digits"));
  if (v < 0 && f.sign == BcdSign::none)
    return std::unexpected(
        err(CodecError::Kind::out_of_range, fmt::format("{} is negative; the BCD format is unsigned", v)));
  const std::int64_t mag = v < 0 ? -v : v;
  if (mag > bcd_max_magnitude(f))
    return std::unexpected(
        err(CodecError::Kind::out_of_range, fmt::format("{} exceeds the BCD limit ±{}", v, bcd_max_magnitude(f))));
  std::uint32_t w = 0;
  std::int64_t m = mag;
  for (int i = 0; i < f.digits; ++i) {
    w |= static_cast<std::uint32_t>(m % 10) << (4 * i);
    m /= 10;
  }
  if (v < 0) {
    if (f.sign == BcdSign::bit31)
      w |= 0x80000000u;
    else
      w |= 0xFu << (4 * (f.digits - 1));
  }
  return w;
}

std::expected<std::int64_t, CodecError> parse_bcd(std::uint32_t word, const BcdFormat& f) {
  if (f.digits < 1 || f.digits > 8)
    return std::unexpected(err(CodecError::Kind::syntax, "BCD format needs 1..8 digits"));
  if (f.sign == BcdSign::bit31 && f.digits != 8)
    return std::unexpected(err(CodecError::Kind::syntax, "the bit-31 sign needs 8 BCD digits"));
  if (f.digits < 8 && (word >> (4 * f.digits)) != 0)
    return std::unexpected(
        err(CodecError::Kind::syntax, fmt::format("BCD word {:08X} has bits above its {} digits", word, f.digits)));
  bool neg = false;
  std::uint32_t w = word;
  const int top_shift = 4 * (f.digits - 1);
  if (f.sign == BcdSign::bit31) {
    neg = (w & 0x80000000u) != 0;
    w &= 0x7FFFFFFFu;
  } else if (f.sign == BcdSign::nibble) {
    const std::uint32_t top = (w >> top_shift) & 0xFu;
    if (top != 0 && top != 0xF)
      return std::unexpected(
          err(CodecError::Kind::invalid_digit,
              fmt::format("BCD word {:08X}: sign nibble {:X} is neither 0 (+) nor F (-)", word, top)));
    neg = top == 0xF;
    w &= ~(0xFu << top_shift);
  }
  std::int64_t v = 0;
  for (int i = f.digits - 1; i >= 0; --i) {
    const std::uint32_t d = (w >> (4 * i)) & 0xFu;
    if (d > 9)
      return std::unexpected(
          err(CodecError::Kind::invalid_digit,
              fmt::format("BCD word {:08X}: nibble {} (10^{}) is {:X}, not a decimal digit", word, i, i, d)));
    v = v * 10 + d;
  }
  return neg ? -v : v;
}

// ---- two's complement -----------------------------------------------------------------------

std::expected<std::uint64_t, CodecError> make_twos_complement(std::int64_t v, const TwosComplementFormat& f) {
  if (f.bits < 1 || f.bits > 64) return std::unexpected(err(CodecError::Kind::syntax, "word width must be 1..64 bits"));
  if (f.bits == 64) {
    if (!f.is_signed && v < 0)
      return std::unexpected(err(CodecError::Kind::out_of_range, fmt::format("{} is negative in an unsigned word", v)));
    return static_cast<std::uint64_t>(v);
  }
  const std::int64_t lo = f.is_signed ? -(std::int64_t{1} << (f.bits - 1)) : 0;
  const std::int64_t hi = f.is_signed ? (std::int64_t{1} << (f.bits - 1)) - 1 : (std::int64_t{1} << f.bits) - 1;
  if (v < lo || v > hi)
    return std::unexpected(
        err(CodecError::Kind::out_of_range, fmt::format("{} does not fit a {}-bit {} word ({}..{})", v, f.bits,
                                                        f.is_signed ? "signed" : "unsigned", lo, hi)));
  return static_cast<std::uint64_t>(v) & ((std::uint64_t{1} << f.bits) - 1);
}

std::expected<std::int64_t, CodecError> parse_twos_complement(std::uint64_t word, const TwosComplementFormat& f) {
  if (f.bits < 1 || f.bits > 64) return std::unexpected(err(CodecError::Kind::syntax, "word width must be 1..64 bits"));
  if (f.bits == 64) return static_cast<std::int64_t>(word);
  if ((word >> f.bits) != 0)
    return std::unexpected(err(CodecError::Kind::syntax, fmt::format("word {:X} is wider than {} bits", word, f.bits)));
  if (f.is_signed && (word >> (f.bits - 1)) & 1u) return static_cast<std::int64_t>(word) - (std::int64_t{1} << f.bits);
  return static_cast<std::int64_t>(word);
}

// ---- bit fields -----------------------------------------------------------------------------

std::expected<std::uint64_t, CodecError> make_bit_field(const std::vector<BitValue>& values, const BitFieldFormat& f) {
  std::uint64_t w = 0;
  for (const auto& v : values) {
    const BitDef* d = nullptr;
    for (const auto& b : f.fields)
      if (b.name == v.name) d = &b;
    if (!d) return std::unexpected(err(CodecError::Kind::syntax, fmt::format("unknown bit field '{}'", v.name)));
    const std::uint64_t mask = d->width >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << d->width) - 1;
    if (v.value > mask)
      return std::unexpected(
          err(CodecError::Kind::out_of_range, fmt::format("{}={} does not fit {} bit(s)", v.name, v.value, d->width)));
    w |= v.value << d->first;
  }
  return w;
}

std::expected<std::vector<BitValue>, CodecError> parse_bit_field(std::uint64_t word, const BitFieldFormat& f) {
  if (f.bits < 64 && (word >> f.bits) != 0)
    return std::unexpected(
        err(CodecError::Kind::out_of_range, fmt::format("{:#x} is wider than {} bits", word, f.bits)));
  std::vector<BitValue> out;
  std::uint64_t covered = 0;
  for (const auto& b : f.fields) {
    const std::uint64_t mask = b.width >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << b.width) - 1;
    out.push_back({b.name, (word >> b.first) & mask});
    covered |= mask << b.first;
  }
  if (!f.allow_unnamed && (word & ~covered) != 0)
    return std::unexpected(
        err(CodecError::Kind::out_of_range, fmt::format("{:#x} sets undefined bits {:#x}", word, word & ~covered)));
  return out;
}

std::expected<std::vector<BitValue>, CodecError> parse_bit_field_text(std::string_view text, const BitFieldFormat& f) {
  std::vector<BitValue> out;
  std::string_view t = text;
  if (t == "0" || t.empty()) return out;
  while (!t.empty()) {
    const auto sep = t.find_first_of("|,+");
    std::string_view item = t.substr(0, sep);
    t = sep == std::string_view::npos ? std::string_view{} : t.substr(sep + 1);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    if (item.empty()) continue;
    std::uint64_t value = 1;
    const auto eq = item.find('=');
    std::string_view name = item.substr(0, eq);
    if (eq != std::string_view::npos) {
      auto v = parse_decimal(item.substr(eq + 1));
      if (!v || v->scale != 0 || v->units < 0)
        return std::unexpected(
            err(CodecError::Kind::syntax, fmt::format("'{}': expected name=unsigned integer", item)));
      value = static_cast<std::uint64_t>(v->units);
    }
    out.push_back({std::string(name), value});
  }
  if (auto w = make_bit_field(out, f); !w) return std::unexpected(w.error());
  return out;
}

std::string bit_field_text(const std::vector<BitValue>& values, const BitFieldFormat& f) {
  std::string s;
  for (const auto& v : values) {
    if (v.value == 0) continue;
    unsigned width = 1;
    for (const auto& b : f.fields)
      if (b.name == v.name) width = b.width;
    if (!s.empty()) s += '|';
    s += width == 1 ? v.name : fmt::format("{}={}", v.name, v.value);
  }
  return s.empty() ? "0" : s;
}

// ---- fixed point ----------------------------------------------------------------------------

std::expected<FixedPointFormat, std::string> FixedPointFormat::parse_lsb(std::string_view lsb,
                                                                         TwosComplementFormat word) {
  FixedPointFormat f;
  f.word = word;
  const auto slash = lsb.find('/');
  if (slash != std::string_view::npos) {
    auto n = parse_decimal(lsb.substr(0, slash));
    auto d = parse_decimal(lsb.substr(slash + 1));
    if (!n || !d || n->scale != 0 || d->scale != 0 || n->units <= 0 || d->units <= 0)
      return std::unexpected(fmt::format("bad fixed-point lsb '{}': expected 'num/den' with positive integers", lsb));
    f.lsb_num = n->units;
    f.lsb_den = d->units;
    return f;
  }
  auto v = parse_decimal(lsb);
  if (!v || v->units <= 0)
    return std::unexpected(fmt::format("bad fixed-point lsb '{}': expected a positive number", lsb));
  f.lsb_num = v->units;
  f.lsb_den = pow10_i64(v->scale);
  return f;
}

std::expected<std::int64_t, CodecError> make_fixed_point(const Decimal& v, const FixedPointFormat& f) {
  // raw = v / (num/den) = v.units × den / (10^scale × num), rounded half away from zero.
  const detail::i128 n = static_cast<detail::i128>(v.units) * f.lsb_den;
  detail::i128 d = static_cast<detail::i128>(f.lsb_num);
  for (int i = 0; i < v.scale; ++i) d *= 10;
  detail::i128 q = n / d;
  const detail::i128 r = n % d;
  if (2 * (r < 0 ? -r : r) >= d) q += n < 0 ? -1 : 1;
  if (q > INT64_MAX || q < INT64_MIN)
    return std::unexpected(
        err(CodecError::Kind::out_of_range, fmt::format("{} is too large for the fixed-point format", v.to_string())));
  const auto raw = static_cast<std::int64_t>(q);
  if (auto w = make_twos_complement(raw, f.word); !w)
    return std::unexpected(err(CodecError::Kind::out_of_range, fmt::format("{} (raw {}) does not fit the {}-bit word",
                                                                           v.to_string(), raw, f.word.bits)));
  return raw;
}

std::expected<Decimal, CodecError> parse_fixed_point(std::int64_t raw, const FixedPointFormat& f) {
  if (auto w = make_twos_complement(raw, f.word); !w) return std::unexpected(w.error());
  const detail::i128 n = static_cast<detail::i128>(raw) * f.lsb_num;
  for (int s = 0; s <= 12; ++s) {
    detail::i128 scaled = n;
    for (int i = 0; i < s; ++i) scaled *= 10;
    if (scaled % f.lsb_den == 0) {
      const detail::i128 u = scaled / f.lsb_den;
      if (u > INT64_MAX || u < INT64_MIN) break;
      return Decimal{static_cast<std::int64_t>(u), s};
    }
  }
  detail::i128 scaled = n * static_cast<detail::i128>(pow10_i64(12));
  detail::i128 q = scaled / f.lsb_den;
  if (2 * ((scaled % f.lsb_den) < 0 ? -(scaled % f.lsb_den) : (scaled % f.lsb_den)) >= f.lsb_den)
    q += scaled < 0 ? -1 : 1;
  if (q > INT64_MAX || q < INT64_MIN)
    return std::unexpected(err(CodecError::Kind::out_of_range, "fixed-point value too large"));
  return Decimal{static_cast<std::int64_t>(q), 12};
}

}  // namespace hil::profiles
