// SPDX-License-Identifier: MIT
#pragma once
// Modbus/TCP application data unit: the 7-byte MBAP header (transaction id, protocol id 0,
// length = unit id + PDU bytes, unit id) followed by the PDU (Modbus Messaging on TCP/IP
// Implementation Guide v1.0b §3.1.3). Framing uses the MBAP length field, not the function
// code (libmodbus 3.1.6 frames by function code and desynchronises on unknown codes, upstream
// issues #848/#867), so garbage cannot shift the frame boundary of the next request.

#include <cstddef>
#include <cstdint>
#include <span>

namespace hil::modbus {

inline constexpr std::size_t kMbapSize = 7;
inline constexpr std::size_t kMaxPduSize = 253;
inline constexpr std::size_t kMaxAduSize = kMbapSize + kMaxPduSize;  // 260
inline constexpr std::uint16_t kMaxReadRegisters = 125;              // FC 3/4
inline constexpr std::uint16_t kMaxWriteRegisters = 123;             // FC 16
inline constexpr std::uint16_t kMaxRwWriteRegisters = 121;           // FC 23 write part
inline constexpr std::uint16_t kMaxReadBits = 2000;                  // FC 1/2 (MB spec §6.1, §6.2)
inline constexpr std::uint16_t kMaxWriteBits = 1968;                 // FC 15 (0x7B0, MB spec §6.11)
inline constexpr std::uint16_t kDefaultPort = 502;

namespace fc {
inline constexpr std::uint8_t read_coils = 0x01;
inline constexpr std::uint8_t read_discrete_inputs = 0x02;
inline constexpr std::uint8_t write_single_coil = 0x05;
inline constexpr std::uint8_t write_multiple_coils = 0x0F;
inline constexpr std::uint8_t read_holding_registers = 0x03;
inline constexpr std::uint8_t read_input_registers = 0x04;
inline constexpr std::uint8_t write_single_register = 0x06;
inline constexpr std::uint8_t write_multiple_registers = 0x10;
inline constexpr std::uint8_t mask_write_register = 0x16;
inline constexpr std::uint8_t read_write_registers = 0x17;
}  // namespace fc

struct MbapHeader {
  std::uint16_t transaction_id = 0;
  std::uint16_t protocol_id = 0;
  std::uint16_t length = 0;  ///< unit id + PDU bytes
  std::uint8_t unit_id = 0;
};

enum class FrameStatus : std::uint8_t {
  complete,         ///< `size` bytes form one ADU
  need_more,        ///< header or body incomplete; read more bytes
  bad_protocol_id,  ///< protocol id != 0: not Modbus; the stream cannot be trusted
  bad_length,       ///< length field < 2 (unit + FC) or > 254 (ADU > 260 bytes)
};

struct FrameCheck {
  FrameStatus status = FrameStatus::need_more;
  std::size_t size = 0;  ///< ADU size when complete
  MbapHeader header{};   ///< valid when the first 7 bytes were present
};

/// Look at the start of a receive buffer: is there a complete ADU? Pure, no allocation.
[[nodiscard]] FrameCheck check_frame(std::span<const std::uint8_t> buffer) noexcept;

/// Big-endian helpers.
[[nodiscard]] constexpr std::uint16_t get_u16(const std::uint8_t* p) noexcept {
  return static_cast<std::uint16_t>((p[0] << 8) | p[1]);
}
constexpr void put_u16(std::uint8_t* p, std::uint16_t v) noexcept {
  p[0] = static_cast<std::uint8_t>(v >> 8);
  p[1] = static_cast<std::uint8_t>(v & 0xFF);
}

/// Write an MBAP header for a PDU of `pdu_size` bytes into `out[0..7)`.
void make_mbap(std::uint8_t* out, std::uint16_t transaction_id, std::uint8_t unit_id, std::size_t pdu_size) noexcept;

/// Build an exception response ADU (FC | 0x80, code) for `request_header`/`function` into `out`
/// (at least 9 bytes). Returns the ADU size (9).
std::size_t make_exception_adu(std::span<std::uint8_t> out, const MbapHeader& request_header, std::uint8_t function,
                               std::uint8_t code) noexcept;

}  // namespace hil::modbus
