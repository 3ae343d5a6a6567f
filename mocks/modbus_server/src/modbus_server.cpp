// SPDX-License-Identifier: MIT
#include "hil/mocks/modbus_server.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <set>
#include <vector>

#include <fmt/format.h>
#include <asio.hpp>

#include "hil/modbus/adu.hpp"

namespace hil::mocks {

using asio::ip::tcp;

struct ModbusDriveServer::Impl {
  explicit Impl(ModbusDriveServer& s) : server(s) {}
  ModbusDriveServer& server;
  asio::io_context io;
  tcp::acceptor acceptor{io};
  asio::steady_timer step_timer{io};
  asio::steady_timer accept_timer{io};
  Duration accept_backoff{};
  std::chrono::steady_clock::time_point last_step{};
  std::set<std::shared_ptr<Connection>> connections;  // I/O thread only
  bool stopping = false;                              // I/O thread only

  void log(std::string_view msg) const {
    if (server.config_.log) server.config_.log(msg);
  }
  void do_accept();
  void arm_step_timer();
  void close_all();
};

// One client connection. Lives on the I/O thread; owns its buffers, so a misbehaving client
// cannot disturb another one's framing.
class ModbusDriveServer::Connection : public std::enable_shared_from_this<Connection> {
 public:
  Connection(ModbusDriveServer::Impl& impl, tcp::socket socket)
      : impl_(impl), socket_(std::move(socket)), timer_(impl.io), frame_timer_(impl.io), idle_timer_(impl.io) {
    std::error_code ec;
    peer_ = fmt::format("{}", socket_.remote_endpoint(ec).address().to_string());
    socket_.set_option(tcp::no_delay(true), ec);
  }
  void start() {
    arm_idle_timer();
    do_read();
  }

  void close() {
    if (!socket_.is_open()) return;
    std::error_code ec;
    socket_.shutdown(tcp::socket::shutdown_both, ec);
    socket_.close(ec);
    timer_.cancel();
    frame_timer_.cancel();
    idle_timer_.cancel();
    impl_.server.open_.fetch_sub(1);
    impl_.connections.erase(shared_from_this());
  }

 private:
  void do_read() {
    socket_.async_read_some(asio::buffer(rx_.data() + have_, rx_.size() - have_),
                            [self = shared_from_this()](std::error_code ec, std::size_t n) {
                              if (ec) return self->close();  // EOF mid-frame included: drop the partial frame
                              self->have_ += n;
                              self->process();
                            });
  }

  void process() {
    auto& srv = impl_.server;
    tx_.clear();
    std::size_t off = 0;
    std::array<std::uint8_t, modbus::kMaxAduSize> out{};
    while (off < have_) {
      const std::span<const std::uint8_t> rest(rx_.data() + off, have_ - off);
      const modbus::FrameCheck frame = modbus::check_frame(rest);
      if (frame.status == modbus::FrameStatus::need_more) break;
      if (frame.status != modbus::FrameStatus::complete) {
        srv.malformed_.fetch_add(1);
        impl_.log(
            fmt::format("modbus server: closing connection from {}: {} (MBAP protocol id {}, length {}); "
                        "the peer does not speak Modbus/TCP",
                        peer_, frame.status == modbus::FrameStatus::bad_protocol_id ? "bad protocol id" : "bad length",
                        frame.header.protocol_id, frame.header.length));
        close_after_write_ = true;
        off = have_;
        break;
      }
      const std::span<const std::uint8_t> adu(rest.data(), frame.size);
      std::size_t size = 0;
      std::uint32_t pending = srv.fail_count_.load();
      bool injected = false;
      while (pending > 0 && !srv.fail_count_.compare_exchange_weak(pending, pending - 1)) {
      }
      if (pending > 0) {
        injected = true;
        size = modbus::make_exception_adu(out, frame.header, adu[modbus::kMbapSize],
                                          static_cast<std::uint8_t>(srv.fail_code_.load()));
      } else {
        modbus::HandleResult r;
        {
          std::lock_guard lock(srv.device_mutex_);
          r = std::visit([&](auto& d) { return d.handle(adu, out, srv.config_.handler); }, srv.device_);
        }
        size = r.size;
        if (r.error != modbus::ModbusError::none) srv.exceptions_.fetch_add(1);
      }
      if (injected) srv.exceptions_.fetch_add(1);
      srv.requests_.fetch_add(1);
      tx_.insert(tx_.end(), out.begin(), out.begin() + static_cast<std::ptrdiff_t>(size));
      off += frame.size;
    }
    if (off > 0) {
      std::memmove(rx_.data(), rx_.data() + off, have_ - off);
      have_ -= off;
    }
    arm_frame_timer(off > 0);
    if (off > 0) arm_idle_timer();
    if (tx_.empty()) {
      if (close_after_write_) return close();
      return do_read();
    }
    const auto delay = std::chrono::nanoseconds(srv.delay_ns_.load());
    if (delay.count() > 0) {
      timer_.expires_after(delay);
      timer_.async_wait([self = shared_from_this()](std::error_code ec) {
        if (ec) return self->close();
        self->do_write();
      });
    } else {
      do_write();
    }
  }

