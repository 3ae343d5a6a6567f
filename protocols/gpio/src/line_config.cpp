// SPDX-License-Identifier: MIT
#include "hil/gpio/line_config.hpp"

namespace hil::gpio {

std::string_view to_string(Bias b) noexcept {
  switch (b) {
    case Bias::as_is:
      return "as-is";
    case Bias::disabled:
      return "disabled";
    case Bias::pull_up:
      return "pull-up";
    case Bias::pull_down:
      return "pull-down";
  }
  return "?";
}

std::optional<Bias> parse_bias(std::string_view s) noexcept {
  if (s == "as-is" || s == "as_is") return Bias::as_is;
  if (s == "disabled" || s == "none") return Bias::disabled;
  if (s == "pull-up" || s == "pull_up") return Bias::pull_up;
  if (s == "pull-down" || s == "pull_down") return Bias::pull_down;
  return std::nullopt;
}

}  // namespace hil::gpio
