// SPDX-License-Identifier: MIT
#include "hil/can/io/socketcand_server.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <vector>

#include <asio/steady_timer.hpp>
#include <asio/write.hpp>

namespace hil::can::socketcand {

struct Server::Shared {
  const Clock& clock;
  BusOpener opener;
  ServerOptions options;
  ServerStats stats;
  std::vector<std::weak_ptr<Session>> sessions;
  bool closed = false;
};

class Server::Session : public std::enable_shared_from_this<Server::Session> {
 public:
  Session(asio::ip::tcp::socket socket, std::shared_ptr<Shared> shared)
      : socket_(std::move(socket)),
        shared_(std::move(shared)),
        hold_timer_(socket_.get_executor()),
        handshake_timer_(socket_.get_executor()),
        stall_timer_(socket_.get_executor()) {
    std::error_code ec;
    const auto ep = socket_.remote_endpoint(ec);
    peer_ = ec ? std::string("unknown") : ep.address().to_string() + ":" + std::to_string(ep.port());
    socket_.set_option(asio::ip::tcp::no_delay(true), ec);  // one frame per element: no Nagle delay
  }

  void start() {
    ++shared_->stats.active;
    // A client that opens no bus in time holds a slot for nothing: closed.
    handshake_timer_.expires_after(shared_->options.handshake_timeout);
    handshake_timer_.async_wait([self = shared_from_this()](const std::error_code& ec) {
      if (ec || self->closed_ || self->state_ != State::no_bus) return;
      ++self->shared_->stats.timed_out;
      self->close();
    });
    write(hi_element);
    read();
  }

  void close() {
    if (closed_) return;
    closed_ = true;
    --shared_->stats.active;
    hold_timer_.cancel();
    std::error_code ec;
    socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ec);
    socket_.close(ec);
    handshake_timer_.cancel();
    stall_timer_.cancel();
    channel_.reset();  // leave the bus now, not when the last handler lets go
  }

 private:
  enum class State { no_bus, bcm, raw };

  void read() {
    socket_.async_read_some(asio::buffer(rx_), [self = shared_from_this()](const std::error_code& ec, std::size_t n) {
      if (self->closed_) return;
      if (ec) {
        self->close();  // EOF or reset, possibly mid-element: the partial element is discarded
        return;
      }
      self->splitter_.feed(std::string_view(self->rx_.data(), n));
      ElementSplitter::Item item;
      while (!self->closed_ && self->splitter_.next(item)) {
        // The client speaks again after its `< ok >`: it has read it, so the held frames may follow.
        if (self->holding_) self->release_held();
        if (item.error) {
          self->protocol_error(item.error, "");
          continue;
        }
        self->handle(item.element);
      }
      // Back-pressure: a client whose replies pile up (it sends but does not read) is not read
      // from until they are written, so its queue stays bounded.
      if (self->closed_) return;
      if (self->pending_.size() >= self->shared_->options.max_output_bytes)
        self->read_paused_ = true;
      else
        self->read();
    });
  }

  void protocol_error(std::error_code ec, std::string_view element) {
    ++shared_->stats.protocol_errors;
    std::string text(ec.message());
    if (!element.empty()) {
      text += " in '";
      text.append(element.substr(0, 64));
      text += "'";
    }
    std::string out;
    format_error_text(out, text);
    write(out);
  }

