// SPDX-License-Identifier: MIT
#pragma once
// An exact, signed gear ratio (slave increments per master increment = num / den) and the
// integer helpers the coupling maths uses (floor division, 128-bit products).

#include <cstdint>

namespace hil::motion {

/// 128-bit signed integer (a GCC/Clang extension) for exact products of 64-bit terms.
__extension__ typedef __int128 i128;

/// Slave increments per master increment = num / den exactly. den > 0; |num|, den <= 2^31
/// (so every product the gear forms fits 128 bits). num = 0 is a disengaged gear.
struct GearRatio {
  std::int64_t num = 0;
  std::int64_t den = 1;
  [[nodiscard]] double value() const noexcept { return static_cast<double>(num) / static_cast<double>(den); }
  friend bool operator==(const GearRatio&, const GearRatio&) = default;
};

inline constexpr std::int64_t max_gear_term = std::int64_t{1} << 31;

[[nodiscard]] constexpr bool valid(const GearRatio& r) noexcept {
  return r.den > 0 && r.den <= max_gear_term && r.num >= -max_gear_term && r.num <= max_gear_term;
}

/// floor(a / b) for b > 0 (C++ division truncates towards zero).
[[nodiscard]] constexpr std::int64_t floor_div(std::int64_t a, std::int64_t b) noexcept {
  const std::int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}
/// a mod b in [0, b) for b > 0 (the remainder of floor_div; C++'s % keeps the sign of a).
[[nodiscard]] constexpr std::int64_t floor_mod(std::int64_t a, std::int64_t b) noexcept {
  const std::int64_t r = a % b;
  return r < 0 ? r + b : r;
}
[[nodiscard]] constexpr i128 floor_div(i128 a, i128 b) noexcept {
  const i128 q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

/// |v| (std::abs has no 128-bit overload).
[[nodiscard]] constexpr i128 abs128(i128 v) noexcept {
  return v < 0 ? -v : v;
}

/// Greatest common divisor of |a| and |b|, for reducing exact ratios (std::gcd takes no __int128).
[[nodiscard]] constexpr i128 gcd128(i128 a, i128 b) noexcept {
  a = abs128(a);
  b = abs128(b);
  while (b != 0) {
    const i128 r = a % b;
    a = b;
    b = r;
  }
  return a;
}

}  // namespace hil::motion
