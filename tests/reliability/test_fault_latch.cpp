// SPDX-License-Identifier: MIT
// The safety rule every transport keeps: a drive fault stays latched and the drive stays disabled
// (it follows no command) until a fault reset is requested, even after the cause has gone; the
// reset never re-enables a CiA 402 drive by itself (enable is a separate request). One test,
// parameterised over the simulated drive, CANopen (simulated CiA 402 node on the virtual bus),
// Modbus/TCP (simulated drive server over loopback) and step/dir (mock GPIO lines).
#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>
#include <memory>
#include <string>

#include "hil/can/virtual_bus.hpp"
#include "hil/canopen/eds.hpp"
#include "hil/cia402/cia402_drive.hpp"
#include "hil/cia402/layout.hpp"
#include "hil/config/yaml_config.hpp"
#include "hil/core/clock.hpp"
#include "hil/drives/modbus_drive.hpp"
#include "hil/drives/stepdir/stepdir_drive.hpp"
#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/mocks/cia402_node.hpp"
#include "hil/mocks/modbus_server.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "hil/modbus/profile.hpp"

using namespace std::chrono_literals;
using hil::DriveRequest;
using hil::DriveState;

namespace {

/// One drive and its far end on a virtual clock. `cycle` runs one 1 ms motion cycle with a
/// position command; `set_cause` switches the injected fault's cause on or off.
class Rig {
 public:
  virtual ~Rig() = default;
  virtual void cycle(std::int64_t position) = 0;
  virtual hil::Drive& drive() = 0;
  virtual void set_cause(bool on) = 0;
  /// Whether a fault reset leaves the drive disabled (CiA 402 transition 15). A step/dir stage
  /// keeps its power on through a fault (IP247: the reset acknowledges the error only).
  virtual bool reset_disables() const { return true; }
  const hil::DriveFeedback& fb() { return drive().feedback(); }
  bool run_until(std::int64_t position, const std::function<bool()>& pred, int max_cycles) {
    for (int i = 0; i < max_cycles; ++i) {
      cycle(position);
      if (pred()) return true;
    }
    return false;
  }
};

class SimRig final : public Rig {
 public:
  SimRig() : drive_(hil::mocks::SimDriveConfig{}) {}
  void cycle(std::int64_t position) override {
    const hil::CycleTime t{clock_.now(), 1ms};
    drive_.read(t);
    drive_.write(t, hil::DriveCommand{hil::CommandMode::position, position, 0.0, 0.0});
    clock_.advance(1ms);
  }
  hil::Drive& drive() override { return drive_; }
  void set_cause(bool on) override { ASSERT_TRUE(drive_.inject_fault("encoder", on)); }

 private:
  hil::VirtualClock clock_;
  hil::mocks::SimDrive drive_;
};

class CanopenRig final : public Rig {
 public:
  CanopenRig() {
    hil::canopen::MasterOptions mo;
    mo.sync_period = 1ms;
    mo.sdo.timeout = 20ms;
    mo.boot_timeout = 100ms;
    network_ = std::make_unique<hil::cia402::Network>(*master_channel_, mo);
    hil::mocks::Cia402NodeOptions no;
    no.node = 1;
    node_ = std::make_unique<hil::mocks::Cia402Node>(*node_channel_, no);
    auto eds = hil::canopen::parse_eds(hil::mocks::cia402_node_eds(), "eds", 1);
    EXPECT_TRUE(eds);
    hil::cia402::AxisOptions axis;
    axis.node = 1;
    network_->master().add_node(hil::cia402::make_axis_node_config(*eds, axis));
    drive_ = std::make_unique<hil::cia402::Cia402Drive>(*network_, 1, hil::cia402::DriveOptions{});
    node_->start(clock_.now());
    network_->start(clock_.now());
    bus_.deliver(clock_.now());
  }
  void cycle(std::int64_t position) override {
    clock_.advance(1ms);
    const hil::CycleTime t{clock_.now(), 1ms};
    network_->step(t.now);
    bus_.deliver(t.now);
    drive_->read(t);
    drive_->write(t, hil::DriveCommand{hil::CommandMode::position, position, 0.0, 0.0});
    node_->step(t.now);
    bus_.deliver(t.now);
  }
  hil::Drive& drive() override { return *drive_; }
  void set_cause(bool on) override { ASSERT_TRUE(node_->inject_fault("overcurrent", on, clock_.now())); }

 private:
  hil::VirtualClock clock_;
  hil::can::VirtualBus bus_{clock_, "vbus"};
  std::unique_ptr<hil::can::VirtualChannel> master_channel_ = bus_.attach("master");
  std::unique_ptr<hil::can::VirtualChannel> node_channel_ = bus_.attach("node1");
  std::unique_ptr<hil::cia402::Network> network_;
  std::unique_ptr<hil::mocks::Cia402Node> node_;
  std::unique_ptr<hil::cia402::Cia402Drive> drive_;
};

class ModbusRig final : public Rig {
 public:
  ModbusRig() {
    auto profile = hil::modbus::load_profile("profiles/modbus/cia402.yaml");
    EXPECT_TRUE(profile) << (profile ? "" : profile.error().describe());
    server_ = std::make_unique<hil::mocks::ModbusDriveServer>(hil::mocks::DriveDevice(*profile),
                                                              hil::mocks::ModbusServerConfig{});
    EXPECT_FALSE(server_->start());
    hil::drives::ModbusDriveConfig c;
    c.name = "x";
    c.host = "127.0.0.1";
    c.port = server_->port();
    c.profile = *profile;
    c.lockstep = true;
    drive_ = std::make_unique<hil::drives::ModbusDrive>(c, clock_);
  }
  void cycle(std::int64_t position) override {
    clock_.advance(1ms);
    server_->step(1ms);
    EXPECT_TRUE(drive_->exchange_sync(clock_.now()));
    const hil::CycleTime t{clock_.now(), 1ms};
    drive_->read(t);
    drive_->write(t, hil::DriveCommand{hil::CommandMode::position, position, 0.0, 0.0});
  }
  hil::Drive& drive() override { return *drive_; }
  void set_cause(bool on) override { server_->inject(hil::PlantFault::encoder, on); }