  // A partial frame must complete within frame_timeout; a new partial frame restarts the clock.
  void arm_frame_timer(bool progressed) {
    if (have_ == 0 || close_after_write_) {
      frame_armed_ = false;
      frame_timer_.cancel();
      return;
    }
    if (frame_armed_ && !progressed) return;
    frame_armed_ = true;  // (re)arming cancels a pending wait, whose handler then sees operation_aborted
    frame_timer_.expires_after(impl_.server.config_.frame_timeout);
    frame_timer_.async_wait([self = shared_from_this()](std::error_code ec) {
      if (ec || !self->frame_armed_) return;
      self->impl_.server.stalled_.fetch_add(1);
      self->impl_.log(fmt::format(
          "modbus server: closing connection from {}: frame incomplete after {} ms ({} bytes)", self->peer_,
          std::chrono::duration_cast<std::chrono::milliseconds>(self->impl_.server.config_.frame_timeout).count(),
          self->have_));
      self->close();
    });
  }

  // Every completed request restarts the idle clock; none for idle_timeout closes the connection.
  void arm_idle_timer() {
    idle_timer_.expires_after(impl_.server.config_.idle_timeout);
    idle_timer_.async_wait([self = shared_from_this()](std::error_code ec) {
      if (ec || !self->socket_.is_open()) return;
      self->impl_.server.idle_closed_.fetch_add(1);
      self->impl_.log(fmt::format("modbus server: closing connection from {}: no request for {} s", self->peer_,
                                  to_seconds(self->impl_.server.config_.idle_timeout)));
      self->close();
    });
  }

  void do_write() {
    asio::async_write(socket_, asio::buffer(tx_), [self = shared_from_this()](std::error_code ec, std::size_t) {
      if (ec || self->close_after_write_) return self->close();
      self->do_read();
    });
  }

