// SPDX-License-Identifier: MIT
#include "hil/can/linux/socketcan_channel.hpp"

#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <deque>
#include <mutex>
#include <vector>

#include <asio/posix/stream_descriptor.hpp>
#include <asio/post.hpp>
#include <asio/steady_timer.hpp>

namespace hil::can::socketcan {

namespace {

can_frame to_kernel(const Frame& f) noexcept {
  can_frame k{};
  k.can_id = to_socketcan_id(f);
  k.can_dlc = f.dlc > 8 ? std::uint8_t{8} : f.dlc;
  std::memcpy(k.data, f.data.data(), 8);
  return k;
}

Frame from_kernel(const can_frame& k) noexcept {
  Frame f;
  set_socketcan_id(f, k.can_id);
  f.dlc = k.can_dlc > 8 ? std::uint8_t{8} : k.can_dlc;
  std::memcpy(f.data.data(), k.data, 8);
  if (f.rtr) f.data = {};
  return f;
}

std::error_code errno_code(int e) noexcept {
  return {e, std::generic_category()};
}

std::error_code apply_options(int fd, const SocketCanOptions& o) {
  const int own = o.receive_own ? 1 : 0;
  const int loop = o.loopback ? 1 : 0;
  const int one = 1;
  if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_LOOPBACK, &loop, sizeof loop) != 0) return errno_code(errno);
  if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof own) != 0) return errno_code(errno);
  std::vector<can_filter> filters;
  for (const auto& f : o.filters.filters)
    filters.push_back(can_filter{f.inverted ? (f.id | CAN_INV_FILTER) : f.id, f.mask});
  if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters.empty() ? nullptr : filters.data(),
                   static_cast<socklen_t>(filters.size() * sizeof(can_filter))) != 0)
    return errno_code(errno);
  if (o.filters.join) {
    if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_JOIN_FILTERS, &one, sizeof one) != 0) return errno_code(errno);
  }
  const can_err_mask_t err_mask = o.filters.error_mask & CAN_ERR_MASK;
  if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) != 0) return errno_code(errno);
  (void)::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one);  // best effort: drop counter
  if (o.sndbuf_bytes > 0 && ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &o.sndbuf_bytes, sizeof o.sndbuf_bytes) != 0)
    return errno_code(errno);
  return {};
}

}  // namespace

struct SocketCanChannel::Impl : std::enable_shared_from_this<SocketCanChannel::Impl> {
  Impl(asio::any_io_executor ex, const Clock& c, int fd, SocketCanOptions o)
      : desc(ex, fd), timer(ex), clock(c), options(std::move(o)), raw_fd(fd) {
    if (!options.write_fn) options.write_fn = [](int f, const void* d, std::size_t n) { return ::write(f, d, n); };
  }

  asio::posix::stream_descriptor desc;
  asio::steady_timer timer;
  const Clock& clock;
  SocketCanOptions options;
  int raw_fd;
  // Held while a handler runs (see SocketcandChannel): destruction from any thread is safe.
  std::recursive_mutex handler_mu;
  ReceiveHandler handler;
  std::function<void(BusState)> state_handler;

  mutable std::mutex mu;  // guards the fields below
  std::deque<can_frame> queue;
  bool waiting = false;  // an async wait/timer for the queue is pending
  Duration backoff{0};
  bool closed = false;
  SocketCanStats stats;

  enum class WriteResult { written, retry_writable, retry_later, failed };

  WriteResult write_one(const can_frame& k) {
    const ssize_t n = options.write_fn(raw_fd, &k, sizeof k);
    if (n == static_cast<ssize_t>(sizeof k)) return WriteResult::written;
    const int e = n < 0 ? errno : EIO;
    if (e == EAGAIN || e == EWOULDBLOCK) {
      ++stats.eagain;
      return WriteResult::retry_writable;
    }
    if (e == ENOBUFS) {
      ++stats.enobufs;
      return WriteResult::retry_later;
    }
    ++stats.tx_errors;
    stats.last_error = errno_code(e);
    return WriteResult::failed;
  }

  /// Caller holds `mu`. Writes queued frames until the kernel pushes back, then arms a wait.
  void drain_locked() {
    while (!queue.empty() && !closed) {
      switch (write_one(queue.front())) {
        case WriteResult::written:
          ++stats.channel.tx_frames;
          queue.pop_front();
          backoff = Duration{0};
          break;
        case WriteResult::failed:
          queue.pop_front();  // counted in tx_errors; later frames may still go
          break;
        case WriteResult::retry_writable:
          arm_locked(false);
          return;
        case WriteResult::retry_later:
          arm_locked(true);
          return;
      }
    }
  }

  /// Caller holds `mu` and runs on the executor.
  void arm_locked(bool enobufs) {
    if (waiting) return;
    waiting = true;
    start_wait(enobufs);
  }