 private:
  hil::VirtualClock clock_;
  std::unique_ptr<hil::mocks::ModbusDriveServer> server_;
  std::unique_ptr<hil::drives::ModbusDrive> drive_;
};

class StepDirRig final : public Rig {
 public:
  StepDirRig() {
    auto d = factory_.make_drive("x",
                                 YAML::Load("{transport: stepdir, fmax_hz: 20000, fss_hz: 500, "
                                            "accel_hz_per_s: 200000, pulse_us: 10}"),
                                 env_);
    EXPECT_TRUE(d) << (d ? "" : d.error().describe());
    if (d) drive_ = std::move(*d);
  }
  void cycle(std::int64_t position) override {
    const hil::CycleTime t{clock_.now(), 1ms};
    drive_->read(t);
    drive_->write(t, hil::DriveCommand{hil::CommandMode::position, position, 0.0, 0.0});
    clock_.advance(1ms);
  }
  hil::Drive& drive() override { return *drive_; }
  void set_cause(bool on) override {
    ASSERT_TRUE(dynamic_cast<hil::FaultInjectable&>(*drive_).inject_fault("not_ready", on));
  }
  bool reset_disables() const override { return false; }

 private:
  hil::VirtualClock clock_;
  hil::RunEnvironment env_{clock_, true, nullptr, "", 1ms, false, {}};
  hil::drives::stepdir::StepDirTransportFactory factory_;
  hil::DrivePtr drive_;
};

struct Transport {
  const char* name;
  std::function<std::unique_ptr<Rig>()> make;
};

class FaultLatch : public ::testing::TestWithParam<Transport> {};

bool faulted(const hil::DriveFeedback& fb) {
  return fb.state == DriveState::fault || fb.state == DriveState::fault_reaction_active || static_cast<bool>(fb.fault);
}

}  // namespace

TEST_P(FaultLatch, AFaultStaysLatchedAndTheDriveDisabledUntilReset) {
  auto rig = GetParam().make();
  rig->run_until(
      0, [] { return false; }, 300);  // boot (CANopen: SDO configuration)
  rig->drive().request(DriveRequest::enable);
  ASSERT_TRUE(rig->run_until(
      0, [&] { return rig->fb().state == DriveState::operation_enabled; }, 500));
  const std::int64_t p0 = rig->fb().position_inc;

  rig->set_cause(true);
  ASSERT_TRUE(rig->run_until(
      p0, [&] { return faulted(rig->fb()); }, 500));
  rig->run_until(
      p0, [] { return false; }, 20);
  rig->set_cause(false);

  // The cause is gone and the master keeps commanding a move: the drive stays faulted, disabled
  // and where it was, for as long as nobody asks for a reset (2 s here).
  const std::int64_t target = p0 + 20'000;
  for (int i = 0; i < 2000; ++i) {
    rig->cycle(target);
    ASSERT_TRUE(faulted(rig->fb())) << "cycle " << i << ": the fault cleared without a reset (state "
                                    << hil::to_string(rig->fb().state) << ")";
    ASSERT_NE(rig->fb().state, DriveState::operation_enabled) << "cycle " << i;
    ASSERT_LE(std::llabs(rig->fb().position_inc - p0), 2) << "cycle " << i << ": the drive moved";
  }

  // The reset clears the fault; a CiA 402 drive comes back disabled and needs an enable.
  rig->drive().request(DriveRequest::fault_reset);
  ASSERT_TRUE(rig->run_until(
      p0, [&] { return !faulted(rig->fb()); }, 500));
  if (rig->reset_disables()) {
    rig->run_until(
        p0, [] { return false; }, 200);
    EXPECT_NE(rig->fb().state, DriveState::operation_enabled) << "a reset never enables";
    rig->drive().request(DriveRequest::enable);
  }
  ASSERT_TRUE(rig->run_until(
      p0, [&] { return rig->fb().state == DriveState::operation_enabled; }, 500));
  EXPECT_TRUE(rig->run_until(
      target, [&] { return std::llabs(rig->fb().position_inc - target) < 100; }, 5000))
      << "after reset and enable the drive follows again";
}

INSTANTIATE_TEST_SUITE_P(EveryTransport, FaultLatch,
                         ::testing::Values(Transport{"sim", [] { return std::make_unique<SimRig>(); }},
                                           Transport{"canopen", [] { return std::make_unique<CanopenRig>(); }},
                                           Transport{"modbus", [] { return std::make_unique<ModbusRig>(); }},
                                           Transport{"stepdir", [] { return std::make_unique<StepDirRig>(); }}),
                         [](const ::testing::TestParamInfo<Transport>& param_info) {
                           return std::string(param_info.param.name);
                         });
