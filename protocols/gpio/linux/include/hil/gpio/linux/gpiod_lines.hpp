// SPDX-License-Identifier: MIT
#pragma once
// LineBank on a kernel GPIO chip through libgpiod 1.6 (Debian 12's API: gpiod_chip /
// gpiod_line_request with ACTIVE_LOW and BIAS_* flags). One object = one set of requested lines.

#include <expected>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hil/gpio/line_bank.hpp"
#include "hil/gpio/line_config.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace hil::gpio::linux_gpiod {

/// An error at open time: what, which chip/line, the errno.
struct OpenError {
  std::string message;  ///< "gpiochip3: line 'step' (offset 9): Device or resource busy"
  std::error_code code;
};

class GpiodLines final : public LineBank {
 public:
  /// Open `chip` ("gpiochip0", "/dev/gpiochip0", a label or a number, as gpiod_chip_open_lookup
  /// accepts) and request every line in `specs` with `consumer` as the consumer label.
  /// Blocking (a few ioctls). Thread: any.
  [[nodiscard]] static std::expected<std::unique_ptr<GpiodLines>, OpenError> open(
      std::string_view chip, const std::vector<LineSpec>& specs, std::string_view consumer = "hilbridge");

  ~GpiodLines() override;
  GpiodLines(const GpiodLines&) = delete;
  GpiodLines& operator=(const GpiodLines&) = delete;

  [[nodiscard]] std::size_t size() const noexcept override { return lines_.size(); }
  std::error_code set_value(std::size_t index, bool level) noexcept override;
  [[nodiscard]] std::expected<bool, std::error_code> get_value(std::size_t index) noexcept override;

  /// Chip offset of the line at `index` (after name lookup).
  [[nodiscard]] unsigned offset(std::size_t index) const noexcept;
  [[nodiscard]] const std::string& chip_name() const noexcept { return chip_name_; }

 private:
  GpiodLines() = default;
  gpiod_chip* chip_ = nullptr;
  std::string chip_name_;
  std::vector<gpiod_line*> lines_;
  std::vector<LineDirection> directions_;
};

}  // namespace hil::gpio::linux_gpiod
