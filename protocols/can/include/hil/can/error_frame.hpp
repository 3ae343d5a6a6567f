// SPDX-License-Identifier: MIT
#pragma once
// Decoding of SocketCAN error frames (<linux/can/error.h>) into controller state and counters.
// Pure; used by the SocketCAN backend for its stats/events and by `hilbridge can dump`.

#include <cstdint>
#include <optional>
#include <string>

#include "hil/can/frame.hpp"

namespace hil::can {

/// ISO 11898-1 fault confinement states.
enum class BusState : std::uint8_t { error_active, error_warning, error_passive, bus_off };
[[nodiscard]] const char* to_string(BusState s) noexcept;

struct ErrorFrameInfo {
  std::optional<BusState> state;  ///< new state if the frame announces one
  bool rx_overflow = false;       ///< controller lost received frames
  bool tx_overflow = false;
  bool no_ack = false;  ///< nobody acknowledged (alone on the bus / wrong bitrate)
  bool tx_timeout = false;
  bool lost_arbitration = false;
  bool protocol_violation = false;
  bool bus_error = false;
  bool transceiver = false;
  std::optional<std::uint8_t> tx_error_count;  ///< CAN_ERR_CNT (data[6])
  std::optional<std::uint8_t> rx_error_count;  ///< CAN_ERR_CNT (data[7])
};

/// Decode an error frame (frame.error must be set; other frames give an empty info).
[[nodiscard]] ErrorFrameInfo decode_error_frame(const Frame& f) noexcept;
/// One line for logs: "bus-off", "controller: rx-passive tx-warning", ...
[[nodiscard]] std::string describe_error_frame(const Frame& f);

}  // namespace hil::can
