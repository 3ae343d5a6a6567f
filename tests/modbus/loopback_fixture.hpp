// SPDX-License-Identifier: MIT
#pragma once
// Both ends real in one process: our ModbusDrive (libmodbus client, lockstep) against our
// simulated drive server over loopback TCP, on a virtual clock. One cycle = step the server's
// plant, one exchange, read, write.
#include <gtest/gtest.h>

#include <memory>

#include "hil/core/clock.hpp"
#include "hil/drives/modbus_drive.hpp"
#include "hil/mocks/modbus_server.hpp"
#include "hil/modbus/profile.hpp"

namespace hil::test {

inline modbus::Profile shipped_profile(const std::string& file) {
  auto p = modbus::load_profile("profiles/modbus/" + file);
  EXPECT_TRUE(p) << (p ? "" : p.error().describe());
  return p ? *p : modbus::Profile{};
}

class Loopback {
 public:
  explicit Loopback(const std::string& profile_file, Duration response_timeout = std::chrono::milliseconds(200))
      : profile(shipped_profile(profile_file)) {
    server = std::make_unique<mocks::ModbusDriveServer>(mocks::DriveDevice(profile), mocks::ModbusServerConfig{});
    EXPECT_FALSE(server->start());
    make_drive(response_timeout);
  }
  void make_drive(Duration response_timeout) {
    drives::ModbusDriveConfig c;
    c.name = "x";
    c.host = "127.0.0.1";
    c.port = server->port();
    c.profile = profile;
    c.lockstep = true;
    c.response_timeout = response_timeout;
    c.backoff_min = std::chrono::milliseconds(50);
    c.backoff_max = std::chrono::milliseconds(400);
    drive = std::make_unique<drives::ModbusDrive>(c, clock);
  }
  /// One motion cycle of `period`.
  void cycle(Duration period = std::chrono::milliseconds(1)) {
    clock.advance(period);
    if (server->running()) server->step(period);
    EXPECT_TRUE(drive->exchange_sync(clock.now()));
    const CycleTime t{clock.now(), period};
    drive->read(t);
    drive->write(t, command);
  }
  /// Cycle until `pred()` or `max` cycles; returns whether pred() held.
  template <class Pred>
  bool cycle_until(Pred pred, int max = 200, Duration period = std::chrono::milliseconds(1)) {
    for (int i = 0; i < max; ++i) {
      cycle(period);
      if (pred()) return true;
    }
    return false;
  }
  bool enable() {
    drive->request(DriveRequest::enable);
    return cycle_until([&] { return drive->feedback().state == DriveState::operation_enabled; }, 20);
  }
  [[nodiscard]] const DriveFeedback& fb() const { return drive->feedback(); }

  VirtualClock clock;
  modbus::Profile profile;
  std::unique_ptr<mocks::ModbusDriveServer> server;
  std::unique_ptr<drives::ModbusDrive> drive;
  DriveCommand command;
};

}  // namespace hil::test
