// SPDX-License-Identifier: MIT
#pragma once
// Retrofit mode of the emulated CLM1.4 (`hilbridge emulate clm14 --machine machine.yaml`,
// docs/clm14.md "Retrofit mode"): the machine file's axes, each on its transport, become the
// station's axes 1..4 in file order, except the axes named `ME1` / `ME2`, which are master
// encoders 1 / 2: their actual increments are the encoder's quadrature counts (C000 / C004 × 4 per
// C002 / C006 IU) instead of the simulated measuring wheel. The CLM never commands them.
// Thread: the emulator's thread only.

#include <array>
#include <expected>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hil/controllers/clm14/motion_axis_port.hpp"
#include "hil/mocks/legacy/clm14_station.hpp"
#include "hil/motion/axis.hpp"

namespace hil::mocks::legacy {

/// The role of each machine axis: `axes` = indices of CLM axes 1..n, `encoders[k]` = the index of
/// master encoder k + 1. Error text (naming `file`) for no CLM axis, more than 4, or an encoder
/// name given twice.
struct Clm14MachineRoles {
  std::vector<std::size_t> axes;
  std::array<std::optional<std::size_t>, 2> encoders{};
};
[[nodiscard]] std::expected<Clm14MachineRoles, std::string> clm14_machine_roles(std::span<const std::string> names,
                                                                                const std::string& file);

/// The ports of a retrofit: one MotionAxisPort per CLM axis, one MotionMasterEncoder per named
/// encoder, over axes that outlive it.
class Clm14Retrofit {
 public:
  Clm14Retrofit(std::span<motion::Axis* const> axes, const Clm14MachineRoles& roles);
  /// Hands the ports to `station` (Clm14Station::use_axes / use_master_encoder); `update` advances
  /// the machine once per NC cycle after the controller's step.
  void attach(Clm14Station& station, std::function<void(const CycleTime&)> update);
  [[nodiscard]] std::size_t axis_count() const noexcept { return ports_.size(); }

 private:
  std::vector<std::unique_ptr<controllers::clm14::MotionAxisPort>> ports_;
  std::array<std::unique_ptr<controllers::clm14::MotionMasterEncoder>, 2> encoders_;
};

}  // namespace hil::mocks::legacy
