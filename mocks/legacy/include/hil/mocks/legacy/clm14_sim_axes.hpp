// SPDX-License-Identifier: MIT
#pragma once
// The axes of an emulated CLM1.4 without hardware: one hil::motion::Axis in IU per enabled axis
// over a simulated servo (SimDrive: Kv loop, velocity lag), built from the CLM parameters and
// rebuilt when they change (keeping the position). Thread: the emulator's thread only.

#include <array>
#include <memory>

#include "hil/controllers/clm14/motion_axis_port.hpp"
#include "hil/controllers/clm14/settings.hpp"
#include "hil/core/drive.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace hil::mocks::legacy {

class Clm14SimAxes {
 public:
  /// Create or re-create the axes that `s` enables (positions are kept across a rebuild).
  void rebuild(const controllers::clm14::Settings& s);
  /// Port of axis 1..4, or null when that axis is not enabled.
  [[nodiscard]] controllers::clm14::AxisPort* port(int axis) const;
  void update(const CycleTime& cycle);

 private:
  struct Slot {
    std::unique_ptr<motion::Axis> axis;
    std::unique_ptr<controllers::clm14::MotionAxisPort> port;
    controllers::clm14::AxisSettings built;
  };
  std::array<Slot, 4> slots_;
};

/// Master encoder 1 of an emulated CLM1.4 (the measuring wheel on the material): a hil::motion::Axis
/// in IU over a simulated drive whose increments are the C000 × 4 counts per C002 IU
/// (master_encoder_config), rebuilt when C000-C002 change (keeping the material position); none
/// while C002 = 0. The material runs at the velocity set by set_velocity (IU/s; the emulator's
/// console `material V`). Thread: the emulator's thread only.
class Clm14SimWheel {
 public:
  void rebuild(const controllers::clm14::Settings& s);
  /// The encoder port, or null when master encoder 1 is not used (C002 = 0).
  [[nodiscard]] controllers::clm14::MasterEncoderPort* port() const { return encoder_.get(); }
  /// Run the material at `iu_per_s` (0 = stop); false when there is no wheel.
  bool set_velocity(double iu_per_s);
  [[nodiscard]] double velocity() const noexcept { return velocity_; }
  void update(const CycleTime& cycle);

 private:
  std::unique_ptr<motion::Axis> axis_;
  std::unique_ptr<controllers::clm14::MotionMasterEncoder> encoder_;
  controllers::clm14::MasterEncoderSettings built_{};
  double velocity_ = 0.0;
  bool enabled_ = false;
};

}  // namespace hil::mocks::legacy
