// SPDX-License-Identifier: MIT
// The Modbus drive server under abuse, each case followed by a well-behaved client that must
// still be served: idle clients holding every slot (closed after idle_timeout), and accept
// failing for lack of file descriptors (a back-off instead of a busy loop that logs a million
// lines).
#include <fcntl.h>
#include <sys/resource.h>

#include <atomic>
#include <cerrno>
#include <memory>
#include <thread>
#include <vector>

#include "loopback_fixture.hpp"
#include "raw_socket.hpp"

namespace hil::test {
namespace {

using std::chrono::milliseconds;

/// Read holding register 10 (FC 3) as a well-behaved client does; true when the answer came.
bool served(std::uint16_t port) {
  RawSocket c(port);
  if (!c.connected()) return false;
  if (!c.send({0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x0A, 0x00, 0x01})) return false;
  const auto r = c.recv(11);
  return r.size() == 11 && r[7] == 0x03;
}

}  // namespace

TEST(ModbusServerAbuse, IdleClientsAreClosedAndFreeTheirSlots) {
  mocks::ModbusServerConfig config;
  config.max_connections = 4;
  config.idle_timeout = milliseconds(300);
  mocks::ModbusDriveServer server(mocks::DriveDevice(shipped_profile("cia402.yaml")), config);
  ASSERT_FALSE(server.start());
  std::vector<std::unique_ptr<RawSocket>> idle;
  for (int i = 0; i < 4; ++i) idle.push_back(std::make_unique<RawSocket>(server.port()));
  RawSocket refused(server.port());
  EXPECT_TRUE(refused.peer_closed()) << "every slot is taken";
  for (auto& s : idle)
    EXPECT_TRUE(s->peer_closed()) << "closed after idle_timeout (bounded by the 2 s receive timeout)";
  EXPECT_EQ(server.stats().idle_closed, 4u);
  EXPECT_TRUE(served(server.port()));
}

TEST(ModbusServerAbuse, AnActiveClientIsNotIdle) {
  mocks::ModbusServerConfig config;
  config.idle_timeout = milliseconds(300);
  mocks::ModbusDriveServer server(mocks::DriveDevice(shipped_profile("cia402.yaml")), config);
  ASSERT_FALSE(server.start());
  RawSocket c(server.port());
  for (int i = 0; i < 10; ++i) {  // a request every 100 ms for a second: never idle for 300 ms
    ASSERT_TRUE(c.send({0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x0A, 0x00, 0x01}));
    ASSERT_EQ(c.recv(11).size(), 11u) << "request " << i;
    std::this_thread::sleep_for(milliseconds(100));
  }
  EXPECT_EQ(server.stats().idle_closed, 0u);
}

TEST(ModbusServerAbuse, AcceptOutOfFileDescriptorsBacksOffAndRecovers) {
  std::atomic<int> log_lines{0};
  mocks::ModbusServerConfig config;
  config.accept_backoff_min = milliseconds(50);
  config.accept_backoff_max = milliseconds(200);
  config.log = [&](std::string_view) { ++log_lines; };
  mocks::ModbusDriveServer server(mocks::DriveDevice(shipped_profile("cia402.yaml")), config);
  ASSERT_FALSE(server.start());
  const int client = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(client, 0);
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_NOFILE, &old), 0);
  rlimit low = old;
  low.rlim_cur = 512;
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &low), 0);
  std::vector<int> hog;
  for (int fd; (fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC)) >= 0;) hog.push_back(fd);
  ASSERT_EQ(errno, EMFILE);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(server.port());
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(client, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);  // completes in the backlog
  std::this_thread::sleep_for(milliseconds(600));
  const auto errors = server.stats().accept_errors;
  const int lines = log_lines.load();
  for (int fd : hog) ::close(fd);
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &old), 0);
  ::close(client);
  EXPECT_GE(errors, 1u) << "accept failed while no descriptor was free";
  EXPECT_LE(errors, 20u) << "a failed accept is retried after a back-off, not at once";
  EXPECT_LE(lines, 20) << "and logged once per attempt";
  EXPECT_TRUE(served(server.port()));
}

}  // namespace hil::test
