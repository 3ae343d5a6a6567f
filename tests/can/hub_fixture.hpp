// SPDX-License-Identifier: MIT
#pragma once
// Test fixture: a socketcand hub (VirtualBus on real time + AsioBusRunner + Server) served by an
// io_context on a background thread, and a thread-safe inbox to wait for frames with a bounded
// timeout (never a fixed sleep).
#include <gtest/gtest.h>

#include <condition_variable>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <asio/executor_work_guard.hpp>
#include <asio/io_context.hpp>
#include <asio/post.hpp>
#include <asio/steady_timer.hpp>

#include "hil/can/io/bus_runner.hpp"
#include "hil/can/io/socketcand_server.hpp"
#include "hil/can/virtual_bus.hpp"

namespace hil::can::test {

class Inbox {
 public:
  void push(const Frame& f) {
    {
      std::lock_guard lock(mu_);
      frames_.push_back(f);
    }
    cv_.notify_all();
  }
  /// Wait until at least `n` frames arrived (bounded); returns a copy of all frames.
  std::vector<Frame> wait_for(std::size_t n, std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
    std::unique_lock lock(mu_);
    cv_.wait_for(lock, timeout, [&] { return frames_.size() >= n; });
    return frames_;
  }
  std::vector<Frame> snapshot() {
    std::lock_guard lock(mu_);
    return frames_;
  }
  Channel::ReceiveHandler handler() {
    return [this](const Frame& f, TimePoint) { push(f); };
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  std::vector<Frame> frames_;
};

class Hub {
 public:
  explicit Hub(socketcand::ServerOptions options = {}, std::string bus_name = "can0")
      : bus(clock, bus_name), bus_name_(std::move(bus_name)) {
    runner_ = std::make_unique<AsioBusRunner>(io.get_executor(), bus, clock);
    server = std::make_unique<socketcand::Server>(
        io.get_executor(), clock,
        [this](std::string_view name,
               const std::string& peer) -> std::expected<std::unique_ptr<Channel>, std::error_code> {
          if (name != bus_name_) return std::unexpected(std::make_error_code(std::errc::no_such_device));
          return bus.attach("socketcand:" + peer);
        },
        std::move(options));
    const auto ec = server->listen({asio::ip::make_address("127.0.0.1"), 0});
    EXPECT_FALSE(ec) << ec.message();
    thread_ = std::thread([this] { io.run(); });
  }
  ~Hub() { shutdown(); }
  std::uint16_t port() const { return server->local_endpoint().port(); }
  /// Run `fn` on the io thread and wait for it (bounded).
  template <class F>
  auto run(F fn) {
    std::packaged_task<decltype(fn())()> task(std::move(fn));
    auto fut = task.get_future();
    asio::post(io, [&task] { task(); });
    EXPECT_EQ(fut.wait_for(std::chrono::seconds(5)), std::future_status::ready);
    return fut.get();
  }
  void shutdown() {
    if (!thread_.joinable()) return;
    run([this] {
      server->close();
      runner_.reset();
    });
    work_.reset();
    io.stop();
    thread_.join();
  }

  SteadyClock clock;
  asio::io_context io;
  VirtualBus bus;
  std::unique_ptr<socketcand::Server> server;

 private:
  std::string bus_name_;
  asio::executor_work_guard<asio::io_context::executor_type> work_{io.get_executor()};
  std::unique_ptr<AsioBusRunner> runner_;
  std::thread thread_;
};

/// Calls `fn` every `period` on `io`'s thread from start() until stop(). Both are called on that
/// thread (e.g. inside Hub::run). A wait that had already completed when stop() ran may still be
/// dispatched: the shared flag makes it a no-op, so `fn` never runs after stop() and the ticker
/// may be destroyed right after it.
class Ticker {
 public:
  Ticker(asio::io_context& io, std::chrono::milliseconds period, std::function<void()> fn)
      : timer_(io), period_(period), fn_(std::move(fn)) {}
  ~Ticker() { stop(); }
  Ticker(const Ticker&) = delete;
  Ticker& operator=(const Ticker&) = delete;
  void start() {
    *running_ = true;
    arm();
  }
  void stop() {
    *running_ = false;
    timer_.cancel();
  }

 private:
  void arm() {
    timer_.expires_after(period_);
    timer_.async_wait([this, running = running_](const std::error_code& ec) {
      if (ec || !*running) return;
      fn_();
      arm();
    });
  }
  asio::steady_timer timer_;
  std::chrono::milliseconds period_;
  std::function<void()> fn_;
  std::shared_ptr<bool> running_ = std::make_shared<bool>(false);
};

}  // namespace hil::can::test
