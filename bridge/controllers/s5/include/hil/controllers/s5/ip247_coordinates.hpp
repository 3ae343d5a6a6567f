// SPDX-License-Identifier: MIT
#pragma once
// The IP247 coordinate model (digest ip247.md §2.5, manual §2.6.6.6/7, §4.2.3, §4.3.5-4.3.9).
// p = internal position of the slide in BU (pulses x resolution, the reference-point frame);
// displayed actual value x = p + Z + T with
//   Z = zero_ba (BA12/BA13, cleared by BA14) + zero_prog (G54..G57 = -MD value, G53 = 0),
//   T = tool_ba (BA15, replaces everything) + tool_prog (G43 +MD, G44 -MD, G40 = 0; BA16 clears both).
// Rotary axes display x wrapped into [start + Z, end + Z) (a zero offset re-maps the number range,
// a tool offset rotates the coordinate system). Pure.

#include <cstdint>

namespace hil::controllers::s5 {

struct Ip247Offsets {
  std::int64_t zero_ba = 0;
  std::int64_t zero_prog = 0;
  std::int64_t tool_ba = 0;
  std::int64_t tool_prog = 0;
  [[nodiscard]] std::int64_t zero() const noexcept { return zero_ba + zero_prog; }
  [[nodiscard]] std::int64_t tool() const noexcept { return tool_ba + tool_prog; }
  friend bool operator==(const Ip247Offsets&, const Ip247Offsets&) = default;
};

/// Floor modulo (result in [0, m) for m > 0).
[[nodiscard]] constexpr std::int64_t ip247_mod(std::int64_t a, std::int64_t m) noexcept {
  const std::int64_t r = a % m;
  return r < 0 ? r + m : r;
}

/// -1, 0 or +1.
[[nodiscard]] constexpr int ip247_sign(std::int64_t v) noexcept {
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

/// Rotary direction rule for absolute targets (G25/G26/G27, BA6 Start/Vorwärts/Rückwärts).
enum class Ip247Rotary : std::uint8_t { shortest, forward, backward };

/// Signed move on a circle of `range` from internal angle `from` to `to` (both BU, unwrapped):
/// shortest path with the tie going forward (preferred direction; backlash ignored), or forced
/// forward/backward, where a forced move to the current angle is one full revolution.
[[nodiscard]] constexpr std::int64_t ip247_rotary_delta(std::int64_t from, std::int64_t to, std::int64_t range,
                                                        Ip247Rotary rule) noexcept {
  const std::int64_t d = ip247_mod(to - from, range);
  switch (rule) {
    case Ip247Rotary::forward:
      return d == 0 ? range : d;
    case Ip247Rotary::backward:
      return d == 0 ? -range : d - range;
    case Ip247Rotary::shortest:
      break;
  }
  if (d == 0) return 0;
  return d <= range - d ? d : d - range;
}

}  // namespace hil::controllers::s5
