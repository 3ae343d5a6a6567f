// SPDX-License-Identifier: MIT
#pragma once
// A hil::can::Channel that is a socketcand client in raw mode (`socketcand://host:port/can0`):
// works against the linux-can socketcand daemon and against `hilbridge can hub`.
//
// Thread: the connection lives on `executor`; receive handlers run there. send(),
// set_receive_handler() and the destructor may be called from any thread; once the destructor
// returns no handler runs (it waits for a running one). The io_context must outlive the channel.
// Limits of the protocol: no RTR frames (send() returns operation_not_supported), no CAN FD.
// Receive times are this process's clock at arrival (the server's wall-clock stamp is not in
// our clock's domain).

#include <cstdint>
#include <expected>
#include <memory>
#include <string>

#include <asio/any_io_executor.hpp>

#include "hil/can/channel.hpp"
#include "hil/core/clock.hpp"

namespace hil::can::socketcand {

struct ClientOptions {
  Duration handshake_timeout{std::chrono::seconds(5)};
  std::size_t max_output_bytes = 1u << 20;  ///< queued, unsent bytes; send() beyond -> no_buffer_space
};

class SocketcandChannel final : public Channel {
 public:
  /// Connect, expect `< hi >`, `< open BUS >`, `< rawmode >`. Blocks the calling thread for at
  /// most options.handshake_timeout (the handshake runs on a private io_context), so call it at
  /// configuration time, not from the executor's own thread while it must serve others.
  /// Errors: connection_refused, timed_out, protocol_error (unexpected reply), no_such_device
  /// (server refused the bus); `diagnostic` receives a sentence saying what happened.
  [[nodiscard]] static std::expected<std::unique_ptr<SocketcandChannel>, std::error_code> connect(
      asio::any_io_executor executor, const Clock& clock, const std::string& host, std::uint16_t port,
      const std::string& bus, ClientOptions options = {}, std::string* diagnostic = nullptr);

  ~SocketcandChannel() override;
  [[nodiscard]] std::string_view name() const noexcept override { return name_; }
  std::error_code send(const Frame& frame) override;
  void set_receive_handler(ReceiveHandler handler) override;
  [[nodiscard]] ChannelStats stats() const noexcept override;
  /// Text of the last `< error ... >` the server sent (empty if none).
  [[nodiscard]] std::string last_server_error() const;
  [[nodiscard]] bool connected() const noexcept;
  /// Bytes accepted by send() and not yet handed to the kernel (0 = flushed).
  [[nodiscard]] std::size_t tx_pending_bytes() const;

  struct Impl;

 private:
  SocketcandChannel(std::shared_ptr<Impl> impl, std::string name);
  std::shared_ptr<Impl> impl_;
  std::string name_;
};

}  // namespace hil::can::socketcand
