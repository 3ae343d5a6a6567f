// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/gear.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "hil/motion/gear_ratio.hpp"

namespace hil::controllers::elg {
namespace {

using motion::abs128;
using motion::gcd128;
using motion::i128;  // exact 128-bit intermediate products

/// Reduces num/den; both must fit 64 bits. A constant whose magnitude exceeds `max_constant` C counts
/// per input count is the manual's "transmission / differential parameter too high" (2203).
std::expected<Rational, Alarm> make_constant(i128 num, i128 den, std::int64_t max_constant) {
  if (den == 0) return std::unexpected(Alarm::constants_error);
  if (den < 0) {
    num = -num;
    den = -den;
  }
  if (num == 0) return Rational{0, 1};
  const i128 g = gcd128(num, den);
  num /= g;
  den /= g;
  constexpr i128 limit = std::numeric_limits<std::int64_t>::max();
  if (abs128(num) > limit || den > limit) return std::unexpected(Alarm::constants_error);
  if (abs128(num) > i128{max_constant} * den) return std::unexpected(Alarm::constants_error);
  return Rational{static_cast<std::int64_t>(num), static_cast<std::int64_t>(den)};
}

/// floor(a / b) and the remainder in [0, b) for b > 0.
std::pair<i128, i128> floor_div(i128 a, i128 b) {
  i128 q = a / b;
  i128 r = a % b;
  if (r < 0) {
    q -= 1;
    r += b;
  }
  return {q, r};
}

}  // namespace

std::expected<Decimal5, std::string> Decimal5::parse(std::string_view text) {
  std::string_view s = text;
  bool negative = false;
  if (!s.empty() && (s.front() == '+' || s.front() == '-')) {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  const auto dot = s.find('.');
  const std::string_view whole = s.substr(0, dot);
  const std::string_view frac = dot == std::string_view::npos ? std::string_view{} : s.substr(dot + 1);
  if (whole.empty() && frac.empty()) return std::unexpected("'" + std::string(text) + "' is not a number");
  if (frac.size() > 5) return std::unexpected("'" + std::string(text) + "' has more than 5 decimals");
  if (whole.size() > 9) return std::unexpected("'" + std::string(text) + "' is out of range");
  std::int64_t w = 0;
  for (char ch : whole) {
    if (ch < '0' || ch > '9') return std::unexpected("'" + std::string(text) + "' is not a number");
    w = w * 10 + (ch - '0');
  }
  std::int64_t f = 0;
  for (std::size_t i = 0; i < 5; ++i) {
    const char ch = i < frac.size() ? frac[i] : '0';
    if (ch < '0' || ch > '9') return std::unexpected("'" + std::string(text) + "' is not a number");
    f = f * 10 + (ch - '0');
  }
  const std::int64_t e5 = w * scale + f;
  return Decimal5{negative ? -e5 : e5};
}

Decimal5 Decimal5::from_double(double value) noexcept {
  return Decimal5{static_cast<std::int64_t>(std::llround(value * static_cast<double>(scale)))};
}

std::expected<GearConstants, Alarm> compute_constants(const GearInput& input, const GearMachineData& md) {
  // Alarm 2200 first: it concerns the machine data, whatever the parameters (10.3).
  constexpr std::int64_t max_pulses = 2000000;
  if (md.contour_factor_c < 200 || md.n00 > max_pulses || md.n02 > max_pulses || md.hae_speed > 30000 || md.n00 < 0 ||
      md.n02 < 0 || !md.axis_declaration_ok) {
    return std::unexpected(Alarm::power_on_error);
  }
  if (input.z2 == 0) return std::unexpected(Alarm::constants_error);
  if (md.n02 == 0 && input.z0 != 0) return std::unexpected(Alarm::constants_error);
  if (md.n00 == 0 && input.z0 != 0) return std::unexpected(Alarm::constants_error);
  if (input.z2 < 0) return std::unexpected(Alarm::constants_error);

  GearConstants k;
  // C counts per B count: both encoders are quadrupled, so the x4 cancels.
  if (input.z0 == 0) {
    k.c_per_b = {0, 1};
  } else {
    auto kb = make_constant(i128{input.z0} * md.n02, i128{input.z2} * md.n00, md.max_constant);
    if (!kb) return std::unexpected(kb.error());
    k.c_per_b = *kb;
  }
  // C counts per Z count: ms [nm] / 1e6 [mm] * ud [deg/mm] / Z2 * (4 N02 / 360) [counts/deg].
  const i128 diff_den = i128{1000000} * Decimal5::scale * input.z2 * 360;
  auto kz = make_constant(i128{md.ms_z_nm} * input.ud_z.e5 * 4 * md.n02, diff_den, md.max_constant);
  if (!kz) return std::unexpected(kz.error());
  auto ky = make_constant(i128{md.ms_y_nm} * input.ud_y.e5 * 4 * md.n02, diff_den, md.max_constant);
  if (!ky) return std::unexpected(ky.error());
  k.c_per_z = *kz;
  k.c_per_y = *ky;
  auto pitch = make_constant(i128{4} * md.n02, input.z2, std::numeric_limits<std::int64_t>::max());
  if (!pitch) return std::unexpected(pitch.error());
  k.pitch = *pitch;
  k.pitch_counts = pitch->num / pitch->den;
  return k;
}

Linkage::Linkage(const GearConstants& constants, std::int64_t b0, std::int64_t z0, std::int64_t y0, std::int64_t c0,
                 bool with_cutter) noexcept
    : k_(constants), b0_(b0), z0_(z0), y0_(y0), c0_(c0), with_cutter_(with_cutter) {}

std::expected<std::int64_t, Alarm> Linkage::c_set(std::int64_t b, std::int64_t z, std::int64_t y) const noexcept {
  const i128 db = with_cutter_ ? i128{b} - b0_ : 0;
  const i128 dz = i128{z} - z0_;
  const i128 dy = i128{y} - y0_;
  constexpr i128 max_delta = i128{1} << 62;
  if (abs128(db) > max_delta || abs128(dz) > max_delta || abs128(dy) > max_delta) {
    return std::unexpected(Alarm::partial_set_value_overflow);
  }
  // Each term as an exact quotient and a remainder; only the three fractional parts (each in
  // [0, 1)) are added in long double and rounded once, so the set value never drifts.
  const auto [qb, rb] = floor_div(db * k_.c_per_b.num, k_.c_per_b.den);
  const auto [qz, rz] = floor_div(dz * k_.c_per_z.num, k_.c_per_z.den);
  const auto [qy, ry] = floor_div(dy * k_.c_per_y.num, k_.c_per_y.den);
  const long double frac = static_cast<long double>(rb) / static_cast<long double>(k_.c_per_b.den) +
                           static_cast<long double>(rz) / static_cast<long double>(k_.c_per_z.den) +
                           static_cast<long double>(ry) / static_cast<long double>(k_.c_per_y.den);
  const auto rounded = static_cast<i128>(std::floor(frac + 0.5L));
  const i128 total = i128{c0_} + qb + qz + qy + rounded;
  if (total > std::numeric_limits<std::int64_t>::max() || total < std::numeric_limits<std::int64_t>::min()) {
    return std::unexpected(Alarm::partial_set_value_overflow);
  }
  return static_cast<std::int64_t>(total);
}

double ud_z_from_gear(double beta0_deg, double module_mm) noexcept {
  return std::sin(beta0_deg * std::numbers::pi / 180.0) / (module_mm * std::numbers::pi) * 360.0;
}

double ud_y_from_gear(double gamma0_deg, double module_mm) noexcept {
  return std::cos(gamma0_deg * std::numbers::pi / 180.0) / (module_mm * std::numbers::pi) * 360.0;
}

}  // namespace hil::controllers::elg
