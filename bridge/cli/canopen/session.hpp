// SPDX-License-Identifier: MIT
#pragma once
// A CLI command's connection to a bus: Asio io_context, steady clock, one channel opened from a
// bus URL, a 1 ms tick, and a bounded run loop. Everything runs on the calling thread.

#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include <asio/io_context.hpp>
#include <asio/steady_timer.hpp>

#include "hil/can/channel.hpp"
#include "hil/can/io/make_channel.hpp"
#include "hil/core/clock.hpp"

namespace hil::cli::canopen_cli {

class BusSession {
 public:
  /// Opens `url`; on failure error() says why (and what to do).
  BusSession(const std::string& url, const std::string& participant);
  [[nodiscard]] bool ok() const noexcept { return channel_ != nullptr; }
  [[nodiscard]] const std::string& error() const noexcept { return error_; }
  [[nodiscard]] can::Channel& channel() noexcept { return *channel_; }
  [[nodiscard]] const SteadyClock& clock() const noexcept { return clock_; }
  [[nodiscard]] TimePoint now() const noexcept { return clock_.now(); }
  [[nodiscard]] asio::io_context& io() noexcept { return io_; }
  /// Run until `done()` is true or `limit` elapsed, calling `tick(now)` every millisecond.
  /// Returns whether done() became true.
  bool run(const std::function<bool()>& done, const std::function<void(TimePoint)>& tick, Duration limit);

 private:
  asio::io_context io_;
  SteadyClock clock_;
  can::VirtualBusRegistry virtual_buses_{clock_};
  std::unique_ptr<can::Channel> channel_;
  std::string error_;
};

}  // namespace hil::cli::canopen_cli
