// SPDX-License-Identifier: MIT
// Step 4 of the trajectory maths: integrating constant-jerk segments (building and sampling).
#include <algorithm>
#include <cmath>

#include "hil/motion/profile.hpp"

namespace hil::motion {
namespace {

State integrate(double p, double v, double a, double j, double t) noexcept {
  return State{p + t * (v + t * (a / 2.0 + t * j * (1.0 / 6.0))), v + t * (a + t * j / 2.0), a + t * j, j};
}

}  // namespace

void Profile::reset(const State& start) noexcept {
  n_ = 0;
  start_ = start;
  start_.j = 0.0;
  cur_ = start_;
  end_ = start_;
  duration_ = 0.0;
}

void Profile::append(double duration, double jerk) noexcept {
  if (!(duration > 0.0) || n_ == max_segments) return;
  seg_[n_++] = Segment{duration_, duration, cur_.p, cur_.v, cur_.a, jerk};
  cur_ = integrate(cur_.p, cur_.v, cur_.a, jerk, duration);
  duration_ += duration;
}

void Profile::append_accel(double duration, double accel) noexcept {
  if (!(duration > 0.0)) {
    cur_.a = accel;  // a zero-length step only sets the acceleration
    return;
  }
  if (n_ == max_segments) return;
  seg_[n_++] = Segment{duration_, duration, cur_.p, cur_.v, accel, 0.0};
  cur_ = integrate(cur_.p, cur_.v, accel, 0.0, duration);
  duration_ += duration;
}

void Profile::finish(const State& end) noexcept {
  end_ = end;
  end_.a = 0.0;
  end_.j = 0.0;
  if (n_ == 0) start_ = State{end_.p, end_.v, start_.a, 0.0};
  cur_ = end_;
}

State Profile::sample(double t, std::size_t& hint) const noexcept {
  if (t >= duration_) {
    const double dt = t - duration_;
    return State{end_.p + end_.v * dt, end_.v, 0.0, 0.0};
  }
  if (t <= 0.0 || n_ == 0) return State{start_.p, start_.v, start_.a, n_ ? seg_[0].j : 0.0};
  std::size_t i = hint < n_ ? hint : 0;
  if (seg_[i].t0 > t) i = 0;
  while (i + 1 < n_ && seg_[i + 1].t0 <= t) ++i;
  hint = i;
  const Segment& s = seg_[i];
  return integrate(s.p, s.v, s.a, s.j, t - s.t0);
}

double Profile::peak_velocity() const noexcept {
  double peak = std::max(std::fabs(start_.v), std::fabs(end_.v));
  for (std::size_t i = 0; i < n_; ++i) {
    const Segment& s = seg_[i];
    peak = std::max(peak, std::fabs(s.v));
    const State e = integrate(s.p, s.v, s.a, s.j, s.duration);
    peak = std::max(peak, std::fabs(e.v));
    if (s.j != 0.0) {
      const double tz = -s.a / s.j;
      if (tz > 0.0 && tz < s.duration) peak = std::max(peak, std::fabs(s.v - s.a * s.a / (2.0 * s.j)));
    }
  }
  return peak;
}

}  // namespace hil::motion
