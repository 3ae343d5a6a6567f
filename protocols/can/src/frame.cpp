// SPDX-License-Identifier: MIT
#include "hil/can/frame.hpp"

#include <algorithm>
#include <cassert>

namespace hil::can {

namespace {
Frame make_data(std::uint32_t id, bool extended, std::span<const std::uint8_t> bytes) noexcept {
  assert(bytes.size() <= 8 && "a classic CAN frame carries at most 8 bytes");
  Frame f;
  f.extended = extended;
  f.id = id & (extended ? eff_mask : sff_mask);
  const auto n = std::min<std::size_t>(bytes.size(), 8);
  std::copy_n(bytes.begin(), n, f.data.begin());
  f.dlc = static_cast<std::uint8_t>(n);
  return f;
}
}  // namespace

Frame make_frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) noexcept {
  return make_data(id, false, std::span<const std::uint8_t>(bytes.begin(), bytes.size()));
}
Frame make_frame(std::uint32_t id, std::span<const std::uint8_t> bytes) noexcept {
  return make_data(id, false, bytes);
}
Frame make_extended_frame(std::uint32_t id, std::span<const std::uint8_t> bytes) noexcept {
  return make_data(id, true, bytes);
}
Frame make_remote_frame(std::uint32_t id, std::uint8_t dlc, bool extended) noexcept {
  Frame f;
  f.extended = extended;
  f.id = id & (extended ? eff_mask : sff_mask);
  f.rtr = true;
  f.dlc = std::min<std::uint8_t>(dlc, 8);
  return f;
}
Frame make_error_frame(std::uint32_t error_class, std::array<std::uint8_t, 8> data) noexcept {
  Frame f;
  f.error = true;
  f.id = error_class & err_mask;
  f.dlc = 8;
  f.data = data;
  return f;
}

}  // namespace hil::can