  void handle(std::string_view text) {
    auto parsed = parse_element(text);
    if (!parsed) {
      protocol_error(parsed.error(), text);
      return;
    }
    const Element& e = *parsed;
    if (std::holds_alternative<Echo>(e)) {
      write("< echo >");
    } else if (const auto* open = std::get_if<Open>(&e)) {
      if (state_ != State::no_bus) {
        reply_error("a bus is already open in this session");
        return;
      }
      auto ch = shared_->opener(open->bus, peer_);
      if (!ch) {
        ++shared_->stats.bus_open_failures;
        std::string out;
        format_error_text(out, "could not open bus");  // the daemon's words; it then closes the connection
        write(out);
        close_after_write_ = true;
        return;
      }
      channel_ = std::move(*ch);
      channel_->set_receive_handler([this](const Frame& f, TimePoint t) { on_bus_frame(f, t); });
      state_ = State::bcm;
      handshake_timer_.cancel();
      write(ok_element);
    } else if (const auto* mode = std::get_if<SwitchMode>(&e)) {
      if (state_ == State::no_bus) {
        reply_error("open a bus first: < open NAME >");
      } else if (mode->mode == Mode::raw || mode->mode == Mode::bcm) {
        const bool joining = mode->mode == Mode::raw && state_ != State::raw;
        state_ = mode->mode == Mode::raw ? State::raw : State::bcm;
        write(ok_element);
        if (joining) hold_after_join();
      } else {
        reply_error("control and isotp modes are not supported by hilbridge");
      }
    } else if (const auto* send = std::get_if<Send>(&e)) {
      if (state_ == State::no_bus) {
        reply_error("open a bus first: < open NAME >");
        return;
      }
      if (auto ec = channel_->send(send->frame)) {
        ++shared_->stats.send_failures;
        reply_error("send failed: " + ec.message());
        return;
      }
      ++shared_->stats.frames_from_clients;
    } else if (const auto* other = std::get_if<Other>(&e)) {
      reply_error("command '" + other->command + "' is not supported by hilbridge (raw mode only)");
    } else {
      reply_error("unexpected element from a client");
    }
  }

  void reply_error(std::string_view text) {
    ++shared_->stats.protocol_errors;
    std::string out;
    format_error_text(out, text);
    write(out);
  }

  void on_bus_frame(const Frame& f, TimePoint t) {
    if (closed_ || state_ != State::raw) return;
    if (f.rtr) {
      ++shared_->stats.rtr_not_forwarded;
      return;
    }
    std::string& out = holding_ ? held_ : pending_;
    if (out.size() >= shared_->options.max_output_bytes) {
      ++shared_->stats.dropped_slow_client;
      return;
    }
    if (format_rx_frame(out, f, shared_->options.to_wire_time(t))) {
      ++shared_->stats.frames_to_clients;
      if (holding_) ++shared_->stats.held_at_join;
    }
    note_queue();
    if (!holding_) flush();
  }

  /// The client has joined (its `< ok >` is queued): frames from now on are its own. Hold them
  /// until it has read that `< ok >` (see ServerOptions::join_hold).
  void hold_after_join() {
    if (shared_->options.join_hold <= Duration{0}) return;
    holding_ = true;
    hold_timer_.expires_after(shared_->options.join_hold);
    hold_timer_.async_wait([self = shared_from_this()](const std::error_code& ec) {
      if (ec || self->closed_ || !self->holding_) return;
      self->release_held();
    });
  }

  void release_held() {
    holding_ = false;
    hold_timer_.cancel();
    pending_.append(held_);
    held_.clear();
    note_queue();
    flush();
  }

  void write(std::string_view text) {
    pending_.append(text);
    note_queue();
    flush();
  }

  void note_queue() {
    auto& peak = shared_->stats.peak_queued_bytes;
    peak = std::max<std::uint64_t>(peak, pending_.size() + outbox_.size() + held_.size());
  }

  void flush() {
    if (writing_ || closed_ || pending_.empty()) return;
    writing_ = true;
    outbox_.swap(pending_);
    pending_.clear();
    // A write that does not complete in time: the client does not read (or is gone without a
    // reset, half-open). It is closed instead of holding its slot and its queue forever.
    stall_timer_.expires_after(shared_->options.write_stall_timeout);
    stall_timer_.async_wait([self = shared_from_this()](const std::error_code& ec) {
      if (ec || self->closed_ || !self->writing_) return;
      ++self->shared_->stats.timed_out;
      self->close();
    });
    asio::async_write(socket_, asio::buffer(outbox_),
                      [self = shared_from_this()](const std::error_code& ec, std::size_t) {
                        self->writing_ = false;
                        self->outbox_.clear();
                        self->stall_timer_.cancel();
                        if (self->closed_) return;
                        if (ec) {
                          self->close();
                          return;
                        }
                        if (self->read_paused_ && self->pending_.size() < self->shared_->options.max_output_bytes) {
                          self->read_paused_ = false;
                          self->read();
                        }
                        if (self->close_after_write_ && self->pending_.empty()) {
                          self->close();
                          return;
                        }
                        self->flush();
                      });
  }

