// SPDX-License-Identifier: MIT
#include "hil/serial/tape/tape_code.hpp"

#include <array>
#include <utility>

namespace hil::serial::tape {

namespace {
// RS-244-B hole patterns, bit 0 = track 1 ... bit 7 = track 8.
constexpr std::array<std::pair<char, std::uint8_t>, 50> eia_table{{
    {'0', 0x20},    {'1', 0x01},  {'2', 0x02},  {'3', 0x13},  {'4', 0x04},    {'5', 0x15}, {'6', 0x16}, {'7', 0x07},
    {'8', 0x08},    {'9', 0x19},  {'A', 0x61},  {'B', 0x62},  {'C', 0x73},    {'D', 0x64}, {'E', 0x75}, {'F', 0x76},
    {'G', 0x67},    {'H', 0x68},  {'I', 0x79},  {'J', 0x51},  {'K', 0x52},    {'L', 0x43}, {'M', 0x54}, {'N', 0x45},
    {'O', 0x46},    {'P', 0x57},  {'Q', 0x58},  {'R', 0x49},  {'S', 0x32},    {'T', 0x23}, {'U', 0x34}, {'V', 0x25},
    {'W', 0x26},    {'X', 0x37},  {'Y', 0x38},  {'Z', 0x29},  {' ', 0x10},    {'+', 0x70}, {'-', 0x40}, {'.', 0x6B},
    {'/', 0x31},    {',', 0x3B},  {'\t', 0x3E}, {'\b', 0x2A}, {'\x7F', 0x7F}, {'(', 0x1A}, {')', 0x4A}, {'\n', eia_eob},
    {'%', eia_eor}, {'\0', 0x00},
}};
}  // namespace

std::optional<std::uint8_t> make_eia(char c) noexcept {
  if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  for (const auto& [ch, b] : eia_table)
    if (ch == c) return b;
  return std::nullopt;
}

EiaDecode parse_eia(std::uint8_t b) noexcept {
  EiaDecode d;
  d.parity_ok = b == eia_eob || b == 0x00 || (__builtin_popcount(b) & 1) == 1;
  if (!d.parity_ok) return d;
  for (const auto& [ch, code] : eia_table)
    if (code == b) {
      d.c = ch;
      break;
    }
  return d;
}

}  // namespace hil::serial::tape
