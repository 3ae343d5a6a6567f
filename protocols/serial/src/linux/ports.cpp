// SPDX-License-Identifier: MIT
#include "hil/serial/linux/ports.hpp"

#include <fcntl.h>
#include <linux/serial.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <termios.h>
#include <unistd.h>
#include <thread>

#include <fmt/format.h>
#include <asio.hpp>
#include <cstdlib>
#include <utility>

namespace hil::serial::linux_io {

int set_any_baud(int fd, unsigned baud) noexcept;  // termios2_baud.cpp

namespace {

std::error_code map_error(const std::error_code& ec) {
  if (ec == asio::error::eof || ec == std::errc::io_error || ec == asio::error::connection_reset ||
      ec == asio::error::broken_pipe)
    return LineError::closed;
  return ec;
}

template <class Stream>
class AsioLine final : public RawLine {
 public:
  template <class... A>
  explicit AsioLine(A&&... a) : s_(io_, std::forward<A>(a)...) {}
  asio::io_context& io() { return io_; }
  Stream& stream() { return s_; }

  ReadResult read_some(std::span<std::uint8_t> buf, Duration timeout) override {
    ReadResult r;
    bool done = false;
    s_.async_read_some(asio::buffer(buf.data(), buf.size()), [&](const std::error_code& ec, std::size_t n) {
      done = true;
      r.size = n;
      if (ec && ec != asio::error::operation_aborted) r.error = map_error(ec);
    });
    run(timeout, done);
    if (r.size == 0 && !r.error) r.error = LineError::timeout;
    return r;
  }

  std::error_code write(std::span<const std::uint8_t> data, Duration timeout) override {
    std::error_code result;
    bool done = false;
    asio::async_write(s_, asio::buffer(data.data(), data.size()), [&](const std::error_code& ec, std::size_t) {
      done = true;
      if (ec == asio::error::operation_aborted)
        result = LineError::cts_stalled;
      else if (ec)
        result = map_error(ec);
    });
    run(timeout, done);
    return result;
  }

  std::uint64_t overrun_count() override {
    serial_icounter_struct c{};
    if (::ioctl(s_.native_handle(), TIOCGICOUNT, &c) != 0) return 0;
    return static_cast<std::uint64_t>(c.overrun) + static_cast<std::uint64_t>(c.buf_overrun);
  }
  bool dsr() override {
    int bits = 0;
    if (::ioctl(s_.native_handle(), TIOCMGET, &bits) != 0) return true;  // no modem lines: not used
    return (bits & TIOCM_DSR) != 0;
  }
  void send_break(Duration d) override {
    (void)::ioctl(s_.native_handle(), TIOCSBRK);
    // A break is a line condition, not a wait of the protocol: real time is intended here.
    io_.restart();
    asio::steady_timer t(io_, d);
    t.wait();
    (void)::ioctl(s_.native_handle(), TIOCCBRK);
  }

 private:
  void run(Duration timeout, const bool& done) {
    io_.restart();
    if (timeout <= Duration::zero())
      io_.poll();
    else
      io_.run_for(timeout);
    if (!done) {
      std::error_code ignored;
      s_.cancel(ignored);
      io_.restart();
      io_.run();
    }
  }

  asio::io_context io_;
  Stream s_;
};

using Descriptor = asio::posix::stream_descriptor;

bool is_pty(int fd) {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISCHR(st.st_mode)) return false;
  const unsigned maj = major(st.st_rdev);
  return maj >= 136 && maj <= 143;  // Unix98 pty slaves
}

std::error_code errno_code() {
  return {errno, std::system_category()};
}

/// Raw mode + the character format. Returns an error text or "".
std::string configure(int fd, const LineFormat& f, bool pty) {
  termios t{};
  if (::tcgetattr(fd, &t) != 0) return fmt::format("tcgetattr failed: {}", errno_code().message());
  ::cfmakeraw(&t);
  t.c_cflag |= CLOCAL | CREAD;
  t.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | PARODD | CSTOPB | CRTSCTS);
  if (!pty) {
    t.c_cflag |= f.data_bits == 7 ? CS7 : CS8;
    if (f.parity != Parity::none) {
      t.c_cflag |= PARENB;
      if (f.parity == Parity::odd) t.c_cflag |= PARODD;
      // Report bad characters in-band (0xFF 0x00 c) instead of dropping or passing them.
      t.c_iflag |= INPCK | PARMRK;
      t.c_iflag &= ~static_cast<tcflag_t>(IGNPAR | ISTRIP);
    }
    if (f.stop_bits == StopBits::two) t.c_cflag |= CSTOPB;
    if (f.stop_bits == StopBits::one_and_half)
      return "1.5 stop bits cannot be set through Linux termios (CSTOPB gives 2); use 2 stop bits, which a "
             "receiver expecting 1.5 accepts";
    if (f.flow == FlowControl::rts_cts) t.c_cflag |= CRTSCTS;
  } else {
    t.c_cflag |= CS8;  // a pty carries 8-bit bytes; parity is done in software
  }
  // XON/XOFF is handled in SerialStream (configurable, parity-carrying bytes), not by IXON.
  t.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  t.c_cc[VMIN] = 1;  // with VMIN = 0 poll() reports a tty readable while it is empty
  t.c_cc[VTIME] = 0;
  if (::tcsetattr(fd, TCSANOW, &t) != 0) return fmt::format("tcsetattr failed: {}", errno_code().message());
  if (!pty) {
    if (int e = set_any_baud(fd, f.baud); e != 0)
      return fmt::format("setting {} baud failed: {}", f.baud, std::error_code(e, std::system_category()).message());
    if (f.use_dtr_dsr) {
      int dtr = TIOCM_DTR;
      (void)::ioctl(fd, TIOCMBIS, &dtr);
    }
  }
  return {};
}

}  // namespace