  ModbusDriveServer::Impl& impl_;
  tcp::socket socket_;
  asio::steady_timer timer_;
  asio::steady_timer frame_timer_;
  asio::steady_timer idle_timer_;
  bool frame_armed_ = false;
  std::string peer_;
  // Two maximal ADUs fit: a full frame never waits for buffer space.
  std::array<std::uint8_t, 4 * modbus::kMaxAduSize> rx_{};
  std::size_t have_ = 0;
  std::vector<std::uint8_t> tx_;
  bool close_after_write_ = false;
};

void ModbusDriveServer::Impl::do_accept() {
  acceptor.async_accept([this](std::error_code ec, tcp::socket socket) {
    if (stopping || !acceptor.is_open()) return;
    if (!ec) {
      if (server.open_.load() >= server.config_.max_connections) {
        log(fmt::format("modbus server: refusing connection: {} connections open (max_connections)",
                        server.open_.load()));
        std::error_code ignored;
        socket.close(ignored);
      } else {
        server.accepted_.fetch_add(1);
        server.open_.fetch_add(1);
        auto c = std::make_shared<Connection>(*this, std::move(socket));
        connections.insert(c);
        c->start();
      }
    } else if (ec != asio::error::operation_aborted) {
      // Out of file descriptors (EMFILE/ENFILE): the connection stays in the backlog, so an
      // accept at once would fail again at once. Back off (doubling) and log once per attempt.
      server.accept_errors_.fetch_add(1);
      const auto& c = server.config_;
      accept_backoff =
          accept_backoff == Duration{} ? c.accept_backoff_min : std::min(2 * accept_backoff, c.accept_backoff_max);
      log(fmt::format("modbus server: accept failed: {}; retrying in {} ms", ec.message(),
                      std::chrono::duration_cast<std::chrono::milliseconds>(accept_backoff).count()));
      accept_timer.expires_after(accept_backoff);
      accept_timer.async_wait([this](std::error_code e) {
        if (!e && !stopping) do_accept();
      });
      return;
    }
    if (!ec) accept_backoff = {};
    do_accept();
  });
}

void ModbusDriveServer::Impl::arm_step_timer() {
  step_timer.expires_after(server.config_.auto_step);
  step_timer.async_wait([this](std::error_code ec) {
    if (ec || stopping) return;
    const auto now = std::chrono::steady_clock::now();
    auto dt = std::min<std::chrono::steady_clock::duration>(now - last_step, std::chrono::milliseconds(100));
    last_step = now;
    server.step(std::chrono::duration_cast<Duration>(dt));
    arm_step_timer();
  });
}

void ModbusDriveServer::Impl::close_all() {
  stopping = true;
  std::error_code ec;
  acceptor.close(ec);
  step_timer.cancel();
  accept_timer.cancel();
  auto copy = connections;
  for (const auto& c : copy) c->close();
}

ModbusDriveServer::ModbusDriveServer(DriveDevice device, ModbusServerConfig config)
    : device_(std::move(device)), config_(std::move(config)) {
  port_ = config_.port;
}

ModbusDriveServer::ModbusDriveServer(IoTerminal terminal, ModbusServerConfig config)
    : device_(std::move(terminal)), config_(std::move(config)) {
  port_ = config_.port;
}

ModbusDriveServer::~ModbusDriveServer() {
  stop();
}

std::error_code ModbusDriveServer::start() {
  if (running_) return {};
  impl_ = std::make_unique<Impl>(*this);
  std::error_code ec;
  auto address = asio::ip::make_address(config_.listen_host, ec);
  if (ec) {  // a host name ("localhost", the machine's name): its first address
    tcp::resolver resolver(impl_->io);
    const auto results =
        resolver.resolve(config_.listen_host, "", tcp::resolver::passive | tcp::resolver::numeric_service, ec);
    if (ec) return ec;
    if (results.empty()) return asio::error::host_not_found;
    address = results.begin()->endpoint().address();
  }
  const tcp::endpoint ep(address, port_.load());
  impl_->acceptor.open(ep.protocol(), ec);
  if (ec) return ec;
  impl_->acceptor.set_option(tcp::acceptor::reuse_address(true), ec);
  impl_->acceptor.bind(ep, ec);
  if (ec) return ec;
  impl_->acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) return ec;
  port_ = impl_->acceptor.local_endpoint(ec).port();
  impl_->do_accept();
  if (config_.auto_step.count() > 0) {
    impl_->last_step = std::chrono::steady_clock::now();
    impl_->arm_step_timer();
  }
  running_ = true;
  io_thread_ = std::thread([this] { impl_->io.run(); });
  return {};
}

void ModbusDriveServer::stop() {
  if (!running_) return;
  asio::post(impl_->io, [this] { impl_->close_all(); });
  io_thread_.join();
  impl_.reset();
  running_ = false;
}

void ModbusDriveServer::adopt(int fd) {
  if (!running_) {
    ::close(fd);
    return;
  }
  asio::post(impl_->io, [this, fd] {
    if (impl_->stopping) {
      ::close(fd);
      return;
    }
    tcp::socket socket(impl_->io);
    std::error_code ec;
    socket.assign(tcp::v4(), fd, ec);
    if (ec) {
      ::close(fd);
      return;
    }
    accepted_.fetch_add(1);
    open_.fetch_add(1);
    auto c = std::make_shared<Connection>(*impl_, std::move(socket));
    impl_->connections.insert(c);
    c->start();
  });
}

void ModbusDriveServer::step(Duration dt) {
  std::lock_guard lock(device_mutex_);
  if (auto* d = std::get_if<DriveDevice>(&device_)) d->step(dt);
}

void ModbusDriveServer::inject(PlantFault fault, bool active) {
  std::lock_guard lock(device_mutex_);
  if (auto* d = std::get_if<DriveDevice>(&device_)) d->inject(fault, active);
}

void ModbusDriveServer::fail_next(std::uint32_t count, modbus::ModbusError code) {
  fail_code_ = static_cast<int>(code);
  fail_count_ = count;
}

void ModbusDriveServer::set_response_delay(Duration delay) {
  delay_ns_ = delay.count();
}

ModbusServerStats ModbusDriveServer::stats() const {
  return {accepted_.load(), requests_.load(), exceptions_.load(),  malformed_.load(),
          stalled_.load(),  open_.load(),     idle_closed_.load(), accept_errors_.load()};
}

}  // namespace hil::mocks
