// SPDX-License-Identifier: MIT
// Byte streams into an in-process Modbus drive server session: one server for the whole run; each
// input goes to a fresh connection (one end of a socketpair the server adopts) in chunks of
// 1 + data[0] % 64 bytes, then the client's write side is shut. Whatever the bytes, the server
// answers only with well-formed MBAP frames and ends the session (EOF) within the time limit:
// never a crash, a sanitizer report or a session left hanging.
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "hil/mocks/modbus_server.hpp"
#include "hil/modbus/adu.hpp"
#include "hil/modbus/profile.hpp"

namespace {

hil::mocks::ModbusDriveServer& server() {
  static hil::mocks::ModbusDriveServer* s = [] {
    auto profile = hil::modbus::load_profile(HIL_MODBUS_PROFILE_DIR "/cia402.yaml");
    if (!profile) std::abort();
    hil::mocks::ModbusServerConfig c;
    c.frame_timeout = std::chrono::milliseconds(200);
    auto* srv = new hil::mocks::ModbusDriveServer(hil::mocks::DriveDevice(*profile), c);
    if (srv->start()) std::abort();
    return srv;
  }();
  return *s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  auto& srv = server();
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0, sv) != 0) std::abort();
  srv.adopt(sv[0]);
  const std::size_t chunk = 1 + data[0] % 64;
  const std::uint8_t* p = data + 1;
  std::size_t left = size - 1;
  bool shut = false;
  std::vector<std::uint8_t> replies;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  for (;;) {
    if (left == 0 && !shut) {
      ::shutdown(sv[1], SHUT_WR);
      shut = true;
    }
    pollfd pfd{sv[1], static_cast<short>(POLLIN | (left > 0 ? POLLOUT : 0)), 0};
    if (::poll(&pfd, 1, 50) < 0) std::abort();
    if (std::chrono::steady_clock::now() > deadline) std::abort();  // the session hangs
    if ((pfd.revents & POLLOUT) && left > 0) {
      const ssize_t n = ::send(sv[1], p, std::min(chunk, left), MSG_NOSIGNAL);
      if (n > 0) {
        p += n;
        left -= static_cast<std::size_t>(n);
      } else if (n < 0 && errno != EAGAIN) {
        left = 0;  // the server closed the connection (malformed header): fine
      }
    }
    if (pfd.revents & (POLLIN | POLLHUP | POLLERR)) {
      std::uint8_t buf[4096];
      const ssize_t n = ::recv(sv[1], buf, sizeof buf, 0);
      if (n == 0 || (n < 0 && errno != EAGAIN)) break;  // the server ended the session
      if (n > 0) replies.insert(replies.end(), buf, buf + n);
    }
  }
  ::close(sv[1]);
  // Every reply is a complete, well-formed ADU.
  std::span<const std::uint8_t> rest(replies);
  while (!rest.empty()) {
    const auto f = hil::modbus::check_frame(rest);
    if (f.status != hil::modbus::FrameStatus::complete) std::abort();
    rest = rest.subspan(f.size);
  }
  return 0;
}
