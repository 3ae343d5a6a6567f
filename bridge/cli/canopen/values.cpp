// SPDX-License-Identifier: MIT
#include "values.hpp"

#include <bit>
#include <charconv>
#include <cstring>
#include <limits>
#include <optional>

#include <fmt/format.h>

namespace hil::cli::canopen_cli {
namespace {

struct TypeInfo {
  std::string_view name;
  std::size_t size;  // 0 = variable
  char kind;         // 'i' signed, 'u' unsigned, 'x' hex unsigned, 'r' real, 's' string, 'o' octets, 'b' bool
};
constexpr TypeInfo k_types[] = {
    {"b", 1, 'b'},   {"i8", 1, 'i'},  {"i16", 2, 'i'}, {"i32", 4, 'i'}, {"i64", 8, 'i'}, {"u8", 1, 'u'},
    {"u16", 2, 'u'}, {"u32", 4, 'u'}, {"u64", 8, 'u'}, {"x8", 1, 'x'},  {"x16", 2, 'x'}, {"x32", 4, 'x'},
    {"x64", 8, 'x'}, {"r32", 4, 'r'}, {"r64", 8, 'r'}, {"vs", 0, 's'},  {"os", 0, 'o'},  {"d", 0, 'o'},
};

/// `hex` (the name `modbus` and the profiles use): unsigned, shown in hex, its width the object's.
/// Read: the x type of the uploaded size (1, 2, 4 or 8 bytes; other sizes as hex bytes). Written:
/// the x type of the digits given (0x and 2, 4, 8 or 16 hex digits).
constexpr std::string_view k_hex = "hex";

std::string_view hex_type_of_size(std::size_t bytes) {
  switch (bytes) {
    case 1:
      return "x8";
    case 2:
      return "x16";
    case 4:
      return "x32";
    case 8:
      return "x64";
    default:
      return "os";
  }
}

const TypeInfo* find(std::string_view t) {
  for (const auto& i : k_types)
    if (i.name == t) return &i;
  return nullptr;
}

std::optional<long long> parse_int(std::string_view s) {
  bool neg = false;
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
    neg = s[0] == '-';
    s.remove_prefix(1);
  }
  int base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    base = 16;
    s.remove_prefix(2);
  }
  unsigned long long v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v, base);
  if (s.empty() || ec != std::errc{} || p != s.data() + s.size()) return std::nullopt;
  return neg ? -static_cast<long long>(v) : static_cast<long long>(v);
}

}  // namespace

bool is_value_type(std::string_view type) noexcept {
  return type == k_hex || find(type) != nullptr;
}

std::string value_types_help() {
  return "b (boolean), i8 i16 i32 i64, u8 u16 u32 u64, x8 x16 x32 x64 (hex), hex (hex, the object's width: "
         "written as 0x with 2, 4, 8 or 16 digits), r32 r64, vs (visible string), os / d (octet string / domain as "
         "hex)";
}

std::expected<std::vector<std::uint8_t>, std::string> encode_value(std::string_view type, std::string_view text) {
  if (type == k_hex) {
    const bool prefixed = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
    const std::size_t digits = prefixed ? text.size() - 2 : 0;
    if (digits != 2 && digits != 4 && digits != 8 && digits != 16)
      return std::unexpected(
          fmt::format("'{}': type hex takes its width from the digits: write 0x and 2, 4, 8 or 16 "
                      "hex digits (e.g. 0x00FF for 16 bits), or give the width with x8..x64",
                      text));
    return encode_value(hex_type_of_size(digits / 2), text);
  }
  const auto* t = find(type);
  if (t == nullptr) return std::unexpected(fmt::format("unknown type '{}'; use one of: {}", type, value_types_help()));
  std::vector<std::uint8_t> out;
  switch (t->kind) {
    case 's':
      out.assign(text.begin(), text.end());
      return out;
    case 'o': {
      std::string hex;
      for (char c : text)
        if (c != ' ' && c != ':') hex.push_back(c);
      if (hex.size() % 2) return std::unexpected(fmt::format("'{}' is not an even number of hex digits", text));
      for (std::size_t i = 0; i < hex.size(); i += 2) {
        unsigned b = 0;
        auto [p, ec] = std::from_chars(hex.data() + i, hex.data() + i + 2, b, 16);
        if (ec != std::errc{} || p != hex.data() + i + 2) return std::unexpected(fmt::format("'{}' is not hex", text));
        out.push_back(static_cast<std::uint8_t>(b));
      }
      return out;
    }
    case 'r': {
      double d = 0;
      auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), d);
      if (ec != std::errc{} || p != text.data() + text.size())
        return std::unexpected(fmt::format("'{}' is not a number", text));
      out.resize(t->size);
      if (t->size == 4) {
        const auto bits = std::bit_cast<std::uint32_t>(static_cast<float>(d));
        std::memcpy(out.data(), &bits, 4);
      } else {
        std::memcpy(out.data(), &d, 8);
      }
      return out;
    }
    default:
      break;
  }
  auto v = parse_int(text);
  if (!v) return std::unexpected(fmt::format("'{}' is not an integer (decimal or 0x hex)", text));
  const auto bits = 8 * t->size;
  if (t->kind == 'b' && *v != 0 && *v != 1) return std::unexpected("a boolean is 0 or 1");
  if (bits < 64) {
    const long long lo = t->kind == 'i' ? -(1LL << (bits - 1)) : 0;
    const long long hi = t->kind == 'i' ? (1LL << (bits - 1)) - 1 : static_cast<long long>((1ULL << bits) - 1);
    if (*v < lo || *v > hi) return std::unexpected(fmt::format("{} is outside {}..{} for type {}", text, lo, hi, type));
  }
  out.resize(t->size);
  const auto u = static_cast<unsigned long long>(*v);
  for (std::size_t i = 0; i < t->size; ++i) out[i] = static_cast<std::uint8_t>(u >> (8 * i));
  return out;
}

