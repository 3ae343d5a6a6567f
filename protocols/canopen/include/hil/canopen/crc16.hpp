// SPDX-License-Identifier: MIT
#pragma once
// CRC-16-CCITT as CiA 301 §7.2.4.3.16 uses it for SDO block transfer: polynomial
// x^16+x^12+x^5+1 (0x1021), initial value 0, no reflection, no final XOR ("XMODEM").
// Check value: "123456789" -> 0x31C3.

#include <cstdint>
#include <span>

namespace hil::canopen {

/// Continue a CRC over `bytes` (start with crc = 0). Pure, table-driven.
[[nodiscard]] std::uint16_t crc16_ccitt(std::span<const std::uint8_t> bytes, std::uint16_t crc = 0) noexcept;

}  // namespace hil::canopen
