// SPDX-License-Identifier: MIT
#pragma once
// How one GPIO line is named and requested, independent of the backend.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hil::gpio {

enum class LineDirection : std::uint8_t { input, output };

/// Kernel bias (GPIO v2 uAPI / libgpiod 1.6 request flags). `as_is` leaves the chip's setting.
enum class Bias : std::uint8_t { as_is, disabled, pull_up, pull_down };

[[nodiscard]] std::string_view to_string(Bias b) noexcept;
[[nodiscard]] std::optional<Bias> parse_bias(std::string_view s) noexcept;

/// One line: by chip offset, or by line name (looked up on the chip at open time).
struct LineSpec {
  std::string role;                ///< what the line is for ("step", "ready"); used in messages
  std::optional<unsigned> offset;  ///< chip offset; exactly one of offset/name is set
  std::string name;                ///< line name as the kernel reports it (gpioinfo)
  LineDirection direction = LineDirection::output;
  bool active_low = false;  ///< the backend inverts: logical 1 = physical low
  Bias bias = Bias::as_is;
  bool initial = false;  ///< outputs: logical level at request time
};

}  // namespace hil::gpio
