// SPDX-License-Identifier: MIT
#pragma once
// Drives a VirtualBus on real time from an Asio executor: a steady_timer armed at the bus's next
// due time (VirtualBus::set_wakeup_handler) calls deliver(). No polling. Used by the socketcand
// hub (`hilbridge can hub`). Thread: the bus, this runner and every channel of the bus belong to
// the executor's thread; construct and destroy on it (or while the io_context is not running).

#include <memory>

#include <asio/any_io_executor.hpp>
#include <asio/steady_timer.hpp>

#include "hil/can/virtual_bus.hpp"
#include "hil/core/clock.hpp"

namespace hil::can {

class AsioBusRunner {
 public:
  AsioBusRunner(asio::any_io_executor executor, VirtualBus& bus, const SteadyClock& clock);
  ~AsioBusRunner();
  AsioBusRunner(const AsioBusRunner&) = delete;
  AsioBusRunner& operator=(const AsioBusRunner&) = delete;

  [[nodiscard]] std::uint64_t wakeups() const noexcept { return wakeups_; }

 private:
  void arm(TimePoint due);
  VirtualBus& bus_;
  const SteadyClock& clock_;
  asio::steady_timer timer_;
  std::optional<TimePoint> armed_for_;
  std::uint64_t wakeups_ = 0;
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);  ///< false once destroyed (see arm())
};

}  // namespace hil::can
