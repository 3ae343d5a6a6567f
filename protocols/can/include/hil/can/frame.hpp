// SPDX-License-Identifier: MIT
#pragma once
// A classic CAN frame (ISO 11898-1), as SocketCAN and every backend carry it. Pure data.

#include <array>
#include <cstdint>
#include <span>

namespace hil::can {

struct Frame {
  std::uint32_t id = 0;     ///< 11-bit (standard) or 29-bit (extended) identifier; error class for error frames
  bool extended = false;    ///< 29-bit identifier
  bool rtr = false;         ///< remote transmission request (no data, dlc = requested length)
  bool error = false;       ///< error frame (SocketCAN CAN_ERR_FLAG); `id` holds CAN_ERR_* class bits
  std::uint8_t dlc = 0;     ///< 0..8
  std::array<std::uint8_t, 8> data{};

  [[nodiscard]] std::span<const std::uint8_t> payload() const noexcept { return {data.data(), dlc}; }
  friend bool operator==(const Frame&, const Frame&) = default;
};

/// Build a data frame with an 11-bit id. Bytes beyond 8 are a programming error (asserted).
[[nodiscard]] Frame make_frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) noexcept;
[[nodiscard]] Frame make_frame(std::uint32_t id, std::span<const std::uint8_t> bytes) noexcept;

}  // namespace hil::can
