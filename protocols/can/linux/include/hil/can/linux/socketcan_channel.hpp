// SPDX-License-Identifier: MIT
#pragma once
// SocketCAN raw socket (PF_CAN / SOCK_RAW / CAN_RAW) as a hil::can::Channel on Asio.
//
// * Classic CAN frames, RTR and error frames. Error frames (CAN_RAW_ERR_FILTER) are decoded into
//   stats (bus-off, error-passive/warning, controller overflows) and a state-change event, and
//   passed to the receive handler too when `deliver_error_frames` is set.
// * Transmit: send() writes straight to the socket when nothing is queued. When the kernel refuses
//   (EAGAIN: socket buffer full; ENOBUFS: interface queue full, txqueuelen) the frame goes into a
//   bounded user-space queue, drained when the socket is writable (EAGAIN) or after a short
//   back-off timer (ENOBUFS: poll() does not signal the qdisc draining). Never a busy loop. A full
//   queue refuses with no_buffer_space and counts tx_dropped.
// * Receive: drop counts of the socket queue (SO_RXQ_OVFL) become rx_overruns.
// * Accepts an already-open, bound fd (adopt): tests pass a socketpair or a vcan socket.
// Thread: the channel lives on `executor`; handlers run there. send(), the set_*_handler()
// functions and the destructor may be called from any thread; once the destructor returns no
// handler runs. The io_context must outlive the channel.

#include <sys/types.h>
#include <cstdint>
#include <expected>
#include <functional>
#include <memory>
#include <string>

#include <asio/any_io_executor.hpp>

#include "hil/can/channel.hpp"
#include "hil/can/error_frame.hpp"
#include "hil/can/filter.hpp"
#include "hil/core/clock.hpp"

namespace hil::can::socketcan {

struct SocketCanOptions {
  bool receive_own = false;  ///< CAN_RAW_RECV_OWN_MSGS
  bool loopback = true;      ///< CAN_RAW_LOOPBACK: other sockets on this host see our frames
  FilterSet filters{.filters = {Filter{}}, .error_mask = error_class::all, .join = false};
  bool deliver_error_frames = true;     ///< pass error frames to the receive handler (stats always)
  std::size_t tx_queue_capacity = 256;  ///< user-space frames waiting for the kernel
  int sndbuf_bytes = 0;                 ///< SO_SNDBUF (0: kernel default); small values make EAGAIN come before ENOBUFS
  Duration enobufs_backoff_min{std::chrono::microseconds(200)};
  Duration enobufs_backoff_max{std::chrono::milliseconds(20)};
  /// Fault-injection seam for tests: replaces ::write for frames (return -1 and set errno).
  std::function<ssize_t(int fd, const void* data, std::size_t size)> write_fn{};
};

struct SocketCanStats {
  ChannelStats channel;
  BusState state = BusState::error_active;
  std::uint64_t enobufs = 0;    ///< ENOBUFS answers from the kernel (retried)
  std::uint64_t eagain = 0;     ///< EAGAIN answers (waited for writability)
  std::uint64_t tx_errors = 0;  ///< frames lost to other write errors (ENETDOWN, ...)
  std::uint64_t tx_queue_high_water = 0;
  std::uint64_t controller_rx_overflows = 0;
  std::uint64_t controller_tx_overflows = 0;
  std::uint64_t no_ack = 0;
  std::uint64_t bus_errors = 0;
  std::uint64_t short_reads = 0;  ///< reads that were not a whole can_frame (ignored)
  std::error_code last_error;
};

class SocketCanChannel final : public Channel {
 public:
  /// Open and bind a raw socket on `interface` ("vcan0", "can0"). Errors: address_family_not_supported
  /// (kernel without CAN), no_such_device (no such interface), permission_denied...;
  /// `diagnostic` gets a sentence with what to do.
  [[nodiscard]] static std::expected<std::unique_ptr<SocketCanChannel>, std::error_code> open(
      asio::any_io_executor executor, const Clock& clock, const std::string& interface, SocketCanOptions options = {},
      std::string* diagnostic = nullptr);
  /// Take ownership of an open, bound socket (closed with the channel). With
  /// `apply_socket_options` the options' CAN_RAW settings are applied, otherwise the fd is used
  /// as it is (socketpairs in tests).
  [[nodiscard]] static std::expected<std::unique_ptr<SocketCanChannel>, std::error_code> adopt(
      asio::any_io_executor executor, const Clock& clock, int fd, std::string name, SocketCanOptions options = {},
      bool apply_socket_options = true);

  ~SocketCanChannel() override;
  [[nodiscard]] std::string_view name() const noexcept override { return name_; }
  /// Errors: invalid_argument, no_buffer_space (user queue full), network_down (interface down
  /// or bus-off reported by the controller), or the socket's error once it failed.
  std::error_code send(const Frame& frame) override;
  void set_receive_handler(ReceiveHandler handler) override;
  [[nodiscard]] ChannelStats stats() const noexcept override;
  [[nodiscard]] SocketCanStats socketcan_stats() const;
  /// Called on the executor when error frames change the controller state.
  void set_state_handler(std::function<void(BusState)> handler);
  /// Frames waiting in the user-space transmit queue.
  [[nodiscard]] std::size_t tx_queued() const;

  struct Impl;

 private:
  SocketCanChannel(std::shared_ptr<Impl> impl, std::string name);
  std::shared_ptr<Impl> impl_;
  std::string name_;
};

}  // namespace hil::can::socketcan
