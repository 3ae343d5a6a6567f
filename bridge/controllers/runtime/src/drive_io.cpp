// SPDX-License-Identifier: MIT
#include "hil/controllers/drive_io.hpp"

namespace hil::controllers {

void DriveInputs::read(TimePoint, IoImage& image) noexcept {
  const std::uint32_t inputs = axis_.digital_inputs();
  for (const auto& m : map_) image.set(m.bit, ((inputs >> (m.drive_bit & 31U)) & 1U) != 0);
}

DriveOutputs::DriveOutputs(motion::Axis& axis, std::vector<DriveIoBit> map) : axis_(axis), map_(std::move(map)) {
  for (const auto& m : map_) mask_ |= 1U << (m.drive_bit & 31U);
}

void DriveOutputs::write(TimePoint, const IoImage& image) noexcept {
  std::uint32_t value = 0;
  for (const auto& m : map_)
    if (image.get(m.bit)) value |= 1U << (m.drive_bit & 31U);
  axis_.set_digital_outputs(mask_, value);
}

}  // namespace hil::controllers
