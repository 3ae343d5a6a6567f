// SPDX-License-Identifier: MIT
// Coupling step 2: cam tables. Interpolation coefficients are computed once (splines by the
// second-derivative form: h_{i-1} M_{i-1} + 2(h_{i-1}+h_i) M_i + h_i M_{i+1} = 6 (s_i - s_{i-1}),
// s_i the secant slope of segment i), then every lookup is one cubic in Horner form.
#include "hil/motion/cam_table.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace hil::motion {
namespace {

// Thomas algorithm: sub[i] x[i-1] + diag[i] x[i] + sup[i] x[i+1] = rhs[i].
std::vector<double> solve_tridiagonal(std::vector<double> sub, std::vector<double> diag, std::vector<double> sup,
                                      std::vector<double> rhs) {
  const std::size_t n = diag.size();
  for (std::size_t i = 1; i < n; ++i) {
    const double w = sub[i] / diag[i - 1];
    diag[i] -= w * sup[i - 1];
    rhs[i] -= w * rhs[i - 1];
  }
  std::vector<double> x(n);
  x[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) x[i] = (rhs[i] - sup[i] * x[i + 1]) / diag[i];
  return x;
}

// Cyclic tridiagonal (corners sub[0] at (0, n-1) and sup[n-1] at (n-1, 0)), Sherman-Morrison; n >= 3.
std::vector<double> solve_cyclic(const std::vector<double>& sub, const std::vector<double>& diag,
                                 const std::vector<double>& sup, const std::vector<double>& rhs) {
  const std::size_t n = diag.size();
  const double alpha = sup[n - 1], beta = sub[0];
  const double gamma = -diag[0];
  std::vector<double> d2 = diag;
  d2[0] -= gamma;
  d2[n - 1] -= alpha * beta / gamma;
  std::vector<double> s = sub, p = sup;
  s[0] = 0.0;
  p[n - 1] = 0.0;
  const std::vector<double> x = solve_tridiagonal(s, d2, p, rhs);
  std::vector<double> u(n, 0.0);
  u[0] = gamma;
  u[n - 1] = alpha;
  const std::vector<double> z = solve_tridiagonal(s, d2, p, u);
  const double fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0] + beta * z[n - 1] / gamma);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = x[i] - fact * z[i];
  return out;
}

bool whole(double v) {
  return std::isfinite(v) && std::fabs(v) < 9e15 && v == std::floor(v);
}

}  // namespace

const char* to_string(CamInterpolation i) noexcept {
  switch (i) {
    case CamInterpolation::linear:
      return "linear";
    case CamInterpolation::cubic_natural:
      return "cubic_natural";
    case CamInterpolation::cubic_clamped:
      return "cubic_clamped";
    case CamInterpolation::cubic_periodic:
      return "cubic_periodic";
  }
  return "?";
}

