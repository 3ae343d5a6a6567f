// SPDX-License-Identifier: MIT
#include "hil/canopen/crc16.hpp"

#include <array>

namespace hil::canopen {
namespace {

constexpr std::array<std::uint16_t, 256> make_table() {
  std::array<std::uint16_t, 256> t{};
  for (unsigned i = 0; i < 256; ++i) {
    auto c = static_cast<std::uint16_t>(i << 8);
    for (int b = 0; b < 8; ++b) c = static_cast<std::uint16_t>((c & 0x8000) ? ((c << 1) ^ 0x1021) : (c << 1));
    t[i] = c;
  }
  return t;
}
constexpr auto k_table = make_table();

}  // namespace

std::uint16_t crc16_ccitt(std::span<const std::uint8_t> bytes, std::uint16_t crc) noexcept {
  for (const auto b : bytes) crc = static_cast<std::uint16_t>((crc << 8) ^ k_table[((crc >> 8) ^ b) & 0xFF]);
  return crc;
}

}  // namespace hil::canopen
