// SPDX-License-Identifier: MIT
#pragma once
// Packing drive values into 16-bit registers and back: 16- or 32-bit, signed or unsigned, and
// for 32-bit values the word order (Modbus itself only fixes big-endian bytes inside a register;
// drives differ in which register holds the high word). Pure, constexpr, no allocation.

#include <cstdint>
#include <span>

namespace hil::modbus {

enum class WordOrder : std::uint8_t {
  high_first,  ///< "big-endian" / ABCD: register n holds bits 31..16 (CiA 402 images, most drives)
  low_first,   ///< "little-endian words" / CDAB: register n holds bits 15..0
};

struct ValueFormat {
  std::uint8_t words = 1;  ///< 1 (16-bit) or 2 (32-bit)
  bool is_signed = false;
  WordOrder order = WordOrder::high_first;
};

/// Clamp `v` to the representable range of `f` (saturation instead of wrap-around: a target of
/// 2^31 must not become -2^31 on the wire).
[[nodiscard]] constexpr std::int64_t saturate(std::int64_t v, const ValueFormat& f) noexcept {
  std::int64_t lo = 0, hi = 0;
  if (f.words == 2) {
    lo = f.is_signed ? INT32_MIN : 0;
    hi = f.is_signed ? INT32_MAX : static_cast<std::int64_t>(UINT32_MAX);
  } else {
    lo = f.is_signed ? INT16_MIN : 0;
    hi = f.is_signed ? INT16_MAX : UINT16_MAX;
  }
  return v < lo ? lo : (v > hi ? hi : v);
}

/// Write `v` (saturated) into `regs[0..f.words)`.
constexpr void pack_value(std::int64_t v, const ValueFormat& f, std::span<std::uint16_t> regs) noexcept {
  const auto u = static_cast<std::uint32_t>(static_cast<std::uint64_t>(saturate(v, f)) & 0xFFFFFFFFu);
  if (f.words == 2 && regs.size() >= 2) {
    const auto hi = static_cast<std::uint16_t>(u >> 16);
    const auto lo = static_cast<std::uint16_t>(u & 0xFFFF);
    regs[0] = f.order == WordOrder::high_first ? hi : lo;
    regs[1] = f.order == WordOrder::high_first ? lo : hi;
  } else if (!regs.empty()) {
    regs[0] = static_cast<std::uint16_t>(u & 0xFFFF);
  }
}

/// Read a value of format `f` from `regs[0..f.words)` (sign-extended when signed).
[[nodiscard]] constexpr std::int64_t unpack_value(std::span<const std::uint16_t> regs, const ValueFormat& f) noexcept {
  if (f.words == 2 && regs.size() >= 2) {
    const std::uint32_t hi = f.order == WordOrder::high_first ? regs[0] : regs[1];
    const std::uint32_t lo = f.order == WordOrder::high_first ? regs[1] : regs[0];
    const std::uint32_t u = (hi << 16) | lo;
    return f.is_signed ? static_cast<std::int64_t>(static_cast<std::int32_t>(u)) : static_cast<std::int64_t>(u);
  }
  if (regs.empty()) return 0;
  return f.is_signed ? static_cast<std::int64_t>(static_cast<std::int16_t>(regs[0]))
                     : static_cast<std::int64_t>(regs[0]);
}

}  // namespace hil::modbus
