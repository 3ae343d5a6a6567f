// SPDX-License-Identifier: MIT
#pragma once
// A small scripted drive for axis tests: CiA 402-like power states after a fixed number of
// cycles, position that follows the command with an optional lag and offset, and switches to
// freeze it, fault it or make its feedback stale.

#include <deque>
#include <vector>

#include "hil/core/drive.hpp"

namespace hil::motion::test {

class TestDrive final : public hil::Drive {
 public:
  int enable_cycles = 2;  ///< write() calls from request(enable) to operation_enabled
  bool never_enable = false;
  bool homing_supported = true;
  /// A drive that runs its own profile: it jumps to DriveCommand::move's target at once (a
  /// worst case for the axis's path supervision, which must then stay out of the way).
  bool drive_profile = false;
  int homing_cycles = 5;
  bool follow = true;  ///< actual := command written `lag` cycles ago, minus `offset`
  std::size_t lag = 0;
  std::int64_t offset = 0;
  std::int64_t position = 0;  ///< actual, increments
  hil::Duration age{};
  hil::Fault fault;
  std::vector<hil::DriveCommand> commands;
  std::vector<hil::DriveRequest> requests;

  std::string_view name() const noexcept override { return "test:0"; }
  hil::DriveCapabilities capabilities() const noexcept override {
    hil::DriveCapabilities c;
    c.homing = homing_supported;
    c.drive_profile = drive_profile;
    return c;
  }
  void read(const hil::CycleTime&) override {
    fb_.position_inc = position;
    fb_.age = age;
    fb_.fault = fault;
    if (fault) state_ = hil::DriveState::fault;
    fb_.state = state_;
    fb_.homing_active = homing_left_ > 0;
    fb_.referenced = referenced_;
  }
  void write(const hil::CycleTime&, const hil::DriveCommand& c) override {
    commands.push_back(c);
    history_.push_back(c.position_inc);
    if (history_.size() > lag + 1) history_.pop_front();
    if (enable_left_ > 0 && --enable_left_ == 0) state_ = hil::DriveState::operation_enabled;
    if (homing_left_ > 0 && --homing_left_ == 0) {
      referenced_ = true;
      position = 0;
      history_.assign(history_.size(), 0);
    }
    if (drive_profile) {
      if (state_ == hil::DriveState::operation_enabled && c.move.kind == hil::DriveMove::Kind::position)
        position = c.move.target_inc - offset;
    } else if (follow && state_ == hil::DriveState::operation_enabled && homing_left_ == 0) {
      position = history_.front() - offset;
    }
  }
  const hil::DriveFeedback& feedback() const noexcept override { return fb_; }
  bool request(hil::DriveRequest r) override {
    requests.push_back(r);
    switch (r) {
      case hil::DriveRequest::enable:
        if (!never_enable) enable_left_ = enable_cycles;
        return true;
      case hil::DriveRequest::disable:
        state_ = hil::DriveState::switch_on_disabled;
        return true;
      case hil::DriveRequest::quick_stop:
        return true;
      case hil::DriveRequest::fault_reset:
        fault = {};
        state_ = hil::DriveState::switch_on_disabled;
        return true;
      case hil::DriveRequest::home:
        if (!homing_supported) return false;
        homing_left_ = homing_cycles;
        return true;
    }
    return false;
  }
  /// The command the axis wrote `back` cycles ago (0 = last).
  std::int64_t written(std::size_t back = 0) const { return commands[commands.size() - 1 - back].position_inc; }

 private:
  hil::DriveFeedback fb_;
  hil::DriveState state_ = hil::DriveState::switch_on_disabled;
  int enable_left_ = 0;
  int homing_left_ = 0;
  bool referenced_ = false;
  std::deque<std::int64_t> history_;
};

}  // namespace hil::motion::test
