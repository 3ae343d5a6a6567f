// SPDX-License-Identifier: MIT
#pragma once
// A drive's digital I/O on the I/O image (scenario `io_links: - drive: AXIS`): DriveInputs copies
// bits of the axis' drive inputs (DriveFeedback::digital_inputs, CiA 402 0x60FD layout: limit
// switches, home switch, interlock, manufacturer bits 16..31) into image bits once per controller
// cycle (an IoSource); DriveOutputs copies image bits into the axis' digital outputs, which the
// axis carries in every DriveCommand (0x60FE:1 layout) from its next update (an IoSink). One
// drive interface: any transport whose DriveCapabilities has digital I/O (CiA 402, `sim`).
// Thread: the cycle thread; both only copy bits (noexcept, no allocation, never block).

#include <cstdint>
#include <vector>

#include "hil/controllers/io_image.hpp"
#include "hil/motion/axis.hpp"

namespace hil::controllers {

struct DriveIoBit {
  std::uint8_t drive_bit = 0;  ///< 0..31 of the drive's digital inputs / outputs
  BitAddress bit;              ///< image bit
};

class DriveInputs final : public IoSource {
 public:
  DriveInputs(const motion::Axis& axis, std::vector<DriveIoBit> map) : axis_(axis), map_(std::move(map)) {}
  void read(TimePoint now, IoImage& image) noexcept override;

 private:
  const motion::Axis& axis_;
  std::vector<DriveIoBit> map_;
};

class DriveOutputs final : public IoSink {
 public:
  DriveOutputs(motion::Axis& axis, std::vector<DriveIoBit> map);
  void write(TimePoint now, const IoImage& image) noexcept override;

 private:
  motion::Axis& axis_;
  std::vector<DriveIoBit> map_;
  std::uint32_t mask_ = 0;  ///< the drive bits this sink owns (other sinks may own others)
};

}  // namespace hil::controllers
