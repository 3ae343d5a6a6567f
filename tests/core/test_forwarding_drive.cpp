// SPDX-License-Identifier: MIT
// hil::ForwardingDrive: every call reaches the inner drive unchanged, a derived drive overrides
// only what it adds, and the inner drive is destroyed before what it needs is released.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "hil/core/forwarding_drive.hpp"

namespace hil {
namespace {

/// Records what it is asked; on destruction checks that its bus still exists.
class RecordingDrive final : public Drive {
 public:
  RecordingDrive(std::vector<std::string>& log, std::weak_ptr<int> bus) : log_(log), bus_(std::move(bus)) {}
  ~RecordingDrive() override { log_.push_back(bus_.expired() ? "drive gone after its bus" : "drive gone"); }
  std::string_view name() const noexcept override { return "rec:1"; }
  DriveCapabilities capabilities() const noexcept override {
    DriveCapabilities c;
    c.homing = false;
    c.digital_output_mask = 0x30000;
    return c;
  }
  void read(const CycleTime& c) override {
    fb_.position_inc = c.now.time_since_epoch().count();
    log_.push_back("read");
  }
  void write(const CycleTime&, const DriveCommand& cmd) override {
    log_.push_back("write " + std::to_string(cmd.position_inc));
  }
  const DriveFeedback& feedback() const noexcept override { return fb_; }
  bool request(DriveRequest r) override {
    log_.push_back("request");
    return r != DriveRequest::home;
  }

 private:
  std::vector<std::string>& log_;
  std::weak_ptr<int> bus_;
  DriveFeedback fb_;
};

/// Adds fault injection to the forwarded drive, as the in-process transports do.
class WithFaults final : public ForwardingDrive, public FaultInjectable {
 public:
  using ForwardingDrive::ForwardingDrive;
  std::vector<std::string> injectable_faults() const override { return {"encoder"}; }
  bool inject_fault(std::string_view name, bool active) override {
    active_ = name == "encoder" && active;
    return name == "encoder";
  }
  bool active_ = false;
};

TEST(ForwardingDrive, ForwardsEveryCallToTheInnerDrive) {
  std::vector<std::string> log;
  auto bus = std::make_shared<int>(0);
  ForwardingDrive d(std::make_unique<RecordingDrive>(log, bus));
  EXPECT_EQ(d.name(), "rec:1");
  EXPECT_FALSE(d.capabilities().homing);
  EXPECT_EQ(d.capabilities().digital_output_mask, 0x30000u);
  d.read(CycleTime{TimePoint{Duration{42}}, std::chrono::milliseconds(1)});
  EXPECT_EQ(d.feedback().position_inc, 42);
  d.write(CycleTime{}, DriveCommand{CommandMode::position, 7, 0.0, 0.0});
  EXPECT_TRUE(d.request(DriveRequest::enable));
  EXPECT_FALSE(d.request(DriveRequest::home));
  EXPECT_EQ(log, (std::vector<std::string>{"read", "write 7", "request", "request"}));
  // A plain forwarding drive adds no fault injection: scenarios see what the inner drive offers.
  EXPECT_EQ(dynamic_cast<FaultInjectable*>(static_cast<Drive*>(&d)), nullptr);
}

TEST(ForwardingDrive, ADerivedDriveAddsOnlyWhatItOverrides) {
  std::vector<std::string> log;
  auto bus = std::make_shared<int>(0);
  WithFaults d(std::make_unique<RecordingDrive>(log, bus));
  Drive& drive = d;
  auto* faults = dynamic_cast<FaultInjectable*>(&drive);
  ASSERT_NE(faults, nullptr);
  EXPECT_TRUE(faults->inject_fault("encoder", true));
  EXPECT_TRUE(d.active_);
  EXPECT_FALSE(faults->inject_fault("no_such_fault", true));
  drive.read(CycleTime{});
  EXPECT_EQ(log, (std::vector<std::string>{"read"}));
}

TEST(ForwardingDrive, TheInnerDriveGoesBeforeWhatItNeeds) {
  std::vector<std::string> log;
  auto bus = std::make_shared<int>(0);
  std::weak_ptr<int> watch = bus;
  auto d = std::make_unique<ForwardingDrive>(std::make_unique<RecordingDrive>(log, bus), bus);
  bus.reset();  // the factory that built the drive is gone first
  EXPECT_FALSE(watch.expired()) << "the drive keeps its bus";
  d.reset();
  EXPECT_EQ(log, (std::vector<std::string>{"drive gone"}));
  EXPECT_TRUE(watch.expired()) << "released with the last drive";
}

}  // namespace
}  // namespace hil