std::expected<std::unique_ptr<SerialStream>, OpenError> open_tty(const std::string& path, const LineFormat& format,
                                                                 const Clock& clock) {
  if (auto v = validate(format); !v)
    return std::unexpected(OpenError{std::make_error_code(std::errc::invalid_argument), v.error().message});
  auto line = std::make_unique<AsioLine<asio::serial_port>>();
  std::error_code ec;
  line->stream().open(path, ec);
  if (ec)
    return std::unexpected(OpenError{ec, fmt::format("cannot open serial port {}: {} (does it exist? are you in group "
                                                     "dialout?)",
                                                     path, ec.message())});
  const int fd = line->stream().native_handle();
  const bool pty = is_pty(fd);
  if (auto err = configure(fd, format, pty); !err.empty())
    return std::unexpected(
        OpenError{std::make_error_code(std::errc::invalid_argument), fmt::format("{}: {}", path, err)});
  Discipline d;
  d.software_parity = pty;
  d.parmrk = !pty && format.parity != Parity::none;
  return std::make_unique<SerialStream>(std::move(line), format, d, clock);
}

std::unique_ptr<RawLine> adopt_fd(int fd) {
  return std::make_unique<AsioLine<Descriptor>>(fd);
}

std::expected<PtyEndpoint, OpenError> PtyEndpoint::create() {
  PtyEndpoint p;
  p.master_fd_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (p.master_fd_ < 0 || ::grantpt(p.master_fd_) != 0 || ::unlockpt(p.master_fd_) != 0)
    return std::unexpected(
        OpenError{errno_code(), fmt::format("cannot create a pseudo-terminal: {}", errno_code().message())});
  char name[128];
  if (::ptsname_r(p.master_fd_, name, sizeof name) != 0)
    return std::unexpected(OpenError{errno_code(), "ptsname failed"});
  p.slave_path_ = name;
  p.slave_keepalive_fd_ = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (p.slave_keepalive_fd_ < 0)
    return std::unexpected(
        OpenError{errno_code(), fmt::format("cannot open pty slave {}: {}", name, errno_code().message())});
  // The line discipline is shared by both ends: make it raw now so nothing is echoed or
  // translated before a client configures it.
  LineFormat raw8;
  if (auto err = configure(p.slave_keepalive_fd_, raw8, true); !err.empty())
    return std::unexpected(OpenError{std::make_error_code(std::errc::io_error), err});
  return p;
}

PtyEndpoint::PtyEndpoint(PtyEndpoint&& o) noexcept
    : master_fd_(std::exchange(o.master_fd_, -1)),
      slave_keepalive_fd_(std::exchange(o.slave_keepalive_fd_, -1)),
      slave_path_(std::move(o.slave_path_)) {}

PtyEndpoint& PtyEndpoint::operator=(PtyEndpoint&& o) noexcept {
  if (this != &o) {
    this->~PtyEndpoint();
    new (this) PtyEndpoint(std::move(o));
  }
  return *this;
}

PtyEndpoint::~PtyEndpoint() {
  if (master_fd_ >= 0) ::close(master_fd_);
  if (slave_keepalive_fd_ >= 0) ::close(slave_keepalive_fd_);
}

std::unique_ptr<RawLine> PtyEndpoint::take_master() {
  const int fd = std::exchange(master_fd_, -1);
  return fd < 0 ? nullptr : adopt_fd(fd);
}

