// SPDX-License-Identifier: MIT
#include "session.hpp"

namespace hil::cli::canopen_cli {

BusSession::BusSession(const std::string& url, const std::string& participant) {
  can::ChannelRequest req{io_.get_executor(), clock_, &virtual_buses_, participant};
  auto ch = can::make_channel(url, req);
  if (!ch) {
    error_ = ch.error().message.empty() ? ch.error().code.message() : ch.error().message;
    return;
  }
  channel_ = std::move(*ch);
}

bool BusSession::run(const std::function<bool()>& done, const std::function<void(TimePoint)>& tick, Duration limit) {
  const auto end = clock_.now() + limit;
  asio::steady_timer timer(io_);
  bool finished = done();
  std::function<void()> arm;
  arm = [&] {
    timer.expires_after(std::chrono::milliseconds(1));
    timer.async_wait([&](const std::error_code& ec) {
      if (ec) return;
      if (tick) tick(clock_.now());
      if (done()) {
        finished = true;
        return;
      }
      if (clock_.now() >= end) return;
      arm();
    });
  };
  if (!finished) arm();
  io_.restart();
  while (!finished && clock_.now() < end + std::chrono::milliseconds(5)) {
    io_.run_one_for(std::chrono::milliseconds(10));
    if (done()) finished = true;
  }
  timer.cancel();
  io_.poll();
  return finished || done();
}

}  // namespace hil::cli::canopen_cli
