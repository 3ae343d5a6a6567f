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

}  // namespace hil::mocks::legacy
