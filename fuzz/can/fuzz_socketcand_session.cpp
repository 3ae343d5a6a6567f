// SPDX-License-Identifier: MIT
// Byte streams into an in-process socketcand hub session: the hub's Server adopts one end of a
// socketpair per input and serves it on this thread's io_context, with the virtual bus behind it.
// The input goes in chunks of 1 + data[0] % 64 bytes; between chunks a node on the bus sends a
// frame (forwarded to the client once it is in raw mode); then the client's write side is shut.
// Whatever the bytes: no crash or sanitizer report, the session ends within the time limit, the
// reply stream is complete `< ... >` elements, and the hub is left with no session and no bus
// participant of the client.
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <expected>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>

#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>

#include "hil/can/io/socketcand_server.hpp"
#include "hil/can/socketcand.hpp"
#include "hil/can/virtual_bus.hpp"
#include "hil/core/clock.hpp"

namespace sc = hil::can::socketcand;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  hil::VirtualClock clock;
  asio::io_context io;
  hil::can::VirtualBus bus(clock, "can0");
  auto node = bus.attach("node");
  sc::ServerOptions options;
  options.max_output_bytes = 16 * 1024;
  options.to_wire_time = [](hil::TimePoint) { return sc::Timestamp{1700000000, 0}; };
  sc::Server server(
      io.get_executor(), clock,
      [&bus](std::string_view name,
             const std::string& peer) -> std::expected<std::unique_ptr<hil::can::Channel>, std::error_code> {
        if (name != "can0") return std::unexpected(std::make_error_code(std::errc::no_such_device));
        return bus.attach("client:" + peer);
      },
      options);
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0, sv) != 0) std::abort();
  asio::ip::tcp::socket socket(io);
  std::error_code ec;
  socket.assign(asio::ip::tcp::v4(), sv[0], ec);
  if (ec) std::abort();
  server.adopt(std::move(socket));

  const std::size_t chunk = 1 + data[0] % 64;
  const std::uint8_t* p = data + 1;
  std::size_t left = size - 1;
  bool shut = false;
  std::string replies;
  std::uint32_t id = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  for (;;) {
    if (std::chrono::steady_clock::now() > deadline) std::abort();  // the session hangs
    io.poll();
    if (left > 0) {
      const ssize_t n = ::send(sv[1], p, std::min(chunk, left), MSG_NOSIGNAL);
      if (n > 0) {
        p += n;
        left -= static_cast<std::size_t>(n);
      } else if (n < 0 && errno != EAGAIN) {
        left = 0;
      }
      // Bus traffic while the client talks: a frame from the node, delivered at once.
      (void)node->send(hil::can::make_frame(0x100 + (id++ % 0x100), {static_cast<std::uint8_t>(id)}));
      clock.advance(std::chrono::microseconds(100));
      bus.deliver(clock.now());
    } else if (!shut) {
      ::shutdown(sv[1], SHUT_WR);
      shut = true;
    }
    io.poll();
    char buf[4096];
    const ssize_t n = ::recv(sv[1], buf, sizeof buf, 0);
    if (n > 0) {
      replies.append(buf, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EAGAIN) {
      if (shut || left == 0) break;  // the hub ended the session
    } else {
      pollfd pfd{sv[1], POLLIN, 0};
      (void)::poll(&pfd, 1, left > 0 ? 0 : 1);
    }
  }
  ::close(sv[1]);
  io.poll();
  // The reply stream is whole elements.
  sc::ElementSplitter splitter;
  splitter.feed(replies);
  sc::ElementSplitter::Item item;
  while (splitter.next(item))
    if (item.error) std::abort();
  if (server.stats().active != 0) std::abort();
  server.close();
  io.poll();
  if (bus.participant_count() != 1) std::abort();  // only the node: the client left the bus
  return 0;
}
