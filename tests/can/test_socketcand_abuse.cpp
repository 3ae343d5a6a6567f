// SPDX-License-Identifier: MIT
// The socketcand hub under abuse, each case followed by a well-behaved client that must still be
// served: a client that floods without reading (bounded queue, then closed when its writes stall),
// idle clients that never open a bus (closed after the handshake timeout, their slots freed), and
// accept failing for lack of file descriptors (a back-off, not a busy loop).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "hil/can/io/socketcand_channel.hpp"
#include "hub_fixture.hpp"

namespace can = hil::can;
namespace sc = hil::can::socketcand;
using can::test::Hub;
using can::test::Inbox;
using namespace std::chrono_literals;

namespace {

/// A plain TCP client on a file descriptor (no Asio: the accept test counts descriptors).
class Peer {
 public:
  explicit Peer(std::uint16_t port, bool connect_now = true) : fd_(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0)) {
    EXPECT_GE(fd_, 0);
    if (connect_now) connect(port);
  }
  ~Peer() { close(); }
  Peer(const Peer&) = delete;
  Peer& operator=(const Peer&) = delete;
  void connect(std::uint16_t port) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::connect(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a), 0) << std::strerror(errno);
  }
  /// Everything that arrives within `wait` (stops early once `until` was seen).
  std::string read_for(std::chrono::milliseconds wait, std::string_view until = {}) {
    std::string got;
    const auto end = std::chrono::steady_clock::now() + wait;
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd_, POLLIN, 0};
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
      if (::poll(&p, 1, static_cast<int>(std::max<long>(1, left.count()))) <= 0) continue;
      char buf[4096];
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) break;
      got.append(buf, static_cast<std::size_t>(n));
      if (!until.empty() && got.find(until) != std::string::npos) break;
    }
    return got;
  }
  /// Send without blocking until `total` bytes are out or nothing more goes out for `stall`.
  std::size_t flood(const std::string& chunk, std::size_t total, std::chrono::milliseconds stall) {
    std::size_t sent = 0;
    auto last = std::chrono::steady_clock::now();
    while (sent < total && std::chrono::steady_clock::now() - last < stall) {
      const ssize_t n = ::send(fd_, chunk.data(), chunk.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
      if (n > 0) {
        sent += static_cast<std::size_t>(n);
        last = std::chrono::steady_clock::now();
      } else {
        std::this_thread::sleep_for(1ms);
      }
    }
    return sent;
  }
  /// True when the hub closed the connection (EOF or reset) within `wait`.
  bool closed_by_peer(std::chrono::milliseconds wait) {
    const auto end = std::chrono::steady_clock::now() + wait;
    char buf[65536];
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      if (::recv(fd_, buf, sizeof buf, 0) <= 0) return true;
    }
    return false;
  }
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_;
};

/// A well-behaved client: connects through our SocketcandChannel, sends a frame the bus sees.
void expect_served(Hub& hub, Inbox& local_rx, std::size_t already) {
  std::string diag;
  auto ch =
      sc::SocketcandChannel::connect(hub.io.get_executor(), hub.clock, "127.0.0.1", hub.port(), "can0", {}, &diag);
  ASSERT_TRUE(ch.has_value()) << diag;
  ASSERT_FALSE(hub.run([&] { return (*ch)->send(can::make_frame(0x123, {0x42})); }));
  const auto rx = local_rx.wait_for(already + 1);
  ASSERT_EQ(rx.size(), already + 1);
  EXPECT_EQ(rx.back(), can::make_frame(0x123, {0x42}));
  hub.run([&] { ch->reset(); });
}

template <class Pred>
bool eventually(Hub& hub, Pred pred, std::chrono::milliseconds limit = 5s) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (hub.run([&] { return pred(hub.server->stats()); })) return true;
    std::this_thread::sleep_for(10ms);
  }
  return false;
}

}  // namespace