  /// From send() on any thread: the descriptor and timer may only be touched on the executor.
  void arm_from_any_thread_locked(bool enobufs) {
    if (waiting) return;
    waiting = true;
    asio::post(desc.get_executor(), [self = shared_from_this(), enobufs] {
      std::lock_guard lock(self->mu);
      if (self->closed) return;
      self->start_wait(enobufs);
    });
  }

  void start_wait(bool enobufs) {
    auto self = shared_from_this();
    if (!enobufs) {
      desc.async_wait(asio::posix::stream_descriptor::wait_write,
                      [self](const std::error_code& ec) { self->on_retry(ec); });
      return;
    }
    backoff = backoff == Duration{0} ? options.enobufs_backoff_min : std::min(backoff * 2, options.enobufs_backoff_max);
    timer.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(backoff));
    timer.async_wait([self](const std::error_code& ec) { self->on_retry(ec); });
  }

  void on_retry(const std::error_code& ec) {
    std::lock_guard lock(mu);
    waiting = false;
    if (ec || closed) return;
    drain_locked();
  }

  void read() {
    desc.async_wait(asio::posix::stream_descriptor::wait_read, [self = shared_from_this()](const std::error_code& ec) {
      if (ec) return;
      if (self->read_available()) self->read();
    });
  }

  /// Read everything queued (non-blocking). Returns false when the socket failed.
  bool read_available() {
    for (int batch = 0; batch < 256; ++batch) {
      can_frame k{};
      iovec iov{&k, sizeof k};
      alignas(cmsghdr) char control[CMSG_SPACE(sizeof(std::uint32_t))];
      msghdr msg{};
      msg.msg_iov = &iov;
      msg.msg_iovlen = 1;
      msg.msg_control = control;
      msg.msg_controllen = sizeof control;
      const ssize_t n = ::recvmsg(raw_fd, &msg, MSG_DONTWAIT);
      if (n < 0) {
        if (errno == EAGAIN || errno == EWOULDBLOCK) return !is_closed();
        if (errno == EINTR) continue;
        std::lock_guard lock(mu);
        stats.last_error = errno_code(errno);
        return false;
      }
      if (n == 0) return false;  // peer closed (socketpair)
      std::uint32_t drops = 0;
      bool have_drops = false;
      for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
          std::memcpy(&drops, CMSG_DATA(c), sizeof drops);
          have_drops = true;
        }
      }
      if (n != static_cast<ssize_t>(sizeof k)) {
        std::lock_guard lock(mu);
        ++stats.short_reads;
        continue;
      }
      const Frame f = from_kernel(k);
      std::optional<BusState> new_state;
      {
        std::lock_guard lock(mu);
        if (have_drops) stats.channel.rx_overruns = drops;  // cumulative count from the kernel
        if (f.error) {
          ++stats.channel.error_frames;
          const auto info = decode_error_frame(f);
          if (info.rx_overflow) ++stats.controller_rx_overflows;
          if (info.tx_overflow) ++stats.controller_tx_overflows;
          if (info.no_ack) ++stats.no_ack;
          if (info.bus_error || info.protocol_violation) ++stats.bus_errors;
          if (info.state && *info.state != stats.state) {
            stats.state = *info.state;
            stats.channel.bus_off = stats.state == BusState::bus_off;
            new_state = info.state;
          }
        } else {
          ++stats.channel.rx_frames;
        }
      }
      std::lock_guard hl(handler_mu);
      if (new_state && state_handler) state_handler(*new_state);
      if (f.error && !options.deliver_error_frames) continue;
      if (handler) handler(f, clock.now());
      if (is_closed()) return false;
    }
    return true;  // yield to other handlers; continue on the next wait
  }

  bool is_closed() const {
    std::lock_guard lock(mu);
    return closed;
  }

  /// Executor only (the descriptor and timer belong to it).
  void close() {
    std::lock_guard lock(mu);
    closed = true;
    queue.clear();
    std::error_code ec;
    timer.cancel();
    desc.cancel(ec);
    desc.close(ec);
  }
};

