// SPDX-License-Identifier: MIT
#pragma once
// The one GPIO line interface: a bank of requested lines addressed by index. The libgpiod
// backend (protocols/gpio/linux) and the mock (mocks/gpio) implement it, so a step/dir drive
// runs unchanged on a real chip and in CI.

#include <cstddef>
#include <expected>
#include <system_error>

namespace hil::gpio {

class LineBank {
 public:
  virtual ~LineBank() = default;

  [[nodiscard]] virtual std::size_t size() const noexcept = 0;
  /// Drive output `index` to logical `level`. Non-blocking (one ioctl on a real chip).
  /// Thread: one writer at a time. Errors: std::errc::invalid_argument for an input or a bad index,
  /// otherwise the backend's errno.
  virtual std::error_code set_value(std::size_t index, bool level) noexcept = 0;
  /// Read the logical level of `index` (input, or an output's last written value).
  /// Non-blocking. Thread: any one thread at a time.
  [[nodiscard]] virtual std::expected<bool, std::error_code> get_value(std::size_t index) noexcept = 0;
};

}  // namespace hil::gpio
