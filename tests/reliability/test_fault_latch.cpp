// SPDX-License-Identifier: MIT
// The safety rule every transport keeps: a drive fault stays latched and the drive stays disabled
// (it follows no command) until a fault reset is requested, even after the cause has gone; the
// reset never re-enables a CiA 402 drive by itself (enable is a separate request). One test,
// parameterised over the simulated drive, CANopen (simulated CiA 402 node on the virtual bus),
// Modbus/TCP (simulated drive server over loopback) and step/dir (mock GPIO lines), each built by
// its transport's real factory from a drive block, as `hilbridge run` builds it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>
#include <memory>
#include <string>

#include <yaml-cpp/yaml.h>

#include "hil/cia402/canopen_transport.hpp"
#include "hil/core/clock.hpp"
#include "hil/core/fault_injection.hpp"
#include "hil/core/transport.hpp"
#include "hil/drives/modbus_transport.hpp"
#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/mocks/sim_drive.hpp"

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

/// A drive built by the transport's real factory (the one `hilbridge run` registers) from a
/// drive block; the factory's bus work runs around each cycle, and the fault is injected through
/// the drive's FaultInjectable into its far end (the simulated node, the drive server, the lines).
class FactoryRig final : public Rig {
 public:
  FactoryRig(std::unique_ptr<hil::TransportFactory> factory, const char* block, std::string fault,
             bool reset_disables = true)
      : factory_(std::move(factory)), fault_(std::move(fault)), reset_disables_(reset_disables) {
    auto d = factory_->make_drive("x", YAML::Load(block), env_);
    EXPECT_TRUE(d) << (d ? "" : d.error().describe());
    if (d) drive_ = std::move(*d);
  }
  void cycle(std::int64_t position) override {
    clock_.advance(1ms);
    const hil::CycleTime t{clock_.now(), 1ms};
    factory_->begin_cycle(t);
    drive_->read(t);
    drive_->write(t, hil::DriveCommand{hil::CommandMode::position, position, 0.0, 0.0});
    factory_->end_cycle(t);
  }
  hil::Drive& drive() override { return *drive_; }
  void set_cause(bool on) override {
    auto* faults = dynamic_cast<hil::FaultInjectable*>(drive_.get());
    ASSERT_NE(faults, nullptr);
    ASSERT_TRUE(faults->inject_fault(fault_, on));
  }
  bool reset_disables() const override { return reset_disables_; }

 private:
  hil::VirtualClock clock_;
  hil::RunEnvironment env_{clock_, true, nullptr, "", 1ms, false, {}};
  std::unique_ptr<hil::TransportFactory> factory_;
  hil::DrivePtr drive_;
  std::string fault_;
  bool reset_disables_;
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

INSTANTIATE_TEST_SUITE_P(
    EveryTransport, FaultLatch,
    ::testing::Values(Transport{"sim", [] { return std::make_unique<SimRig>(); }},
                      Transport{"canopen",
                                [] {
                                  return std::make_unique<FactoryRig>(hil::cia402::make_canopen_transport(),
                                                                      "{transport: canopen, node: 1}", "overcurrent");
                                }},
                      Transport{"modbus",
                                [] {
                                  return std::make_unique<FactoryRig>(hil::drives::make_modbus_transport(),
                                                                      "{transport: modbus, profile: cia402}",
                                                                      "encoder");
                                }},
                      Transport{"stepdir",
                                [] {
                                  // IP247: the reset acknowledges the error only.
                                  return std::make_unique<FactoryRig>(
                                      std::make_unique<hil::drives::stepdir::StepDirTransportFactory>(),
                                      "{transport: stepdir, fmax_hz: 20000, fss_hz: 500, "
                                      "accel_hz_per_s: 200000, pulse_us: 10}",
                                      "not_ready", false);
                                }}),
    [](const ::testing::TestParamInfo<Transport>& param_info) { return std::string(param_info.param.name); });
