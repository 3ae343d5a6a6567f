// SPDX-License-Identifier: MIT
// The serial emulators' TCP listener (`hilbridge emulate ... --tcp`) out of file descriptors: every
// failed accept is counted and takes its whole timeout (the emulator's accept loop backs off
// instead of spinning), nothing throws, and once descriptors are free again the client that waited
// in the backlog is accepted and served.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "hil/serial/linux/ports.hpp"

using namespace hil::serial;
using namespace std::chrono_literals;

namespace {
/// Every file descriptor in use (under a lowered soft limit) while it lives; all released after.
class DescriptorsExhausted {
 public:
  DescriptorsExhausted() {
    EXPECT_EQ(::getrlimit(RLIMIT_NOFILE, &old_), 0);
    rlimit low = old_;
    low.rlim_cur = 512;
    EXPECT_EQ(::setrlimit(RLIMIT_NOFILE, &low), 0);
    for (int fd; (fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC)) >= 0;) hog_.push_back(fd);
    exhausted_ = errno == EMFILE;
  }
  ~DescriptorsExhausted() {
    for (int fd : hog_) ::close(fd);
    ::setrlimit(RLIMIT_NOFILE, &old_);
  }
  DescriptorsExhausted(const DescriptorsExhausted&) = delete;
  DescriptorsExhausted& operator=(const DescriptorsExhausted&) = delete;
  [[nodiscard]] bool exhausted() const noexcept { return exhausted_; }

 private:
  rlimit old_{};
  std::vector<int> hog_;
  bool exhausted_ = false;
};
}  // namespace

TEST(TcpListener, AcceptOutOfFileDescriptorsBacksOffAndRecovers) {
  hil::SteadyClock clock;
  auto listener = linux_io::TcpListener::create("127.0.0.1", 0);
  ASSERT_TRUE(listener) << listener.error().message;
  const int client = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  ASSERT_GE(client, 0);
  int calls = 0;
  std::uint64_t errors = 0;
  std::error_code last;
  {
    DescriptorsExhausted no_fds;
    ASSERT_TRUE(no_fds.exhausted());
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons((*listener)->port());
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    // The kernel completes the connection into the backlog; accepting it needs a descriptor.
    // Non-blocking with a bounded wait: a SYN dropped (a full backlog) fails the test, never hangs it.
    ASSERT_TRUE(::connect(client, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0 || errno == EINPROGRESS)
        << std::strerror(errno);
    pollfd p{client, POLLOUT, 0};
    ASSERT_EQ(::poll(&p, 1, 5000), 1) << "the connection did not complete within 5 s";
    int so_error = 0;
    socklen_t len = sizeof so_error;
    ASSERT_EQ(::getsockopt(client, SOL_SOCKET, SO_ERROR, &so_error, &len), 0);
    ASSERT_EQ(so_error, 0) << std::strerror(so_error);
    // The emulator's loop: accept with a short timeout, again and again, for one second.
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < 1s) {
      auto line = (*listener)->accept(100ms);
      ++calls;
      if (line) break;
    }
    errors = (*listener)->accept_errors();
    last = (*listener)->last_accept_error();
  }
  EXPECT_GE(errors, 1u) << "accept failed while no descriptor was free";
  EXPECT_EQ(errors, static_cast<std::uint64_t>(calls)) << "every call failed (the client waited in the backlog)";
  EXPECT_LE(calls, 11) << "each failed accept took its whole timeout: no busy loop";
  EXPECT_EQ(last.value(), EMFILE) << last.message();
  // Descriptors are back: the client that waited is accepted and its bytes arrive.
  auto line = (*listener)->accept(2s);
  ASSERT_TRUE(line) << "the waiting client is accepted once descriptors are free";
  SerialStream server(std::move(line), LineFormat{}, Discipline{}, clock);
  ASSERT_EQ(::send(client, ":1\r\n", 4, MSG_NOSIGNAL), 4);
  std::string got;
  std::array<std::uint8_t, 16> buf{};
  for (int i = 0; i < 20 && got.size() < 4; ++i) {
    const auto r = server.read_some(buf, 100ms);
    got.append(reinterpret_cast<const char*>(buf.data()), r.size);
  }
  EXPECT_EQ(got, ":1\r\n");
  EXPECT_EQ((*listener)->accept_errors(), errors) << "no failure once descriptors are free";
  ::close(client);
}
