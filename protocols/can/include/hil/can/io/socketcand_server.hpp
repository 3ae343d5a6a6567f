// SPDX-License-Identifier: MIT
#pragma once
// socketcand-compatible TCP server (protocol: hil/can/socketcand.hpp). Each client opens a bus by
// name; the BusOpener gives it its own Channel (a participant of an in-process VirtualBus, or a
// SocketCAN socket when bridging a real interface), exactly like the daemon gives each client its
// own raw socket. Raw mode forwards frames both ways; BCM mode accepts `< send >` only.
//
// Robustness: garbage between elements is skipped, malformed elements get `< error ... >` and the
// session continues, overlong elements are dropped, clients may disconnect mid-element, and a
// client that does not read loses frames (counted) instead of stalling the bus, and is not read
// from while its replies are backed up (its output stays bounded by max_output_bytes plus one
// read's worth of replies). A client that opens no bus within handshake_timeout, or that takes no
// data for write_stall_timeout, is closed; a failed accept (out of file descriptors) is retried
// after a growing back-off instead of at once.
// Thread: the server, its sessions and the opened channels run on the executor's thread.

#include <cstdint>
#include <expected>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>

#include <asio/any_io_executor.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/steady_timer.hpp>

#include "hil/can/channel.hpp"
#include "hil/can/socketcand.hpp"
#include "hil/core/clock.hpp"

namespace hil::can::socketcand {

/// Opens bus `name` for client `peer` ("127.0.0.1:50000"). Called on the executor's thread.
using BusOpener = std::function<std::expected<std::unique_ptr<Channel>, std::error_code>(std::string_view name,
                                                                                         const std::string& peer)>;

struct ServerOptions {
  std::size_t max_clients = 32;
  std::size_t max_output_bytes = 1u << 20;  ///< per client; frames beyond are dropped and counted
  /// Receive time (bus clock) -> wire timestamp. Default: wall clock (offset taken at construction).
  std::function<Timestamp(TimePoint)> to_wire_time{};
  /// A client joins the bus when its `< rawmode >` is acknowledged: from then on every frame is
  /// its own and none is dropped. python-can 4.1 (Debian 12) expects that `< ok >` alone in one
  /// recv(), so frames that arrive right after it are queued (not dropped) until the client
  /// sends its first element (proof that it has read its `< ok >`) or `join_hold` has passed,
  /// whichever comes first. 0 = forward at once, like the daemon.
  Duration join_hold{0};
  Duration handshake_timeout{std::chrono::seconds(10)};    ///< from connect to `< open >`
  Duration write_stall_timeout{std::chrono::seconds(30)};  ///< one write pending this long: the client is gone
  Duration accept_backoff_min{std::chrono::milliseconds(50)};
  Duration accept_backoff_max{std::chrono::seconds(1)};
};

struct ServerStats {
  std::uint64_t accepted = 0;
  std::uint64_t refused = 0;  ///< over max_clients
  std::uint64_t active = 0;
  std::uint64_t bus_open_failures = 0;
  std::uint64_t protocol_errors = 0;      ///< malformed/unknown/overlong elements answered with < error >
  std::uint64_t frames_from_clients = 0;  ///< `< send >` put on the bus
  std::uint64_t send_failures = 0;        ///< Channel::send refused (bus-off, queue full)
  std::uint64_t frames_to_clients = 0;
  std::uint64_t dropped_slow_client = 0;
  std::uint64_t rtr_not_forwarded = 0;  ///< socketcand raw mode has no RTR form
  std::uint64_t held_at_join = 0;       ///< frames queued while joining (see ServerOptions::join_hold), all delivered
  std::uint64_t accept_errors = 0;      ///< failed accepts (EMFILE, ENFILE, ...), each followed by a back-off
  std::uint64_t timed_out = 0;          ///< closed: no bus opened in time, or not reading
  std::uint64_t peak_queued_bytes = 0;  ///< largest output queue of any client (bounded, see above)
};

class Server {
 public:
  Server(asio::any_io_executor executor, const Clock& clock, BusOpener opener, ServerOptions options = {});
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  /// Bind and listen (port 0 picks a free port). Errors: address in use, permission, ...
  std::error_code listen(const asio::ip::tcp::endpoint& endpoint);
  [[nodiscard]] asio::ip::tcp::endpoint local_endpoint() const;
  /// Serve an already connected stream socket as a client session (one end of a socketpair for
  /// tests and fuzzing, or a socket handed over by a supervisor). Counts against max_clients.
  void adopt(asio::ip::tcp::socket socket);
  /// Stop accepting and disconnect every client.
  void close();
  [[nodiscard]] const ServerStats& stats() const noexcept;

 private:
  struct Shared;
  class Session;
  void accept();
  std::shared_ptr<Shared> shared_;
  asio::ip::tcp::acceptor acceptor_;
  asio::steady_timer accept_timer_;
  Duration accept_backoff_{};
};

}  // namespace hil::can::socketcand