  asio::ip::tcp::socket socket_;
  std::shared_ptr<Shared> shared_;
  std::string peer_;
  std::array<char, 4096> rx_{};
  ElementSplitter splitter_;
  State state_ = State::no_bus;
  asio::steady_timer hold_timer_;
  bool holding_ = false;
  std::string held_;  ///< frames for a client that has not yet read its raw-mode `< ok >`
  std::unique_ptr<Channel> channel_;
  std::string pending_;
  std::string outbox_;
  bool writing_ = false;
  bool closed_ = false;
  bool close_after_write_ = false;
  bool read_paused_ = false;
  asio::steady_timer handshake_timer_;
  asio::steady_timer stall_timer_;
};

Server::Server(asio::any_io_executor executor, const Clock& clock, BusOpener opener, ServerOptions options)
    : shared_(std::make_shared<Shared>(Shared{clock, std::move(opener), std::move(options), {}, {}, false})),
      acceptor_(executor),
      accept_timer_(executor) {
  if (!shared_->options.to_wire_time) {
    const auto offset = std::chrono::duration_cast<Duration>(std::chrono::system_clock::now().time_since_epoch()) -
                        clock.now().time_since_epoch();
    shared_->options.to_wire_time = [offset](TimePoint t) {
      const auto ns = (t.time_since_epoch() + offset).count();
      return Timestamp{ns / 1'000'000'000, static_cast<std::uint32_t>((ns % 1'000'000'000) / 1000)};
    };
  }
}

Server::~Server() {
  close();
}

std::error_code Server::listen(const asio::ip::tcp::endpoint& endpoint) {
  std::error_code ec;
  acceptor_.open(endpoint.protocol(), ec);
  if (ec) return ec;
  acceptor_.set_option(asio::socket_base::reuse_address(true), ec);
  acceptor_.bind(endpoint, ec);
  if (ec) {
    acceptor_.close();
    return ec;
  }
  acceptor_.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    acceptor_.close();
    return ec;
  }
  shared_->closed = false;
  accept();
  return {};
}

asio::ip::tcp::endpoint Server::local_endpoint() const {
  std::error_code ec;
  return acceptor_.local_endpoint(ec);
}

const ServerStats& Server::stats() const noexcept {
  return shared_->stats;
}

void Server::accept() {
  acceptor_.async_accept([this, shared = shared_](const std::error_code& ec, asio::ip::tcp::socket socket) {
    if (shared->closed || ec == asio::error::operation_aborted) return;  // `this` may be gone
    if (ec) {
      // Out of file descriptors (EMFILE/ENFILE) or another accept error: the pending connection
      // stays in the backlog, so accepting again at once would spin. Back off, growing to the max.
      ++shared->stats.accept_errors;
      const auto& o = shared->options;
      accept_backoff_ =
          accept_backoff_ == Duration{} ? o.accept_backoff_min : std::min(2 * accept_backoff_, o.accept_backoff_max);
      accept_timer_.expires_after(accept_backoff_);
      accept_timer_.async_wait([this, shared](const std::error_code& e) {
        if (!e && !shared->closed) accept();
      });
      return;
    }
    accept_backoff_ = {};
    {
      std::erase_if(shared->sessions, [](const std::weak_ptr<Session>& w) { return w.expired(); });
      if (shared->stats.active >= shared->options.max_clients) {
        ++shared->stats.refused;
        std::error_code ignored;
        socket.write_some(asio::buffer(std::string_view("< error too many clients >")), ignored);
        socket.close(ignored);
      } else {
        ++shared->stats.accepted;
        auto session = std::make_shared<Session>(std::move(socket), shared);
        shared->sessions.push_back(session);
        session->start();
      }
    }
    accept();
  });
}

void Server::adopt(asio::ip::tcp::socket socket) {
  std::erase_if(shared_->sessions, [](const std::weak_ptr<Session>& w) { return w.expired(); });
  if (shared_->closed || shared_->stats.active >= shared_->options.max_clients) {
    ++shared_->stats.refused;
    std::error_code ignored;
    socket.close(ignored);
    return;
  }
  ++shared_->stats.accepted;
  auto session = std::make_shared<Session>(std::move(socket), shared_);
  shared_->sessions.push_back(session);
  session->start();
}

void Server::close() {
  shared_->closed = true;
  std::error_code ec;
  acceptor_.close(ec);
  accept_timer_.cancel();
  for (auto& w : shared_->sessions)
    if (auto s = w.lock()) s->close();
  shared_->sessions.clear();
}

}  // namespace hil::can::socketcand