std::expected<CamTable, std::string> CamTable::make(const CamTableSpec& spec) {
  const auto& p = spec.points;
  const std::size_t n = p.size();
  if (n < 2) return std::unexpected(fmt::format("a cam table needs at least 2 points, got {}", n));
  if (n > 100000) return std::unexpected(fmt::format("a cam table has at most 100000 points, got {}", n));
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || std::fabs(p[i].x) > 1e15 || std::fabs(p[i].y) > 1e15)
      return std::unexpected(fmt::format("point {}: x and y must be finite and below 1e15", i));
    if (i > 0 && !(p[i].x > p[i - 1].x))
      return std::unexpected(
          fmt::format("point {}: x = {} is not above point {}'s x = {}", i, p[i].x, i - 1, p[i - 1].x));
  }
  if (p[0].x != 0.0 || p[0].y != 0.0)
    return std::unexpected(fmt::format(
        "point 0 must be (0, 0): tables start at the master's and the slave's origin, got ({}, {})", p[0].x, p[0].y));
  if (spec.interpolation == CamInterpolation::cubic_periodic && !spec.periodic)
    return std::unexpected("cubic_periodic interpolation needs a periodic table");
  if (spec.interpolation == CamInterpolation::cubic_periodic && n < 4)
    return std::unexpected(fmt::format("cubic_periodic interpolation needs at least 4 points, got {}", n));
  if (spec.periodic && (!whole(p[n - 1].x) || !whole(p[n - 1].y)))
    return std::unexpected(fmt::format(
        "a periodic table's last point must be whole increments (its length and lift repeat exactly), got ({}, {})",
        p[n - 1].x, p[n - 1].y));
  if (!std::isfinite(spec.start_slope) || !std::isfinite(spec.end_slope))
    return std::unexpected("start_slope and end_slope must be finite");

  CamTable t;
  t.periodic_ = spec.periodic;
  t.interpolation_ = spec.interpolation;
  t.lift_ = p[n - 1].y;
  t.x_.resize(n);
  for (std::size_t i = 0; i < n; ++i) t.x_[i] = p[i].x;
  const std::size_t m = n - 1;  // segments
  std::vector<double> h(m), s(m);
  for (std::size_t i = 0; i < m; ++i) {
    h[i] = p[i + 1].x - p[i].x;
    s[i] = (p[i + 1].y - p[i].y) / h[i];
  }
  bool equidistant = true;
  for (std::size_t i = 1; i < m; ++i)
    if (std::fabs(h[i] - h[0]) > 1e-12 * h[0]) equidistant = false;
  t.inv_h_ = equidistant ? static_cast<double>(m) / p[n - 1].x : 0.0;

  std::vector<double> M(n, 0.0);  // second derivatives at the points
  switch (spec.interpolation) {
    case CamInterpolation::linear:
      break;
    case CamInterpolation::cubic_natural:
      if (n >= 3) {
        const std::size_t k = n - 2;
        std::vector<double> sub(k), diag(k), sup(k), rhs(k);
        for (std::size_t j = 0; j < k; ++j) {
          const std::size_t i = j + 1;
          sub[j] = h[i - 1];
          diag[j] = 2.0 * (h[i - 1] + h[i]);
          sup[j] = h[i];
          rhs[j] = 6.0 * (s[i] - s[i - 1]);
        }
        const auto x = solve_tridiagonal(sub, diag, sup, rhs);
        for (std::size_t j = 0; j < k; ++j) M[j + 1] = x[j];
      }
      break;
    case CamInterpolation::cubic_clamped: {
      std::vector<double> sub(n), diag(n), sup(n), rhs(n);
      diag[0] = 2.0 * h[0];
      sup[0] = h[0];
      rhs[0] = 6.0 * (s[0] - spec.start_slope);
      for (std::size_t i = 1; i + 1 < n; ++i) {
        sub[i] = h[i - 1];
        diag[i] = 2.0 * (h[i - 1] + h[i]);
        sup[i] = h[i];
        rhs[i] = 6.0 * (s[i] - s[i - 1]);
      }
      sub[n - 1] = h[m - 1];
      diag[n - 1] = 2.0 * h[m - 1];
      rhs[n - 1] = 6.0 * (spec.end_slope - s[m - 1]);
      M = solve_tridiagonal(sub, diag, sup, rhs);
      break;
    }
    case CamInterpolation::cubic_periodic: {
      // Unknowns M_0..M_{m-1}, M_m = M_0; the segment before 0 is segment m-1 shifted by a period.
      std::vector<double> sub(m), diag(m), sup(m), rhs(m);
      for (std::size_t i = 0; i < m; ++i) {
        const std::size_t prev = i == 0 ? m - 1 : i - 1;
        sub[i] = h[prev];
        diag[i] = 2.0 * (h[prev] + h[i]);
        sup[i] = h[i];
        rhs[i] = 6.0 * (s[i] - s[prev]);
      }
      const auto x = solve_cyclic(sub, diag, sup, rhs);
      for (std::size_t i = 0; i < m; ++i) M[i] = x[i];
      M[m] = M[0];
      break;
    }
  }
  t.a_.resize(m);
  t.b_.resize(m);
  t.c_.resize(m);
  t.d_.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    t.a_[i] = p[i].y;
    t.b_[i] = s[i] - h[i] * (2.0 * M[i] + M[i + 1]) / 6.0;
    t.c_[i] = M[i] / 2.0;
    t.d_[i] = (M[i + 1] - M[i]) / (6.0 * h[i]);
  }
  return t;
}

std::size_t CamTable::segment(double x, std::size_t hint) const noexcept {
  const std::size_t m = a_.size();
  if (inv_h_ > 0.0) {
    const auto i = static_cast<std::size_t>(x * inv_h_);
    return i < m ? i : m - 1;
  }
  if (hint < m && x >= x_[hint] && x <= x_[hint + 1]) return hint;
  if (hint + 1 < m && x >= x_[hint + 1] && x <= x_[hint + 2]) return hint + 1;
  if (hint > 0 && hint <= m && x >= x_[hint - 1] && x <= x_[hint]) return hint - 1;
  const auto it = std::upper_bound(x_.begin(), x_.end(), x);
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - x_.begin() - 1, 0));
  return i < m ? i : m - 1;
}

double CamTable::value(double x, std::size_t& hint) const noexcept {
  x = std::clamp(x, 0.0, x_.back());
  const std::size_t i = segment(x, hint);
  hint = i;
  const double t = x - x_[i];
  return a_[i] + t * (b_[i] + t * (c_[i] + t * d_[i]));
}

CamSample CamTable::sample(double x, std::size_t& hint) const noexcept {
  const bool outside = x < 0.0 || x > x_.back();
  x = std::clamp(x, 0.0, x_.back());
  const std::size_t i = segment(x, hint);
  hint = i;
  const double t = x - x_[i];
  CamSample s;
  s.y = a_[i] + t * (b_[i] + t * (c_[i] + t * d_[i]));
  if (!outside) {
    s.dy = b_[i] + t * (2.0 * c_[i] + 3.0 * t * d_[i]);
    s.d2y = 2.0 * c_[i] + 6.0 * t * d_[i];
  }
  return s;
}

int CamTable::continuity() const noexcept {
  return interpolation_ == CamInterpolation::linear ? 0 : 2;
}

int CamTable::seam_continuity() const noexcept {
  return interpolation_ == CamInterpolation::cubic_periodic ? 2 : 0;
}

}  // namespace hil::motion
