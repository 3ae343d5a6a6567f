// SPDX-License-Identifier: MIT
#include "hil/can/io/bus_runner.hpp"

namespace hil::can {

AsioBusRunner::AsioBusRunner(asio::any_io_executor executor, VirtualBus& bus, const SteadyClock& clock)
    : bus_(bus), clock_(clock), timer_(std::move(executor)) {
  bus_.set_wakeup_handler([this](TimePoint due) { arm(due); });
  if (auto due = bus_.next_due()) arm(*due);
}

AsioBusRunner::~AsioBusRunner() {
  *alive_ = false;  // a wait that already completed may still be dispatched: it must not touch `this`
  bus_.set_wakeup_handler({});
  timer_.cancel();
}

void AsioBusRunner::arm(TimePoint due) {
  if (armed_for_ && *armed_for_ <= due) return;  // an earlier wakeup is already pending
  armed_for_ = due;
  timer_.expires_at(clock_.to_steady(due));
  timer_.async_wait([this, alive = alive_](const std::error_code& ec) {
    if (ec || !*alive) return;  // cancelled (re-armed earlier), or the runner is gone: do not touch `this`
    armed_for_.reset();
    ++wakeups_;
    bus_.deliver(clock_.now());  // re-arms through the wakeup handler if frames remain
  });
}

}  // namespace hil::can
