// SPDX-License-Identifier: MIT
#pragma once
// CiA 301 predefined connection set (11-bit COB-IDs, CiA 301 §7.3.5) and the frame sink every
// CANopen service emits through. Pure data.

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <span>

#include "hil/can/frame.hpp"

namespace hil::canopen {

using NodeId = std::uint8_t;  ///< 1..127; 0 addresses all nodes in NMT commands

inline constexpr std::uint32_t cob_nmt = 0x000;
inline constexpr std::uint32_t cob_sync = 0x080;
inline constexpr std::uint32_t cob_emcy_base = 0x080;
inline constexpr std::uint32_t cob_time = 0x100;
inline constexpr std::uint32_t cob_tpdo_base[4] = {0x180, 0x280, 0x380, 0x480};
inline constexpr std::uint32_t cob_rpdo_base[4] = {0x200, 0x300, 0x400, 0x500};
inline constexpr std::uint32_t cob_sdo_tx_base = 0x580;  ///< server -> client
inline constexpr std::uint32_t cob_sdo_rx_base = 0x600;  ///< client -> server
inline constexpr std::uint32_t cob_heartbeat_base = 0x700;

[[nodiscard]] constexpr bool is_valid_node_id(unsigned id) noexcept {
  return id >= 1 && id <= 127;
}

/// Where services put the frames they produce. Called synchronously from on_frame()/step();
/// the callee queues or sends the frame and must not re-enter the calling service.
using FrameSink = std::function<void(const can::Frame&)>;

/// Data frame with an 11-bit id from up to 8 bytes (more are cut; pure helper for the services).
[[nodiscard]] inline can::Frame frame_of(std::uint32_t id, std::span<const std::uint8_t> bytes) noexcept {
  can::Frame f;
  f.id = id;
  f.dlc = static_cast<std::uint8_t>(bytes.size() > 8 ? 8 : bytes.size());
  for (std::size_t i = 0; i < f.dlc; ++i) f.data[i] = bytes[i];
  return f;
}
[[nodiscard]] inline can::Frame frame_of(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) noexcept {
  return frame_of(id, std::span<const std::uint8_t>(bytes.begin(), bytes.size()));
}

/// Little-endian helpers (CANopen is little-endian on the wire, CiA 301 §7.1.2).
[[nodiscard]] constexpr std::uint16_t get_le16(const std::uint8_t* p) noexcept {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
[[nodiscard]] constexpr std::uint32_t get_le32(const std::uint8_t* p) noexcept {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
constexpr void put_le16(std::uint8_t* p, std::uint16_t v) noexcept {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
constexpr void put_le32(std::uint8_t* p, std::uint32_t v) noexcept {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

}  // namespace hil::canopen
