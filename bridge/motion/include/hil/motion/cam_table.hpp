// SPDX-License-Identifier: MIT
#pragma once
// A cam (function) table: slave position y as a function of master position x, given by
// interpolation points. Pure data once built; lookups are noexcept and allocation-free.
//
//   x_0 = 0 < x_1 < ... < x_{n-1} = X (the table's master length: Xme in distance mode, Te in
//   time mode), y_0 = 0 (every table starts at 0 and moves the slave relatively, as the
//   AMKASYN SF tables do). Between points:
//   - linear:          the SF interpolation (FIPW/FIPZ/XFIPW): y = y_i + (y_{i+1}-y_i)(x-x_i)/h_i; C0;
//   - cubic_natural:   cubic spline with y'' = 0 at both ends; C2 inside;
//   - cubic_clamped:   cubic spline with given end slopes (0 = start/stop at rest); C2 inside, C1 at the ends;
//   - cubic_periodic:  cubic spline with y'(0) = y'(X) and y''(0) = y''(X): C2 across the period seam
//                      (periodic tables only).
// A periodic table repeats every X with cumulative continuation: after k whole periods the slave
// stands at k*Y + y(x mod X), Y = y_{n-1} (the lift per period, 0 for a back-and-forth cam).
// A periodic table's X and Y must be whole increments so the continuation is exact.

#include <cstdint>
#include <expected>
#include <string>
#include <vector>

namespace hil::motion {

enum class CamInterpolation : std::uint8_t { linear, cubic_natural, cubic_clamped, cubic_periodic };
[[nodiscard]] const char* to_string(CamInterpolation i) noexcept;

struct CamPoint {
  double x = 0.0;  ///< master position (master increments, or time units)
  double y = 0.0;  ///< slave position (slave increments)
};

struct CamTableSpec {
  std::vector<CamPoint> points;  ///< >= 2; x strictly increasing from 0; y_0 = 0
  CamInterpolation interpolation = CamInterpolation::linear;
  bool periodic = false;
  double start_slope = 0.0;  ///< cubic_clamped: dy/dx at x = 0
  double end_slope = 0.0;    ///< cubic_clamped: dy/dx at x = X
};

/// y, dy/dx and d2y/dx2 at one x.
struct CamSample {
  double y = 0.0, dy = 0.0, d2y = 0.0;
};

class CamTable {
 public:
  /// Builds the table; an error names the point and the rule ("point 3: x = 10 is not above
  /// point 2's x = 10").
  [[nodiscard]] static std::expected<CamTable, std::string> make(const CamTableSpec& spec);

  /// y at x; x is clamped into [0, X]. `hint` caches the segment for monotone lookups.
  [[nodiscard]] double value(double x, std::size_t& hint) const noexcept;
  [[nodiscard]] CamSample sample(double x, std::size_t& hint) const noexcept;
  [[nodiscard]] double value(double x) const noexcept {
    std::size_t h = 0;
    return value(x, h);
  }

  [[nodiscard]] double length() const noexcept { return x_.back(); }  ///< X
  [[nodiscard]] double lift() const noexcept { return lift_; }        ///< Y = y at X
  [[nodiscard]] bool periodic() const noexcept { return periodic_; }
  [[nodiscard]] CamInterpolation interpolation() const noexcept { return interpolation_; }
  /// Order of continuity guaranteed inside the table (0 linear, 2 cubic) and, for periodic
  /// tables, the order across the seam (seam_continuity: cubic_periodic 2, the others 0).
  [[nodiscard]] int continuity() const noexcept;
  [[nodiscard]] int seam_continuity() const noexcept;
  [[nodiscard]] std::size_t size() const noexcept { return x_.size(); }

 private:
  CamTable() = default;
  [[nodiscard]] std::size_t segment(double x, std::size_t hint) const noexcept;

  std::vector<double> x_;
  std::vector<double> a_, b_, c_, d_;  ///< per segment: y = a + b t + c t^2 + d t^3, t = x - x_i
  double lift_ = 0.0;
  double inv_h_ = 0.0;  ///< 1/h for equidistant tables (0 otherwise): O(1) lookup
  bool periodic_ = false;
  CamInterpolation interpolation_ = CamInterpolation::linear;
};

}  // namespace hil::motion
