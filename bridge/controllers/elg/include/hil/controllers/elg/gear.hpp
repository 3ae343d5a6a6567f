// SPDX-License-Identifier: MIT
#pragma once
// The hobbing linkage of the SINUMERIK System 3 ELG (manual 2.2-2.4, digest §2), in encoder counts:
//
//   phi2set = phi0 * Z0/Z2 + s_z * ud_z/Z2 + s_y * ud_y/Z2          [deg]
//
// evaluated as C counts from B, Z and Y counts relative to the positions latched at Gearing ON.
// Every constant is an exact rational number: the set value is computed from the totals since
// engagement with exact integer quotients, never by summing rounded per-cycle increments, so it
// cannot drift over hours of hobbing.

#include <cstdint>
#include <expected>
#include <string>

#include "hil/controllers/elg/alarm.hpp"

namespace hil::controllers::elg {

/// An R parameter with five decimals, as the ELG holds ud_z and ud_y (range 0..999.99999, signed):
/// value = e5 / 100000.
struct Decimal5 {
  std::int64_t e5 = 0;
  static constexpr std::int64_t scale = 100000;
  double value() const noexcept { return static_cast<double>(e5) / static_cast<double>(scale); }
  /// Parses "8.18511", "-0.5", "12" (at most 5 decimals). Error text says what is wrong.
  static std::expected<Decimal5, std::string> parse(std::string_view text);
  /// Rounds a real value to 5 decimals.
  static Decimal5 from_double(double value) noexcept;
};

/// The ELG input parameters of ch. 5 (R20, R21, R60, R61).
struct GearInput {
  std::int32_t z0 = 0;  ///< R20: hob threads / shaper teeth, -999..999; negative = up milling
  std::int32_t z2 = 0;  ///< R21: workpiece teeth, 2..999
  Decimal5 ud_z;        ///< R61 "AXIAL": differential constant, deg per mm of Z
  Decimal5 ud_y;        ///< R60 "TANG": differential constant, deg per mm of Y
};

/// The machine data the constants depend on (digest §2.5, §2.6, §9.1).
struct GearMachineData {
  std::int64_t n00 = 180000;             ///< MD 396* of the guide axis B: pulses per revolution (before x4)
  std::int64_t n02 = 180000;             ///< MD 396* of the drive axis C
  std::int64_t ms_z_nm = 500;            ///< measuring-system unit of Z in nm per count (MD 5002: 0.5 um)
  std::int64_t ms_y_nm = 500;            ///< measuring-system unit of Y in nm per count
  std::int32_t contour_factor_c = 1666;  ///< MD 252* of C (0.01 1/s); < 200 gives alarm 2200
  std::int32_t hae_speed = 1000;         ///< MD 170: HAE speed, 1/1000 rpm, max 30000 (alarm 2200)
  bool axis_declaration_ok = true;       ///< MD 5020/5021 declare drive and guide axes in order
  /// [I] The manual's "transmission / differential parameter too high" (2203) as a number: the most
  /// C counts one count of B, Z or Y may move (profile option `max_constant`).
  std::int64_t max_constant = 65536;
};

/// An exact ratio num/den (den > 0), reduced.
struct Rational {
  std::int64_t num = 0;
  std::int64_t den = 1;
};

/// The gearing constants the ELG computes on "Compute gearing constants" (digest §2.5, §3.2):
/// C counts per B count, per Z count and per Y count.
struct GearConstants {
  Rational c_per_b;
  Rational c_per_z;
  Rational c_per_y;
  std::int64_t pitch_counts = 0;  ///< one tooth pitch N02/Z2 pulses, in C counts (x4): 4*N02/Z2
  Rational pitch;                 ///< the exact pitch when 4*N02 is not a multiple of Z2
};

/// The compute step with its validation: alarm 2200 (machine data: contour factor < 200, pulses per
/// revolution > 2 000 000, HAE speed > 30000, axis declaration) and 2203 (Z2 = 0; N02 = 0 with
/// Z0 != 0; a constant of more than `max_constant` C counts per input count, the manual's
/// "transmission / differential parameter too high").
std::expected<GearConstants, Alarm> compute_constants(const GearInput& input, const GearMachineData& md);

/// The linkage latched at Gearing ON: c_set(b, z, y) = c0 + (b-b0)*kb + (z-z0)*kz + (y-y0)*ky,
/// rounded to the nearest count (halves up), with exact 128-bit quotients.
class Linkage {
 public:
  Linkage() = default;
  /// Latches the engagement positions. `with_cutter` = false drops the B term (single pitch, 4.3).
  Linkage(const GearConstants& constants, std::int64_t b0, std::int64_t z0, std::int64_t y0, std::int64_t c0,
          bool with_cutter) noexcept;

  /// The C set value for the current B, Z, Y counts; std::nullopt-like failure (alarm 2202) when
  /// the result does not fit 64 bits.
  std::expected<std::int64_t, Alarm> c_set(std::int64_t b, std::int64_t z, std::int64_t y) const noexcept;

  bool with_cutter() const noexcept { return with_cutter_; }
  std::int64_t c0() const noexcept { return c0_; }

 private:
  GearConstants k_;
  std::int64_t b0_ = 0, z0_ = 0, y0_ = 0, c0_ = 0;
  bool with_cutter_ = true;
};

/// ud_z = sin(beta0) / (m_N * pi) * 360 [deg/mm] (2.2.2): helix angle of the workpiece teeth
/// beta0 in degrees, normal module m_N in mm.
double ud_z_from_gear(double beta0_deg, double module_mm) noexcept;
/// ud_y = cos(gamma0) / (m_N * pi) * 360 [deg/mm] (2.2.3): lead angle of the hob gamma0 in degrees.
double ud_y_from_gear(double gamma0_deg, double module_mm) noexcept;

}  // namespace hil::controllers::elg
