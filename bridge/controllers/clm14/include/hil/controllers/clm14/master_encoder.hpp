// SPDX-License-Identifier: MIT
#pragma once
// Master encoder 1 of the CLM1.4 (manual §8.4, digest §3.10: C000-C003, the incremental encoder 5
// on X1 - the measuring wheel of a flying cutoff, the master of a slave axis): what the model
// needs from it is its raw quadrature counter. The model unwraps it (hil::motion::EncoderInput,
// 32 bits), applies the C001 direction and scales it with C000 × 4 counts per C002 IU.
// motion_axis_port.hpp implements it on a hil::motion::Axis, so the material can be any machine
// axis on any transport. Called on the controller's cycle thread only; never blocks or throws.

#include <cstdint>

namespace hil::controllers::clm14 {

class MasterEncoderPort {
 public:
  virtual ~MasterEncoderPort() = default;
  /// The counter's low 32 bits (quadrature counts).
  [[nodiscard]] virtual std::uint32_t count() const = 0;
};

}  // namespace hil::controllers::clm14