std::string format_value(std::string_view type, const std::vector<std::uint8_t>& bytes) {
  if (type == k_hex) return format_value(hex_type_of_size(bytes.size()), bytes);
  std::string hex;
  for (auto b : bytes) hex += fmt::format("{}{:02X}", hex.empty() ? "" : " ", b);
  const auto* t = find(type);
  unsigned long long u = 0;
  for (std::size_t i = 0; i < bytes.size() && i < 8; ++i) u |= static_cast<unsigned long long>(bytes[i]) << (8 * i);
  if (t == nullptr) {
    if (bytes.empty()) return "(empty)";
    if (bytes.size() <= 8) return fmt::format("{} (= {} = 0x{:X})", hex, u, u);
    return hex;
  }
  switch (t->kind) {
    case 's':
      return std::string(bytes.begin(), bytes.end());
    case 'o':
      return hex;
    case 'r':
      if (bytes.size() == 4) return fmt::format("{}", std::bit_cast<float>(static_cast<std::uint32_t>(u)));
      if (bytes.size() == 8) return fmt::format("{}", std::bit_cast<double>(static_cast<std::uint64_t>(u)));
      return hex;
    case 'x':
      return fmt::format("0x{:0{}X}", u, t->size * 2);
    case 'i': {
      const auto n = std::min(bytes.size(), t->size);
      long long s = static_cast<long long>(u);
      if (n > 0 && n < 8 && (bytes[n - 1] & 0x80)) s |= static_cast<long long>(~0ULL << (8 * n));
      return fmt::format("{}", s);
    }
    default:
      return fmt::format("{}", u);
  }
}

std::expected<std::pair<std::uint16_t, std::uint8_t>, std::string> parse_object(std::string_view text) {
  const auto colon = text.find(':');
  auto idx_text = text.substr(0, colon);
  if (idx_text.size() > 2 && idx_text[0] == '0' && (idx_text[1] == 'x' || idx_text[1] == 'X'))
    idx_text.remove_prefix(2);
  unsigned idx = 0, sub = 0;
  auto [p, ec] = std::from_chars(idx_text.data(), idx_text.data() + idx_text.size(), idx, 16);
  if (idx_text.empty() || ec != std::errc{} || p != idx_text.data() + idx_text.size() || idx > 0xFFFF)
    return std::unexpected(
        fmt::format("'{}' is not an object: expected INDEX:SUB in hex, e.g. 0x6041:0 or 1018:1", text));
  if (colon != std::string_view::npos) {
    auto sub_text = text.substr(colon + 1);
    int base = 16;
    if (sub_text.size() > 2 && sub_text[0] == '0' && (sub_text[1] == 'x' || sub_text[1] == 'X'))
      sub_text.remove_prefix(2);
    auto [q, ec2] = std::from_chars(sub_text.data(), sub_text.data() + sub_text.size(), sub, base);
    if (sub_text.empty() || ec2 != std::errc{} || q != sub_text.data() + sub_text.size() || sub > 0xFF)
      return std::unexpected(fmt::format("'{}': sub-index must be 0..FF (hex)", text));
  }
  return std::pair{static_cast<std::uint16_t>(idx), static_cast<std::uint8_t>(sub)};
}

}  // namespace hil::cli::canopen_cli