TEST(SocketcandAbuse, AFloodingClientThatNeverReadsHasABoundedQueueAndIsClosed) {
  sc::ServerOptions o;
  o.max_output_bytes = 64 * 1024;
  o.write_stall_timeout = 500ms;
  Hub hub(o);
  Inbox local_rx;
  auto local = hub.run([&] {
    auto ch = hub.bus.attach("local");
    ch->set_receive_handler(local_rx.handler());
    return ch;
  });
  Peer flooder(hub.port());
  // 8 MiB of empty elements, each answered with an error the flooder never reads.
  std::string chunk;
  for (int i = 0; i < 4096; ++i) chunk += "<>";
  flooder.flood(chunk, std::size_t{8} << 20, 300ms);
  const auto peak = hub.run([&] { return hub.server->stats().peak_queued_bytes; });
  EXPECT_LE(peak, o.max_output_bytes + 256 * 1024) << "the queue of a client that does not read stays bounded";
  expect_served(hub, local_rx, 0);
  // The flooder reads nothing until the hub has closed it: a client that reads (as
  // closed_by_peer() does) is served, not closed, so reading before would prove nothing.
  EXPECT_TRUE(eventually(hub, [](const sc::ServerStats& s) { return s.timed_out >= 1 && s.active == 0; }))
      << "closed once its writes stall";
  EXPECT_TRUE(flooder.closed_by_peer(5s)) << "the flooder sees its connection end";
  expect_served(hub, local_rx, 1);
  hub.run([&] { local.reset(); });
}

TEST(SocketcandAbuse, IdleClientsAreClosedAfterTheHandshakeTimeoutAndFreeTheirSlots) {
  sc::ServerOptions o;
  o.max_clients = 4;
  o.handshake_timeout = 300ms;
  Hub hub(o);
  Inbox local_rx;
  auto local = hub.run([&] {
    auto ch = hub.bus.attach("local");
    ch->set_receive_handler(local_rx.handler());
    return ch;
  });
  std::vector<std::unique_ptr<Peer>> idle;
  for (int i = 0; i < 4; ++i) {
    idle.push_back(std::make_unique<Peer>(hub.port()));
    EXPECT_NE(idle.back()->read_for(2s, "< hi >").find("< hi >"), std::string::npos);
  }
  Peer late(hub.port());
  EXPECT_NE(late.read_for(2s, "too many").find("too many clients"), std::string::npos) << "every slot is taken";
  ASSERT_TRUE(eventually(hub, [](const sc::ServerStats& s) { return s.active == 0; }))
      << "idle clients closed after the handshake timeout";
  for (auto& p : idle) EXPECT_TRUE(p->closed_by_peer(1s));
  EXPECT_EQ(hub.run([&] { return hub.server->stats().timed_out; }), 4u);
  expect_served(hub, local_rx, 0);
  hub.run([&] { local.reset(); });
}

TEST(SocketcandAbuse, AcceptOutOfFileDescriptorsBacksOffAndRecovers) {
  sc::ServerOptions o;
  o.accept_backoff_min = 50ms;
  o.accept_backoff_max = 200ms;
  Hub hub(o);
  Inbox local_rx;
  auto local = hub.run([&] {
    auto ch = hub.bus.attach("local");
    ch->set_receive_handler(local_rx.handler());
    return ch;
  });
  Peer client(hub.port(), false);
  // Use up every file descriptor (under a lowered limit), then connect: the kernel completes the
  // connection, the hub's accept fails with EMFILE.
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_NOFILE, &old), 0);
  rlimit low = old;
  low.rlim_cur = 512;
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &low), 0);
  std::vector<int> hog;
  for (int fd; (fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC)) >= 0;) hog.push_back(fd);
  ASSERT_EQ(errno, EMFILE);
  client.connect(hub.port());
  std::this_thread::sleep_for(600ms);
  const auto errors = hub.run([&] { return hub.server->stats().accept_errors; });
  for (int fd : hog) ::close(fd);
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &old), 0);
  EXPECT_GE(errors, 1u) << "accept failed while no descriptor was free";
  EXPECT_LE(errors, 20u) << "a failed accept is retried after a back-off, not at once";
  // Descriptors are back: the waiting client is accepted and served, and so is a new one.
  EXPECT_NE(client.read_for(3s, "< hi >").find("< hi >"), std::string::npos);
  expect_served(hub, local_rx, 0);
  hub.run([&] { local.reset(); });
}
