// SPDX-License-Identifier: MIT
#pragma once
// A legacy-device emulator's line side, and the host that runs it on a byte stream.
// Endpoint: pure reaction to received bytes and time (bytes in, reply bytes out).
// EndpointHost: the I/O loop (one thread), debounced persistence, fault injection hooks.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <span>
#include <string>
#include <system_error>

#include "hil/core/clock.hpp"
#include "hil/serial/byte_stream.hpp"

namespace hil::mocks::legacy {

class Endpoint {
 public:
  virtual ~Endpoint() = default;
  /// Bytes received from the line (after line discipline). Returns bytes to send.
  virtual std::string on_bytes(std::span<const std::uint8_t> data, TimePoint now) = 0;
  /// A character error (parity/framing/overrun/break) at this point of the stream.
  virtual std::string on_line_error(std::error_code ec, TimePoint now) = 0;
  /// Called when nothing arrived for a while (timers of timed protocols). Returns bytes to send.
  virtual std::string on_idle(TimePoint /*now*/) { return {}; }
  /// Earliest time on_idle needs to run; TimePoint::max() if none.
  [[nodiscard]] virtual TimePoint next_deadline() const { return TimePoint::max(); }
  /// State changed since the last call (persist now).
  [[nodiscard]] virtual bool take_dirty() { return false; }
  /// Serialised state for the state file.
  [[nodiscard]] virtual std::string save_state() const { return {}; }
};

class EndpointHost {
 public:
  /// `state_file` may be empty (no persistence). Thread: run() on one thread; stop() and
  /// with_endpoint() from any thread.
  EndpointHost(Endpoint& endpoint, serial::ByteStream& stream, const Clock& clock,
               std::filesystem::path state_file = {});

  /// Serve until stop(). Persists state whenever the line is quiet after changes.
  void run();
  /// One step: wait at most `max_wait` for bytes, handle them, write the reply. Returns the
  /// line's error (LineError::closed when a TCP client went away).
  std::error_code step(Duration max_wait);
  void stop() noexcept { stop_ = true; }
  /// Run `fn` on the endpoint under the host's lock (mode changes while serving).
  void with_endpoint(const std::function<void(Endpoint&)>& fn);
  /// Save now if dirty. Returns the error of the last save.
  std::error_code persist();
  /// When the last byte arrived (construction time before the first): idle TCP clients are
  /// closed by the caller.
  [[nodiscard]] TimePoint last_rx() const noexcept { return last_rx_; }

  /// Fault injection: after `after` more replies, drop the next `count` (a station or line
  /// that stops answering). Thread-safe.
  void drop_replies(int after, int count) {
    drop_after_ = after;
    drop_replies_ = count;
  }

 private:
  void send(const std::string& bytes);

  Endpoint& endpoint_;
  serial::ByteStream& stream_;
  const Clock& clock_;
  std::filesystem::path state_file_;
  std::mutex mutex_;
  std::atomic<bool> stop_{false};
  std::atomic<int> drop_replies_{0};
  std::atomic<int> drop_after_{0};
  bool pending_save_ = false;
  TimePoint last_rx_;
};

}  // namespace hil::mocks::legacy