std::expected<std::unique_ptr<RawLine>, OpenError> connect_tcp(const std::string& host, std::uint16_t port,
                                                               Duration timeout) {
  auto line = std::make_unique<AsioLine<asio::ip::tcp::socket>>();
  std::error_code ec;
  asio::ip::tcp::resolver resolver(line->io());
  const auto endpoints = resolver.resolve(host, std::to_string(port), ec);
  if (ec) return std::unexpected(OpenError{ec, fmt::format("cannot resolve {}: {}", host, ec.message())});
  bool done = false;
  std::error_code result;
  asio::async_connect(line->stream(), endpoints, [&](const std::error_code& e, const auto&) {
    done = true;
    result = e;
  });
  line->io().run_for(timeout);
  if (!done) {
    line->stream().close(ec);
    return std::unexpected(OpenError{LineError::timeout, fmt::format("connecting to {}:{} timed out", host, port)});
  }
  if (result)
    return std::unexpected(OpenError{result, fmt::format("cannot connect to {}:{}: {}", host, port, result.message())});
  line->stream().set_option(asio::ip::tcp::no_delay(true), ec);
  return line;
}

namespace {
class AsioTcpListener final : public TcpListener {
 public:
  AsioTcpListener() : acceptor_(io_) {}
  std::error_code open(const std::string& addr, std::uint16_t port) {
    std::error_code ec;
    const auto a = asio::ip::make_address(addr, ec);
    if (ec) return ec;
    asio::ip::tcp::endpoint ep(a, port);
    acceptor_.open(ep.protocol(), ec);
    if (!ec) acceptor_.set_option(asio::ip::tcp::acceptor::reuse_address(true), ec);
    if (!ec) acceptor_.bind(ep, ec);
    if (!ec) acceptor_.listen(1, ec);
    return ec;
  }
  std::uint16_t port() const noexcept override {
    std::error_code ec;
    return acceptor_.local_endpoint(ec).port();
  }
  std::unique_ptr<RawLine> accept(Duration timeout) override {
    const auto start = std::chrono::steady_clock::now();
    // The line's own io_context needs descriptors (epoll, eventfd): made first, so that when
    // there are none the client stays in the backlog, and this counts as a failed accept (Asio
    // throws; an exception here would end the emulator's line thread and the emulator).
    std::unique_ptr<AsioLine<asio::ip::tcp::socket>> line;
    try {
      line = std::make_unique<AsioLine<asio::ip::tcp::socket>>();
    } catch (const std::system_error& e) {
      ++accept_errors_;
      last_accept_error_ = e.code();
      std::this_thread::sleep_until(start + timeout);
      return nullptr;
    }
    std::error_code ec;
    // Accept on our own io_context into a socket, then move the native handle into the line.
    asio::ip::tcp::socket sock(io_);
    bool done = false;
    acceptor_.async_accept(sock, [&](const std::error_code& e) {
      done = true;
      ec = e;
    });
    io_.restart();
    io_.run_for(timeout);
    if (!done) {
      acceptor_.cancel(ec);
      io_.restart();
      io_.run();
      return nullptr;
    }
    if (ec) {
      // Out of file descriptors (EMFILE) or another accept error: the client stays in the
      // backlog and would fail again at once. A failed accept takes the whole timeout, so a
      // caller that loops on accept() backs off instead of spinning.
      ++accept_errors_;
      last_accept_error_ = ec;
      std::this_thread::sleep_until(start + timeout);
      return nullptr;
    }
    sock.set_option(asio::ip::tcp::no_delay(true), ec);
    const auto proto = sock.local_endpoint(ec).protocol();
    line->stream().assign(proto, sock.release(ec), ec);
    if (ec) return nullptr;
    return line;
  }
  std::uint64_t accept_errors() const noexcept override { return accept_errors_; }
  std::error_code last_accept_error() const noexcept override { return last_accept_error_; }

 private:
  asio::io_context io_;
  asio::ip::tcp::acceptor acceptor_;
  std::uint64_t accept_errors_ = 0;
  std::error_code last_accept_error_;
};
}  // namespace

std::expected<std::unique_ptr<TcpListener>, OpenError> TcpListener::create(const std::string& bind_address,
                                                                           std::uint16_t port) {
  auto l = std::make_unique<AsioTcpListener>();
  if (auto ec = l->open(bind_address, port))
    return std::unexpected(OpenError{ec, fmt::format("cannot listen on {}:{}: {}", bind_address, port, ec.message())});
  return l;
}

}  // namespace hil::serial::linux_io
