// SPDX-License-Identifier: MIT
// Our ModbusDrive (libmodbus client) against an independent server: pymodbus 3.0 with a CiA 402
// device in Python (pymodbus_cia402_server.py), run with /usr/bin/python3. FC 23 and FC 16 + FC 3
// exchanges, word order seen from the other implementation, exception 02 from pymodbus, and the
// Python server killed and restarted on the same port mid-run.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <modbus.h>

#include <filesystem>
#include <string>

#include "loopback_fixture.hpp"

extern char** environ;

namespace hil::test {
namespace {

using std::chrono::milliseconds;

const char* kPython = "/usr/bin/python3";
const char* kScript = "tests/modbus/pymodbus_cia402_server.py";

/// The Python server as a child process; its first stdout line is "port N".
class PythonServer {
 public:
  explicit PythonServer(int port = 0) {
    int fds[2];
    if (::pipe(fds) != 0) return;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&fa, fds[0]);
    const std::string port_arg = std::to_string(port);
    const char* argv[] = {kPython, kScript, "--port", port_arg.c_str(), nullptr};
    if (posix_spawn(&pid_, kPython, &fa, nullptr, const_cast<char**>(argv), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&fa);
    ::close(fds[1]);
    out_ = fds[0];
    // Wait (bounded) for "port N\n".
    std::string line;
    pollfd p{out_, POLLIN, 0};
    while (pid_ > 0 && line.find('\n') == std::string::npos && ::poll(&p, 1, 15000) == 1) {
      char buf[64];
      const ssize_t n = ::read(out_, buf, sizeof buf);
      if (n <= 0) break;
      line.append(buf, static_cast<std::size_t>(n));
    }
    if (line.starts_with("port ")) port_ = static_cast<std::uint16_t>(std::stoi(line.substr(5)));
  }
  ~PythonServer() { kill(); }
  void kill() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      int status = 0;
      ::waitpid(pid_, &status, 0);
      pid_ = -1;
    }
    if (out_ >= 0) ::close(out_);
    out_ = -1;
  }
  [[nodiscard]] std::uint16_t port() const { return port_; }

 private:
  pid_t pid_ = -1;
  int out_ = -1;
  std::uint16_t port_ = 0;
};

bool have_python() {
  return std::filesystem::exists(kPython) && std::system("/usr/bin/python3 -c 'import pymodbus' 2>/dev/null") == 0;
}

struct PeerDrive {
  PeerDrive(const modbus::Profile& profile, std::uint16_t port) {
    drives::ModbusDriveConfig c;
    c.profile = profile;
    c.port = port;
    c.lockstep = true;
    c.response_timeout = milliseconds(500);
    c.backoff_min = milliseconds(20);
    c.backoff_max = milliseconds(100);
    drive = std::make_unique<drives::ModbusDrive>(c, clock);
  }
  void cycle() {
    clock.advance(milliseconds(1));
    EXPECT_TRUE(drive->exchange_sync(clock.now()));
    drive->read({clock.now(), milliseconds(1)});
    drive->write({clock.now(), milliseconds(1)}, command);
  }
  template <class Pred>
  bool until(Pred p, int max) {
    for (int i = 0; i < max; ++i) {
      cycle();
      if (p()) return true;
    }
    return false;
  }
  VirtualClock clock;
  std::unique_ptr<drives::ModbusDrive> drive;
  DriveCommand command;
};

class ModbusPymodbusServer : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!have_python()) GTEST_SKIP() << "/usr/bin/python3 with python3-pymodbus is not installed";
  }
};

void enable_and_move(PeerDrive& d, std::int64_t target) {
  d.drive->request(DriveRequest::enable);
  ASSERT_TRUE(d.until([&] { return d.drive->feedback().state == DriveState::operation_enabled; }, 20))
      << to_string(d.drive->feedback().state) << " " << d.drive->feedback().fault.describe();
  d.command.position_inc = target;
  ASSERT_TRUE(d.until([&] { return d.drive->feedback().position_inc == target; }, 10));
}

TEST_F(ModbusPymodbusServer, Fc23ExchangeEnablesAndWordOrderMatches) {
  PythonServer py;
  ASSERT_NE(py.port(), 0) << "pymodbus server did not start";
  PeerDrive d(shipped_profile("cia402.yaml"), py.port());
  enable_and_move(d, -100000);
  // Read the target back with a separate libmodbus client: high word first on the wire.
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", py.port());
  ASSERT_EQ(modbus_connect(ctx), 0);
  std::uint16_t r[2];
  ASSERT_EQ(modbus_read_registers(ctx, 2, 2, r), 2);
  EXPECT_EQ(r[0], 0xFFFE);  // -100000 = 0xFFFE7960
  EXPECT_EQ(r[1], 0x7960);
  modbus_close(ctx);
  modbus_free(ctx);
  EXPECT_EQ(d.drive->link_stats().errors, 0u);
}

TEST_F(ModbusPymodbusServer, Fc16PlusFc3Exchange) {
  PythonServer py;
  ASSERT_NE(py.port(), 0);
  auto profile = shipped_profile("cia402.yaml");
  profile.function_codes.read_write = false;  // separate FC 16 write and FC 3 read
  PeerDrive d(profile, py.port());
  enable_and_move(d, 4242);
  d.drive->request(DriveRequest::disable);
  ASSERT_TRUE(d.until([&] { return d.drive->feedback().state == DriveState::switch_on_disabled; }, 5));
}

TEST_F(ModbusPymodbusServer, IllegalAddressFromPymodbusFaultsTheAxis) {
  PythonServer py;
  ASSERT_NE(py.port(), 0);
  auto profile = shipped_profile("cia402.yaml");
  profile.field(modbus::FieldRole::fault_code).address = 40;  // outside pymodbus' 32 registers
  profile.function_codes.read_write = false;
  PeerDrive d(profile, py.port());
  d.cycle();
  EXPECT_EQ(d.drive->feedback().state, DriveState::fault);
  EXPECT_EQ(d.drive->feedback().fault.code, modbus::make_error_code(modbus::ModbusError::illegal_data_address))
      << d.drive->feedback().fault.describe();
}

TEST_F(ModbusPymodbusServer, KilledAndRestartedOnTheSamePort) {
  auto py = std::make_unique<PythonServer>();
  const std::uint16_t port = py->port();
  ASSERT_NE(port, 0);
  PeerDrive d(shipped_profile("cia402.yaml"), port);
  enable_and_move(d, 777);
  py->kill();
  ASSERT_TRUE(d.until([&] { return d.drive->feedback().state == DriveState::fault; }, 5));
  EXPECT_STREQ(d.drive->feedback().fault.code.category().name(), "modbus");
  py = std::make_unique<PythonServer>(port);
  ASSERT_EQ(py->port(), port);
  ASSERT_TRUE(d.until([&] { return d.drive->link_stats().connected && d.drive->feedback().age == Duration{}; }, 2000));
  d.drive->request(DriveRequest::fault_reset);
  ASSERT_TRUE(d.until([&] { return d.drive->feedback().state == DriveState::switch_on_disabled; }, 10));
  d.command.position_inc = 0;
  enable_and_move(d, 555);
}

}  // namespace
}  // namespace hil::test
