// SPDX-License-Identifier: MIT
#pragma once
// A step/dir axis from a YAML drive block on the stepdir TransportFactory, on a virtual clock.
#include <gtest/gtest.h>

#include "hil/config/yaml_config.hpp"
#include "hil/core/clock.hpp"
#include "hil/drives/stepdir/axis.hpp"
#include "hil/drives/stepdir/stepdir_drive.hpp"
#include "hil/drives/stepdir/transport_factory.hpp"

struct DriveRig {
  hil::VirtualClock clock;
  hil::RunEnvironment env{clock, true, nullptr, "", std::chrono::milliseconds(1), false, {}};
  hil::drives::stepdir::StepDirTransportFactory factory;
  hil::DrivePtr drive;
  hil::drives::stepdir::StepDirDrive* sd = nullptr;
  hil::Duration period = std::chrono::milliseconds(1);

  explicit DriveRig(const std::string& yaml) {
    env.verify_edge_streams = true;
    auto node = YAML::Load(yaml);
    auto d = factory.make_drive("x", node, env);
    if (!d) {
      ADD_FAILURE() << d.error().describe();
      return;
    }
    drive = std::move(*d);
    sd = factory.axes().back()->drive;  // the StepDirDrive inside the drive handed out
  }
  hil::drives::stepdir::StepDirTransportFactory::Axis& axis() { return *factory.axes().front(); }
  void cycle(std::int64_t position) {
    hil::CycleTime c{clock.now(), period};
    drive->read(c);
    drive->write(c, hil::DriveCommand{hil::CommandMode::position, position, 0.0, 0.0});
    clock.advance(period);
  }
  /// Run cycles holding `position` until pred() or max cycles.
  template <class Pred>
  bool run_until(std::int64_t position, Pred pred, int max_cycles = 200'000) {
    for (int i = 0; i < max_cycles; ++i) {
      cycle(position);
      if (pred()) return true;
    }
    return false;
  }
  /// Refresh feedback without a new command (what the next cycle's read() will show).
  void refresh() { drive->read(hil::CycleTime{clock.now(), period}); }
  bool enable() {
    drive->request(hil::DriveRequest::enable);
    return run_until(
        drive->feedback().position_inc, [&] { return drive->feedback().state == hil::DriveState::operation_enabled; },
        5'000);
  }
  std::int64_t plant_position() { return axis().decoder->position_at(clock.now().time_since_epoch().count()); }
  void expect_clean() {
    auto rep = factory.finish(hil::CycleTime{clock.now(), period});
    EXPECT_TRUE(rep.ok);
    for (const auto& l : rep.lines) EXPECT_EQ(l.find("VIOLATION"), std::string::npos) << l;
  }
};
