// SPDX-License-Identifier: MIT
// Teardown by ownership (docs/ARCHITECTURE.md, "Teardown"): a drive built by a transport factory
// holds what it uses (the CANopen bus with its master and simulated node, the in-process Modbus
// server, the step/dir lines and sink), so the run may destroy its factories and its axes in
// either order. Each transport's real factory, on a virtual clock: the drive boots and enables,
// then the factory is destroyed first and the drive keeps working on what it holds (stale feedback
// where the factory stepped the far end, never freed memory: the ASan stage of CI checks that).
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>

#include <yaml-cpp/yaml.h>

#include "hil/cia402/canopen_transport.hpp"
#include "hil/core/fault_injection.hpp"
#include "hil/core/transport.hpp"
#include "hil/drives/modbus_transport.hpp"
#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/mocks/sim_transport.hpp"

namespace {

using namespace std::chrono_literals;
using hil::DriveState;

struct Case {
  const char* name;
  std::function<std::unique_ptr<hil::TransportFactory>()> make;
  const char* block;
};

class Teardown : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    factory_ = GetParam().make();
    auto d = factory_->make_drive("x", YAML::Load(GetParam().block), env_);
    ASSERT_TRUE(d) << d.error().describe();
    drive_ = std::move(*d);
  }
  /// One run cycle; the factory's bus work only while it exists.
  void cycle() {
    const hil::CycleTime t{clock_.now(), 1ms};
    if (factory_) factory_->begin_cycle(t);
    drive_->read(t);
    drive_->write(t, hil::DriveCommand{hil::CommandMode::position, drive_->feedback().position_inc, 0.0, 0.0});
    if (factory_) factory_->end_cycle(t);
    clock_.advance(1ms);
  }
  bool enable() {
    for (int i = 0; i < 3000; ++i) {
      if (i == 300) drive_->request(hil::DriveRequest::enable);  // after the boot (CANopen SDO configuration)
      cycle();
      if (i > 300 && drive_->feedback().state == DriveState::operation_enabled) return true;
    }
    return false;
  }

  hil::VirtualClock clock_;
  hil::RunEnvironment env_{clock_, true, nullptr, "", 1ms, false, {}};
  std::unique_ptr<hil::TransportFactory> factory_;
  hil::DrivePtr drive_;
};

TEST_P(Teardown, TheDriveOutlivesItsFactory) {
  ASSERT_TRUE(enable());
  const std::string name(drive_->name());
  factory_->finish(hil::CycleTime{clock_.now(), 1ms});
  factory_.reset();  // the factory first: its buses, servers and lines stay with the drive
  for (int i = 0; i < 50; ++i) cycle();
  EXPECT_EQ(drive_->name(), name);
  EXPECT_TRUE(drive_->request(hil::DriveRequest::disable));
  if (auto* faults = dynamic_cast<hil::FaultInjectable*>(drive_.get())) {
    // The far end a fault acts on is still there.
    const auto names = faults->injectable_faults();
    ASSERT_FALSE(names.empty());
    faults->inject_fault(names.front(), true);
    faults->inject_fault(names.front(), false);
  }
  for (int i = 0; i < 50; ++i) cycle();
  drive_.reset();  // releases the last owner of what it used
}

TEST_P(Teardown, TheFactoryOutlivesItsDrive) {
  ASSERT_TRUE(enable());
  const auto report = factory_->finish(hil::CycleTime{clock_.now(), 1ms});
  EXPECT_TRUE(report.ok);
  drive_.reset();  // the drive first (the order hilbridge's Machine uses)
  factory_.reset();
}

INSTANTIATE_TEST_SUITE_P(
    EveryTransport, Teardown,
    ::testing::Values(
        Case{"sim", [] { return hil::mocks::make_sim_transport(); }, "{transport: sim}"},
        Case{"canopen", [] { return hil::cia402::make_canopen_transport(); }, "{transport: canopen, node: 3}"},
        Case{"modbus", [] { return hil::drives::make_modbus_transport(); }, "{transport: modbus, profile: cia402}"},
        Case{"stepdir", [] { return std::make_unique<hil::drives::stepdir::StepDirTransportFactory>(); },
             "{transport: stepdir, fmax_hz: 20000, fss_hz: 500, accel_hz_per_s: 200000, pulse_us: 10}"}),
    [](const ::testing::TestParamInfo<Case>& param_info) { return std::string(param_info.param.name); });

}  // namespace
