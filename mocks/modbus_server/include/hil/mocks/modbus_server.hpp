// SPDX-License-Identifier: MIT
#pragma once
// Simulated Modbus/TCP server: serves a DriveDevice (profile + state machine + plant) or an
// IoTerminal (coils and discrete inputs) to any number of clients at once on one Asio I/O thread.
//
// Threads:
//  - the I/O thread (started by start(), joined by stop()) accepts connections, frames requests
//    by the MBAP length, has libmodbus answer each one (DriveDevice / ModbusResponder) under the
//    device mutex and writes the replies;
//    with `auto_step` set it also steps the plant on a real-time timer;
//  - any other thread may call step(), inject(), with_device(), with_terminal(), the fault hooks
//    and stats().
// Each connection owns its receive buffer: a client sending garbage (bad protocol id / length)
// is logged and disconnected alone; one that stops mid-frame only holds its own buffer; wrong
// PDU lengths inside a well-framed ADU get exception 03 and the connection stays up.
//
// Unlike libmodbus 3.1.6's modbus_receive(), framing uses the MBAP length (upstream issues
// #848/#867: function-code framing desynchronises on unknown codes), and no connection can block
// the others while a frame trickles in. See docs/modbus.md.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <variant>

#include "hil/core/clock.hpp"
#include "hil/mocks/modbus_drive_device.hpp"
#include "hil/mocks/modbus_io_terminal.hpp"
#include "hil/modbus/error.hpp"
#include "hil/modbus/request_handler.hpp"

namespace hil::mocks {

struct ModbusServerConfig {
  std::string listen_host = "127.0.0.1";  ///< loopback by default; "0.0.0.0" to serve the LAN
  std::uint16_t port = 0;                 ///< 0 = ephemeral (see ModbusDriveServer::port())
  modbus::HandlerOptions handler{};
  std::size_t max_connections = 64;  ///< further connections are accepted and closed at once
  Duration auto_step{};              ///< > 0: step the plant on a real-time timer with this period
  /// A frame started but not completed within this time closes the connection (a stalled
  /// client must not hold a connection slot forever). Real time.
  Duration frame_timeout{std::chrono::seconds(5)};
  /// A connection that completes no request for this long is closed: idle or half-open clients
  /// must not hold every slot. Real time.
  Duration idle_timeout{std::chrono::seconds(60)};
  /// A failed accept (out of file descriptors) is retried after this back-off, doubling up to
  /// the max, instead of at once.
  Duration accept_backoff_min{std::chrono::milliseconds(50)};
  Duration accept_backoff_max{std::chrono::seconds(1)};
  /// Diagnostics (malformed frames, refused connections). Called on the I/O thread; must not block.
  std::function<void(std::string_view)> log;
};

struct ModbusServerStats {
  std::uint64_t connections_accepted = 0;
  std::uint64_t requests = 0;
  std::uint64_t exceptions = 0;  ///< exception responses sent (handler or injected)
  std::uint64_t malformed = 0;   ///< connections closed for a bad MBAP header
  std::uint64_t stalled = 0;     ///< connections closed for a frame left incomplete (frame_timeout)
  std::uint64_t open_connections = 0;
  std::uint64_t idle_closed = 0;    ///< connections closed for completing no request (idle_timeout)
  std::uint64_t accept_errors = 0;  ///< failed accepts (EMFILE, ...), each followed by a back-off
};

class ModbusDriveServer {
 public:
  ModbusDriveServer(DriveDevice device, ModbusServerConfig config);
  /// Serve a simulated I/O terminal instead of a drive (step() and inject() do nothing).
  ModbusDriveServer(IoTerminal terminal, ModbusServerConfig config);
  ~ModbusDriveServer();
  ModbusDriveServer(const ModbusDriveServer&) = delete;
  ModbusDriveServer& operator=(const ModbusDriveServer&) = delete;

  /// Bind, listen and start the I/O thread. Errors: address in use, bad host, ...
  /// Restartable after stop() (binds the same port again when config.port was 0 and a port had
  /// been chosen, so clients can reconnect to the address they know).
  std::error_code start();
  /// Close the listener and every connection and join the I/O thread. Idempotent.
  void stop();
  [[nodiscard]] bool running() const noexcept { return running_.load(); }
  /// Serve an already connected stream socket `fd` (one end of a socketpair for tests and fuzzing)
  /// as a client connection; the server takes ownership. Needs a running server.
  void adopt(int fd);
  /// The bound port (valid after a successful start()).
  [[nodiscard]] std::uint16_t port() const noexcept { return port_.load(); }

  /// Step the plant by `dt` (any thread; takes the device mutex).
  void step(Duration dt);
  void inject(PlantFault fault, bool active);
  /// Run `fn(device)` under the device mutex. Only for a server built on a DriveDevice
  /// (std::bad_variant_access otherwise).
  template <class Fn>
  decltype(auto) with_device(Fn&& fn) {
    std::lock_guard lock(device_mutex_);
    return fn(std::get<DriveDevice>(device_));
  }
  /// Run `fn(terminal)` under the device mutex. Only for a server built on an IoTerminal.
  template <class Fn>
  decltype(auto) with_terminal(Fn&& fn) {
    std::lock_guard lock(device_mutex_);
    return fn(std::get<IoTerminal>(device_));
  }

  /// Fault hooks for tests: answer the next `count` requests with exception `code` instead of
  /// serving them; delay every response by `delay` (0 = off).
  void fail_next(std::uint32_t count, modbus::ModbusError code);
  void set_response_delay(Duration delay);

  [[nodiscard]] ModbusServerStats stats() const;

 private:
  struct Impl;
  class Connection;
  std::variant<DriveDevice, IoTerminal> device_;
  mutable std::mutex device_mutex_;
  ModbusServerConfig config_;
  std::unique_ptr<Impl> impl_;
  std::thread io_thread_;
  std::atomic<bool> running_{false};
  std::atomic<std::uint16_t> port_{0};
  std::atomic<std::uint32_t> fail_count_{0};
  std::atomic<int> fail_code_{0};
  std::atomic<std::int64_t> delay_ns_{0};
  std::atomic<std::uint64_t> accepted_{0}, requests_{0}, exceptions_{0}, malformed_{0}, stalled_{0}, open_{0};
  std::atomic<std::uint64_t> idle_closed_{0}, accept_errors_{0};
};

}  // namespace hil::mocks