std::expected<std::unique_ptr<SocketCanChannel>, std::error_code> SocketCanChannel::open(asio::any_io_executor executor,
                                                                                         const Clock& clock,
                                                                                         const std::string& interface,
                                                                                         SocketCanOptions options,
                                                                                         std::string* diagnostic) {
  auto fail = [&](std::error_code ec, const std::string& what) -> std::unexpected<std::error_code> {
    if (diagnostic) *diagnostic = "SocketCAN " + interface + ": " + what + " (" + ec.message() + ")";
    return std::unexpected(ec);
  };
  if (interface.empty() || interface.size() >= IFNAMSIZ)
    return fail(std::make_error_code(std::errc::invalid_argument), "interface names have 1..15 characters");
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    const int e = errno;
    if (e == EAFNOSUPPORT || e == EPROTONOSUPPORT)
      return fail(errno_code(e),
                  "this kernel has no CAN support; load it with `modprobe can-raw` (and `modprobe vcan` for virtual "
                  "interfaces)");
    return fail(errno_code(e), "cannot create a CAN_RAW socket");
  }
  const unsigned index = ::if_nametoindex(interface.c_str());
  if (index == 0) {
    ::close(fd);
    return fail(std::make_error_code(std::errc::no_such_device),
                "no such interface; create a virtual one with `ip link add dev " + interface +
                    " type vcan && ip link set up " + interface + "`");
  }
  if (auto ec = apply_options(fd, options)) {
    ::close(fd);
    return fail(ec, "cannot configure the socket");
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(index);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    const int e = errno;
    ::close(fd);
    return fail(errno_code(e), "cannot bind to the interface");
  }
  return adopt(std::move(executor), clock, fd, interface, std::move(options), false);
}

std::expected<std::unique_ptr<SocketCanChannel>, std::error_code> SocketCanChannel::adopt(
    asio::any_io_executor executor, const Clock& clock, int fd, std::string name, SocketCanOptions options,
    bool apply_socket_options) {
  if (fd < 0) return std::unexpected(std::make_error_code(std::errc::bad_file_descriptor));
  if (apply_socket_options) {
    if (auto ec = apply_options(fd, options)) {
      ::close(fd);
      return std::unexpected(ec);
    }
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) (void)::fcntl(fd, F_SETFL, flags | O_NONBLOCK);
  auto impl = std::make_shared<Impl>(executor, clock, fd, std::move(options));
  std::unique_ptr<SocketCanChannel> ch(new SocketCanChannel(impl, std::move(name)));
  asio::post(impl->desc.get_executor(), [impl] { impl->read(); });
  return ch;
}

SocketCanChannel::SocketCanChannel(std::shared_ptr<Impl> impl, std::string name)
    : impl_(std::move(impl)), name_(std::move(name)) {}

SocketCanChannel::~SocketCanChannel() {
  {
    std::lock_guard hl(impl_->handler_mu);
    impl_->handler = nullptr;
    impl_->state_handler = nullptr;
  }
  {
    std::lock_guard lock(impl_->mu);
    impl_->closed = true;  // no more sends; the queue is dropped
    impl_->queue.clear();
  }
  asio::post(impl_->desc.get_executor(), [impl = impl_] { impl->close(); });
}

std::error_code SocketCanChannel::send(const Frame& frame) {
  if (!is_valid(frame)) return std::make_error_code(std::errc::invalid_argument);
  const can_frame k = to_kernel(frame);
  std::lock_guard lock(impl_->mu);
  if (impl_->closed) return std::make_error_code(std::errc::network_down);
  if (impl_->stats.state == BusState::bus_off) return std::make_error_code(std::errc::network_down);
  if (impl_->queue.empty()) {
    const auto r = impl_->write_one(k);
    switch (r) {
      case Impl::WriteResult::written:
        ++impl_->stats.channel.tx_frames;
        return {};
      case Impl::WriteResult::failed:
        return impl_->stats.last_error;  // e.g. ENETDOWN == std::errc::network_down
      case Impl::WriteResult::retry_writable:
      case Impl::WriteResult::retry_later: {
        const bool enobufs = r == Impl::WriteResult::retry_later;
        impl_->queue.push_back(k);
        impl_->stats.tx_queue_high_water = std::max<std::uint64_t>(impl_->stats.tx_queue_high_water, 1);
        impl_->arm_from_any_thread_locked(enobufs);
        return {};
      }
    }
  }
  if (impl_->queue.size() >= impl_->options.tx_queue_capacity) {
    ++impl_->stats.channel.tx_dropped;
    return std::make_error_code(std::errc::no_buffer_space);
  }
  impl_->queue.push_back(k);
  impl_->stats.tx_queue_high_water = std::max<std::uint64_t>(impl_->stats.tx_queue_high_water, impl_->queue.size());
  return {};
}

void SocketCanChannel::set_receive_handler(ReceiveHandler handler) {
  std::lock_guard hl(impl_->handler_mu);
  impl_->handler = std::move(handler);
}
void SocketCanChannel::set_state_handler(std::function<void(BusState)> handler) {
  std::lock_guard hl(impl_->handler_mu);
  impl_->state_handler = std::move(handler);
}

ChannelStats SocketCanChannel::stats() const noexcept {
  std::lock_guard lock(impl_->mu);
  return impl_->stats.channel;
}

SocketCanStats SocketCanChannel::socketcan_stats() const {
  std::lock_guard lock(impl_->mu);
  return impl_->stats;
}

std::size_t SocketCanChannel::tx_queued() const {
  std::lock_guard lock(impl_->mu);
  return impl_->queue.size();
}

}  // namespace hil::can::socketcan
