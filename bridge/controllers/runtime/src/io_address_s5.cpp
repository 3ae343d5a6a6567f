// SPDX-License-Identifier: MIT
#include "hil/controllers/io_address_s5.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

namespace hil::controllers {
namespace {

struct Cursor {
  std::string_view s;
  std::size_t i = 0;
  void skip_spaces() noexcept {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  }
  [[nodiscard]] bool done() const noexcept { return i >= s.size(); }
  [[nodiscard]] char peek(std::size_t k = 0) const noexcept {
    return i + k < s.size() ? static_cast<char>(std::toupper(static_cast<unsigned char>(s[i + k]))) : '\0';
  }
  /// Decimal number of at most 5 digits; empty when none.
  std::optional<unsigned> number() noexcept {
    unsigned v = 0;
    std::size_t n = 0;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9' && n < 6) {
      v = v * 10 + static_cast<unsigned>(s[i] - '0');
      ++i;
      ++n;
    }
    if (n == 0 || n > 5) return std::nullopt;
    return v;
  }
};

bool data_operand(S5Operand o) noexcept {
  return o == S5Operand::data_bit || o == S5Operand::data_left_byte || o == S5Operand::data_right_byte;
}

std::string_view mnemonic(S5Operand o) noexcept {
  switch (o) {
    case S5Operand::input_bit:
      return "E";
    case S5Operand::output_bit:
      return "A";
    case S5Operand::marker_bit:
      return "M";
    case S5Operand::input_byte:
      return "EB";
    case S5Operand::output_byte:
      return "AB";
    case S5Operand::marker_byte:
      return "MB";
    case S5Operand::data_bit:
      return "D";
    case S5Operand::data_left_byte:
      return "DL";
    case S5Operand::data_right_byte:
      return "DR";
  }
  return "?";
}

}  // namespace

std::expected<S5Address, std::string> parse_s5_address(std::string_view text, std::optional<std::uint16_t> default_db) {
  const auto fail = [&](std::string_view why) {
    return std::unexpected(
        fmt::format("'{}': {} (S5 operand: E/A/M n.b, EB/AB/MB n, [DBk] D w.b, [DBk] DL/DR w)", text, why));
  };
  Cursor c{text};
  c.skip_spaces();
  S5Address a;
  bool have_db = false;
  if (c.peek() == 'D' && c.peek(1) == 'B') {
    c.i += 2;
    c.skip_spaces();
    const auto db = c.number();
    if (!db || *db == 0 || *db > 255) return fail("DB number must be 1..255");
    a.db = static_cast<std::uint16_t>(*db);
    have_db = true;
    c.skip_spaces();
    if (c.peek() == '.' || c.peek() == ':' || c.peek() == ',') {
      ++c.i;
      c.skip_spaces();
    }
  }
  const char m0 = c.peek();
  const char m1 = c.peek(1);
  if (m0 == 'E' || m0 == 'A' || m0 == 'M') {
    if (m1 == 'B') {
      a.operand = m0 == 'E' ? S5Operand::input_byte : m0 == 'A' ? S5Operand::output_byte : S5Operand::marker_byte;
      c.i += 2;
    } else {
      a.operand = m0 == 'E' ? S5Operand::input_bit : m0 == 'A' ? S5Operand::output_bit : S5Operand::marker_bit;
      c.i += 1;
    }
  } else if (m0 == 'D') {
    if (m1 == 'L' || m1 == 'R') {
      a.operand = m1 == 'L' ? S5Operand::data_left_byte : S5Operand::data_right_byte;
      c.i += 2;
    } else {
      a.operand = S5Operand::data_bit;
      c.i += 1;
    }
  } else {
    return fail("unknown operand");
  }
  if (have_db && !data_operand(a.operand)) return fail("a DB prefix only goes with D, DL or DR");
  if (data_operand(a.operand) && !have_db) {
    if (!default_db) return fail("data operand without DB number (write e.g. DB10 D 2.0)");
    a.db = *default_db;
  }
  c.skip_spaces();
  const auto index = c.number();
  if (!index) return fail("number expected after the operand");
  if (*index > 255) return fail(data_operand(a.operand) ? "data word must be 0..255" : "byte must be 0..255");
  a.index = static_cast<std::uint16_t>(*index);
  if (a.is_bit()) {
    if (c.peek() != '.') return fail("'.bit' expected");
    ++c.i;
    const auto bit = c.number();
    const unsigned max_bit = a.operand == S5Operand::data_bit ? 15 : 7;
    if (!bit || *bit > max_bit) return fail(fmt::format("bit must be 0..{}", max_bit));
    a.bit = static_cast<std::uint8_t>(*bit);
  }
  c.skip_spaces();
  if (!c.done()) return fail("unexpected text after the address");
  return a;
}

