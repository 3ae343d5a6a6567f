// SPDX-License-Identifier: MIT
#include "hil/can/io/socketcand_channel.hpp"

#include <array>
#include <atomic>
#include <mutex>

#include <asio/connect.hpp>
#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/post.hpp>
#include <asio/write.hpp>

#include "hil/can/socketcand.hpp"

namespace hil::can::socketcand {

struct SocketcandChannel::Impl : std::enable_shared_from_this<SocketcandChannel::Impl> {
  Impl(asio::any_io_executor ex, const Clock& c, ClientOptions o) : socket(std::move(ex)), clock(c), options(o) {}

  asio::ip::tcp::socket socket;
  const Clock& clock;
  ClientOptions options;
  ElementSplitter splitter;
  std::array<char, 4096> rx{};
  // Held while a handler runs, so the destructor (any thread) waits for a running handler and no
  // handler starts afterwards. Recursive: a handler may destroy its own channel.
  std::recursive_mutex handler_mu;
  ReceiveHandler handler;

  mutable std::mutex mu;  // guards everything below
  std::string pending;
  std::string outbox;
  bool writing = false;
  bool closed = false;
  ChannelStats stats;
  std::string last_error;

  void read() {
    socket.async_read_some(asio::buffer(rx), [self = shared_from_this()](const std::error_code& ec, std::size_t n) {
      if (ec) {
        self->close();
        return;
      }
      self->splitter.feed(std::string_view(self->rx.data(), n));
      self->drain_elements();
      if (!self->is_closed()) self->read();
    });
  }

  void drain_elements() {
    ElementSplitter::Item item;
    while (splitter.next(item)) {
      if (item.error) continue;
      auto e = parse_element(item.element);
      if (!e) continue;  // tolerate what we do not understand, as the daemon does
      if (const auto* rx_frame = std::get_if<RxFrame>(&*e)) {
        {
          std::lock_guard lock(mu);
          ++stats.rx_frames;
        }
        std::lock_guard hl(handler_mu);
        if (handler) handler(rx_frame->frame, clock.now());
      } else if (const auto* ef = std::get_if<ErrorFrame>(&*e)) {
        {
          std::lock_guard lock(mu);
          ++stats.error_frames;
          if (ef->frame.id & error_class::bus_off) stats.bus_off = true;
          if (ef->frame.id & error_class::restarted) stats.bus_off = false;
        }
        std::lock_guard hl(handler_mu);
        if (handler) handler(ef->frame, clock.now());
      } else if (const auto* et = std::get_if<ErrorText>(&*e)) {
        std::lock_guard lock(mu);
        last_error = et->text;
      }
    }
  }

  bool is_closed() const {
    std::lock_guard lock(mu);
    return closed;
  }

  void close() {
    {
      std::lock_guard lock(mu);
      if (closed) return;
      closed = true;
    }
    std::error_code ec;
    socket.shutdown(asio::ip::tcp::socket::shutdown_both, ec);
    socket.close(ec);
  }

  void start_write() {
    {
      std::lock_guard lock(mu);
      if (closed || pending.empty()) {
        writing = false;
        return;
      }
      outbox.swap(pending);
      pending.clear();
    }
    asio::async_write(socket, asio::buffer(outbox),
                      [self = shared_from_this()](const std::error_code& ec, std::size_t) {
                        self->outbox.clear();
                        if (ec) {
                          {
                            std::lock_guard lock(self->mu);
                            self->writing = false;
                          }
                          self->close();
                          return;
                        }
                        self->start_write();
                      });
  }
};

namespace {

struct Handshake {
  asio::io_context io;
  asio::ip::tcp::socket sock{io};
  ElementSplitter splitter;
  std::array<char, 1024> buf{};
  std::chrono::steady_clock::time_point deadline;

  /// Run the private context until `done` or the deadline.
  std::error_code wait(const bool& done, const std::error_code& result) {
    io.restart();
    while (!done) {
      if (io.run_one_until(deadline) == 0) {
        std::error_code ignored;
        sock.close(ignored);
        io.restart();
        io.run();
        return std::make_error_code(std::errc::timed_out);
      }
    }
    return result;
  }

  std::expected<std::string, std::error_code> next_element() {
    for (;;) {
      ElementSplitter::Item item;
      if (splitter.next(item)) {
        if (item.error) return std::unexpected(make_error_code(std::errc::protocol_error));
        return std::string(item.element);
      }
      bool done = false;
      std::error_code result;
      std::size_t got = 0;
      sock.async_read_some(asio::buffer(buf), [&](const std::error_code& ec, std::size_t n) {
        done = true;
        result = ec;
        got = n;
      });
      if (auto ec = wait(done, result)) return std::unexpected(ec);
      splitter.feed(std::string_view(buf.data(), got));
    }
  }

