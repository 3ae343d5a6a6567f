// SPDX-License-Identifier: MIT
#pragma once
// pcap file bytes for CAN captures (pure): classic libpcap format (magic 0xA1B2C3D4 written in
// little-endian, version 2.4) with LINKTYPE_CAN_SOCKETCAN (227), the link type tcpdump uses on a
// SocketCAN interface and Wireshark's CAN/CANopen dissectors read. Each record is the 16-byte
// SocketCAN frame with the can_id word (id plus EFF/RTR/ERR flags) in BIG-endian byte order,
// then the payload length, FD flags (0), two reserved bytes and 8 data bytes (zero padded).
// Spec: https://www.tcpdump.org/linktypes/LINKTYPE_CAN_SOCKETCAN.html

#include <array>
#include <cstdint>

#include "hil/can/frame.hpp"
#include "hil/can/socketcand.hpp"  // Timestamp

namespace hil::can::pcap {

inline constexpr std::uint32_t linktype_can_socketcan = 227;
inline constexpr std::uint32_t snaplen = 65535;
inline constexpr std::size_t global_header_size = 24;
inline constexpr std::size_t record_header_size = 16;
inline constexpr std::size_t frame_size = 16;

[[nodiscard]] std::array<std::uint8_t, global_header_size> make_global_header() noexcept;
/// Record header plus frame bytes (record_header_size + frame_size).
[[nodiscard]] std::array<std::uint8_t, record_header_size + frame_size> make_record(
    const Frame& frame, socketcand::Timestamp time) noexcept;

}  // namespace hil::can::pcap
