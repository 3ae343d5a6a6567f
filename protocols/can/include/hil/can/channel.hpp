// SPDX-License-Identifier: MIT
#pragma once
// The CAN channel concept. Backends: the in-process virtual bus (protocols/can, deterministic on
// the virtual clock), SocketCAN raw sockets on Asio (protocols/can/linux), and socketcand over
// TCP. CANopen services and mock nodes talk to a Channel and never know which one it is.

#include <cstdint>
#include <functional>
#include <string_view>
#include <system_error>

#include "hil/can/frame.hpp"
#include "hil/core/clock.hpp"

namespace hil::can {

struct ChannelStats {
  std::uint64_t tx_frames = 0;
  std::uint64_t rx_frames = 0;
  std::uint64_t tx_dropped = 0;  ///< rejected because the transmit queue was full (ENOBUFS)
  std::uint64_t rx_overruns = 0;
  std::uint64_t error_frames = 0;
  bool bus_off = false;
};

class Channel {
 public:
  /// Called for every received frame with its receive time. Runs on the channel's executor:
  /// for the virtual bus inside VirtualBus::deliver(), for SocketCAN on the io_context thread.
  /// Must not block; may call send() (re-entrancy is allowed: the frame is queued).
  using ReceiveHandler = std::function<void(const Frame&, TimePoint)>;

  virtual ~Channel() = default;
  [[nodiscard]] virtual std::string_view name() const noexcept = 0;
  /// Queue a frame. Non-blocking. Errors: std::errc::no_buffer_space (queue full, frame
  /// dropped and counted), std::errc::network_down (bus-off / interface down).
  virtual std::error_code send(const Frame& frame) = 0;
  /// Replace the receive handler (one per channel; fan out above this layer).
  virtual void set_receive_handler(ReceiveHandler handler) = 0;
  [[nodiscard]] virtual ChannelStats stats() const noexcept = 0;
};

}  // namespace hil::can