  std::error_code write(std::string_view text) {
    bool done = false;
    std::error_code result;
    asio::async_write(sock, asio::buffer(text), [&](const std::error_code& ec, std::size_t) {
      done = true;
      result = ec;
    });
    return wait(done, result);
  }
};

std::unexpected<std::error_code> failure(std::errc e, std::string* diagnostic, std::string text) {
  if (diagnostic) *diagnostic = std::move(text);
  return std::unexpected(std::make_error_code(e));
}

}  // namespace

std::expected<std::unique_ptr<SocketcandChannel>, std::error_code> SocketcandChannel::connect(
    asio::any_io_executor executor, const Clock& clock, const std::string& host, std::uint16_t port,
    const std::string& bus, ClientOptions options, std::string* diagnostic) {
  const std::string where = "socketcand://" + host + ":" + std::to_string(port) + "/" + bus;
  if (bus.empty() || bus.size() > max_bus_name)
    return failure(std::errc::invalid_argument, diagnostic, where + ": bus name must have 1..16 characters");
  Handshake h;
  h.deadline = std::chrono::steady_clock::now() +
               std::chrono::duration_cast<std::chrono::steady_clock::duration>(options.handshake_timeout);

  asio::ip::tcp::resolver resolver(h.io);
  std::error_code ec;
  const auto endpoints = resolver.resolve(host, std::to_string(port), ec);
  if (ec) return failure(std::errc::host_unreachable, diagnostic, where + ": cannot resolve host: " + ec.message());
  {
    bool done = false;
    std::error_code result;
    asio::async_connect(h.sock, endpoints, [&](const std::error_code& e, const asio::ip::tcp::endpoint&) {
      done = true;
      result = e;
    });
    if (auto e = h.wait(done, result)) {
      if (diagnostic)
        *diagnostic = where + ": connect failed: " + e.message() + " (is `hilbridge can hub` or socketcand running?)";
      return std::unexpected(e);
    }
  }
  auto expect = [&](std::string_view step, auto accept) -> std::expected<void, std::error_code> {
    auto el = h.next_element();
    if (!el)
      return failure(el.error() == std::errc::timed_out ? std::errc::timed_out : std::errc::protocol_error, diagnostic,
                     where + ": no reply to " + std::string(step) + ": " + el.error().message());
    auto parsed = parse_element(*el);
    if (parsed && accept(*parsed)) return {};
    if (parsed && std::holds_alternative<ErrorText>(*parsed))
      return failure(step == "open" ? std::errc::no_such_device : std::errc::protocol_error, diagnostic,
                     where + ": server refused " + std::string(step) + ": " + std::get<ErrorText>(*parsed).text);
    return failure(std::errc::protocol_error, diagnostic,
                   where + ": unexpected reply to " + std::string(step) + ": '" + *el + "'");
  };
  auto is_ok = [](const Element& e) { return std::holds_alternative<Ok>(e); };
  if (auto r = expect("connect (waiting for < hi >)", [](const Element& e) { return std::holds_alternative<Hi>(e); });
      !r)
    return std::unexpected(r.error());
  std::string out;
  format_open(out, bus);
  if (auto e = h.write(out)) return failure(std::errc::connection_reset, diagnostic, where + ": " + e.message());
  if (auto r = expect("open", is_ok); !r) return std::unexpected(r.error());
  if (auto e = h.write("< rawmode >"))
    return failure(std::errc::connection_reset, diagnostic, where + ": " + e.message());
  if (auto r = expect("rawmode", is_ok); !r) return std::unexpected(r.error());

  h.sock.set_option(asio::ip::tcp::no_delay(true), ec);
  // Hand the connected socket (and any frames already buffered) over to the caller's executor.
  const auto protocol = h.sock.local_endpoint(ec).protocol();
  const int fd = h.sock.release(ec);
  if (ec) return failure(std::errc::io_error, diagnostic, where + ": " + ec.message());
  auto impl = std::make_shared<Impl>(executor, clock, options);
  impl->socket.assign(protocol, fd, ec);
  if (ec) return failure(std::errc::io_error, diagnostic, where + ": " + ec.message());
  impl->splitter = std::move(h.splitter);
  std::unique_ptr<SocketcandChannel> ch(new SocketcandChannel(impl, where));
  asio::post(impl->socket.get_executor(), [impl] {
    impl->drain_elements();
    impl->read();
  });
  return ch;
}

SocketcandChannel::SocketcandChannel(std::shared_ptr<Impl> impl, std::string name)
    : impl_(std::move(impl)), name_(std::move(name)) {}

SocketcandChannel::~SocketcandChannel() {
  {
    std::lock_guard hl(impl_->handler_mu);
    impl_->handler = nullptr;
  }
  {
    std::lock_guard lock(impl_->mu);
    impl_->pending.clear();
  }
  // The socket belongs to the executor: close it there (safe from any thread).
  asio::post(impl_->socket.get_executor(), [impl = impl_] { impl->close(); });
}

std::error_code SocketcandChannel::send(const Frame& frame) {
  if (frame.rtr || frame.error) return std::make_error_code(std::errc::operation_not_supported);
  if (!is_valid(frame)) return std::make_error_code(std::errc::invalid_argument);
  std::lock_guard lock(impl_->mu);
  if (impl_->closed) return std::make_error_code(std::errc::network_down);
  if (impl_->pending.size() >= impl_->options.max_output_bytes) {
    ++impl_->stats.tx_dropped;
    return std::make_error_code(std::errc::no_buffer_space);
  }
  (void)format_send(impl_->pending, frame);
  ++impl_->stats.tx_frames;
  if (!impl_->writing) {
    impl_->writing = true;
    asio::post(impl_->socket.get_executor(), [impl = impl_] { impl->start_write(); });
  }
  return {};
}

void SocketcandChannel::set_receive_handler(ReceiveHandler handler) {
  std::lock_guard hl(impl_->handler_mu);
  impl_->handler = std::move(handler);
}

ChannelStats SocketcandChannel::stats() const noexcept {
  std::lock_guard lock(impl_->mu);
  return impl_->stats;
}

std::string SocketcandChannel::last_server_error() const {
  std::lock_guard lock(impl_->mu);
  return impl_->last_error;
}

bool SocketcandChannel::connected() const noexcept {
  return !impl_->is_closed();
}

std::size_t SocketcandChannel::tx_pending_bytes() const {
  std::lock_guard lock(impl_->mu);
  return impl_->pending.size() + (impl_->writing ? impl_->outbox.size() + 1 : 0);
}

}  // namespace hil::can::socketcand
