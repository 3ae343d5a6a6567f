// SPDX-License-Identifier: MIT
#pragma once
// A classic CAN frame (ISO 11898-1), as SocketCAN and every backend carry it. Pure data.

#include <array>
#include <cstdint>
#include <initializer_list>
#include <span>

namespace hil::can {

struct Frame {
  std::uint32_t id = 0;   ///< 11-bit (standard) or 29-bit (extended) identifier; error class for error frames
  bool extended = false;  ///< 29-bit identifier
  bool rtr = false;       ///< remote transmission request (no data, dlc = requested length)
  bool error = false;     ///< error frame (SocketCAN CAN_ERR_FLAG); `id` holds CAN_ERR_* class bits
  std::uint8_t dlc = 0;   ///< 0..8
  std::array<std::uint8_t, 8> data{};

  [[nodiscard]] std::span<const std::uint8_t> payload() const noexcept {
    return {data.data(), rtr ? std::size_t{0} : std::size_t{dlc > 8 ? std::uint8_t{8} : dlc}};
  }
  friend bool operator==(const Frame&, const Frame&) = default;
};

/// Identifier masks and flag bits of the SocketCAN `can_id` word (<linux/can.h>); the same
/// encoding is used on the wire by pcap (LINKTYPE_CAN_SOCKETCAN, big-endian) and for filters.
inline constexpr std::uint32_t sff_mask = 0x000007FFu;
inline constexpr std::uint32_t eff_mask = 0x1FFFFFFFu;
inline constexpr std::uint32_t err_mask = 0x1FFFFFFFu;
inline constexpr std::uint32_t eff_flag = 0x80000000u;
inline constexpr std::uint32_t rtr_flag = 0x40000000u;
inline constexpr std::uint32_t err_flag = 0x20000000u;

/// Error-frame classes (`id` of an error frame; <linux/can/error.h> CAN_ERR_*).
namespace error_class {
inline constexpr std::uint32_t tx_timeout = 0x001;
inline constexpr std::uint32_t lost_arbitration = 0x002;
inline constexpr std::uint32_t controller = 0x004;  ///< data[1] holds CAN_ERR_CRTL_* bits
inline constexpr std::uint32_t protocol = 0x008;    ///< data[2..3] type/location
inline constexpr std::uint32_t transceiver = 0x010;
inline constexpr std::uint32_t no_ack = 0x020;
inline constexpr std::uint32_t bus_off = 0x040;
inline constexpr std::uint32_t bus_error = 0x080;
inline constexpr std::uint32_t restarted = 0x100;
inline constexpr std::uint32_t all = 0x1FFFFFFFu;
}  // namespace error_class

/// Controller status bits (data[1] of an error frame with class `controller`; CAN_ERR_CRTL_*).
namespace controller_status {
inline constexpr std::uint8_t rx_overflow = 0x01;
inline constexpr std::uint8_t tx_overflow = 0x02;
inline constexpr std::uint8_t rx_warning = 0x04;
inline constexpr std::uint8_t tx_warning = 0x08;
inline constexpr std::uint8_t rx_passive = 0x10;
inline constexpr std::uint8_t tx_passive = 0x20;
inline constexpr std::uint8_t active = 0x40;
}  // namespace controller_status

/// Build a data frame with an 11-bit id. Bytes beyond 8 are a programming error (asserted).
[[nodiscard]] Frame make_frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) noexcept;
[[nodiscard]] Frame make_frame(std::uint32_t id, std::span<const std::uint8_t> bytes) noexcept;
/// Data frame with a 29-bit id.
[[nodiscard]] Frame make_extended_frame(std::uint32_t id, std::span<const std::uint8_t> bytes) noexcept;
/// Remote frame (RTR) asking for `dlc` bytes (0..8).
[[nodiscard]] Frame make_remote_frame(std::uint32_t id, std::uint8_t dlc, bool extended = false) noexcept;
/// Error frame of class `error_class` (CAN_ERR_* bits) with its 8 data bytes.
[[nodiscard]] Frame make_error_frame(std::uint32_t error_class, std::array<std::uint8_t, 8> data = {}) noexcept;

/// The SocketCAN `can_id` word: identifier plus CAN_EFF/RTR/ERR flags.
[[nodiscard]] constexpr std::uint32_t to_socketcan_id(const Frame& f) noexcept {
  if (f.error) return err_flag | (f.id & err_mask);
  return (f.extended ? (eff_flag | (f.id & eff_mask)) : (f.id & sff_mask)) | (f.rtr ? rtr_flag : 0u);
}
/// Inverse of to_socketcan_id for the id/flag fields (dlc and data are left untouched).
constexpr void set_socketcan_id(Frame& f, std::uint32_t can_id) noexcept {
  f.error = (can_id & err_flag) != 0;
  f.extended = !f.error && (can_id & eff_flag) != 0;
  f.rtr = !f.error && (can_id & rtr_flag) != 0;
  f.id = f.error ? (can_id & err_mask) : f.extended ? (can_id & eff_mask) : (can_id & sff_mask);
}

/// A frame a bus can carry: dlc <= 8, id within its 11/29 bits.
[[nodiscard]] constexpr bool is_valid(const Frame& f) noexcept {
  if (f.dlc > 8) return false;
  if (f.error) return f.id <= err_mask;
  return f.id <= (f.extended ? eff_mask : sff_mask);
}

}  // namespace hil::can