std::string format_s5_address(const S5Address& a) {
  std::string prefix = a.db != 0 && data_operand(a.operand) ? fmt::format("DB{} ", a.db) : std::string();
  if (a.is_bit()) return fmt::format("{}{} {}.{}", prefix, mnemonic(a.operand), a.index, a.bit);
  return fmt::format("{}{} {}", prefix, mnemonic(a.operand), a.index);
}

namespace {

std::expected<const S5DataBlock*, std::string> find_block(const S5Address& a, std::span<const S5DataBlock> blocks) {
  const auto it = std::ranges::find_if(blocks, [&](const S5DataBlock& b) { return b.number == a.db; });
  if (it == blocks.end()) {
    return std::unexpected(fmt::format("{}: DB{} is not part of this controller's image", format_s5_address(a), a.db));
  }
  if (a.index >= it->words) {
    return std::unexpected(
        fmt::format("{}: DB{} has data words 0..{} only", format_s5_address(a), a.db, it->words - 1));
  }
  return &*it;
}

}  // namespace

std::expected<BitAddress, std::string> to_bit_address(const S5Address& a, std::span<const S5DataBlock> blocks) {
  switch (a.operand) {
    case S5Operand::input_bit:
      return BitAddress{IoArea::input, a.index, a.bit};
    case S5Operand::output_bit:
      return BitAddress{IoArea::output, a.index, a.bit};
    case S5Operand::marker_bit:
      return BitAddress{IoArea::marker, a.index, a.bit};
    case S5Operand::data_bit: {
      const auto b = find_block(a, blocks);
      if (!b) return std::unexpected(b.error());
      // Bits 15..8 are the left byte (DL, lower address), 7..0 the right byte (DR).
      const std::uint32_t byte = (*b)->base + 2U * a.index + (a.bit >= 8 ? 0U : 1U);
      return BitAddress{IoArea::data, byte, static_cast<std::uint8_t>(a.bit % 8)};
    }
    default:
      return std::unexpected(fmt::format("{} is a byte, not a bit", format_s5_address(a)));
  }
}

std::expected<ByteAddress, std::string> to_byte_address(const S5Address& a, std::span<const S5DataBlock> blocks) {
  switch (a.operand) {
    case S5Operand::input_byte:
      return ByteAddress{IoArea::input, a.index};
    case S5Operand::output_byte:
      return ByteAddress{IoArea::output, a.index};
    case S5Operand::marker_byte:
      return ByteAddress{IoArea::marker, a.index};
    case S5Operand::data_left_byte:
    case S5Operand::data_right_byte: {
      const auto b = find_block(a, blocks);
      if (!b) return std::unexpected(b.error());
      const std::uint32_t right = a.operand == S5Operand::data_right_byte ? 1U : 0U;
      return ByteAddress{IoArea::data, (*b)->base + 2U * a.index + right};
    }
    default:
      return std::unexpected(fmt::format("{} is a bit, not a byte", format_s5_address(a)));
  }
}

}  // namespace hil::controllers
