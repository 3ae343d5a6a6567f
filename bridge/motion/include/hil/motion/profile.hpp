// SPDX-License-Identifier: MIT
#pragma once
// A planned one-dimensional trajectory: a short list of constant-jerk segments, each holding its
// own start state, so sampling never accumulates error. After the last segment the profile
// continues at its end velocity with zero acceleration (a position move ends at rest; a
// velocity move cruises on). Pure data; sampling is noexcept and allocation-free.

#include <array>
#include <cstddef>
#include <span>

namespace hil::motion {

/// Kinematic state in user units (p), units/s (v), units/s^2 (a); `j` is the jerk of the
/// segment the sample lies in (0 when an acceleration step is taken: trapezoid).
struct State {
  double p = 0.0, v = 0.0, a = 0.0, j = 0.0;
};

struct Segment {
  double t0 = 0.0;                   ///< start time, s from the profile start
  double duration = 0.0;             ///< s
  double p = 0.0, v = 0.0, a = 0.0;  ///< state at t0
  double j = 0.0;                    ///< constant jerk in the segment
};

class Profile {
 public:
  static constexpr std::size_t max_segments = 16;

  /// Start a new profile at `start` (its `a` is the acceleration at t = 0).
  void reset(const State& start) noexcept;
  /// Append a constant-jerk segment from the current end state.
  void append(double duration, double jerk) noexcept;
  /// Append a segment of constant acceleration `accel` (a step from the current one:
  /// trapezoidal profiles).
  void append_accel(double duration, double accel) noexcept;
  /// Close the profile: the end state becomes `end` exactly (the segments' integration error,
  /// ~1e-12, is absorbed here so the target is reached exactly). `end.a` must be 0.
  void finish(const State& end) noexcept;

  /// State at `t` seconds from the start (t < 0 gives the start). `hint` caches the segment
  /// index for monotone sampling (start with 0).
  [[nodiscard]] State sample(double t, std::size_t& hint) const noexcept;
  [[nodiscard]] State sample(double t) const noexcept {
    std::size_t h = 0;
    return sample(t, h);
  }

  [[nodiscard]] double duration() const noexcept { return duration_; }
  [[nodiscard]] const State& start() const noexcept { return start_; }
  [[nodiscard]] const State& end() const noexcept { return end_; }
  /// End state of the segments appended so far (before finish()).
  [[nodiscard]] const State& current() const noexcept { return cur_; }
  [[nodiscard]] std::span<const Segment> segments() const noexcept { return {seg_.data(), n_}; }
  /// Largest |v| over the profile (segment ends and interior extrema).
  [[nodiscard]] double peak_velocity() const noexcept;

 private:
  std::array<Segment, max_segments> seg_{};
  std::size_t n_ = 0;
  State start_{}, cur_{}, end_{};
  double duration_ = 0.0;
};

}  // namespace hil::motion
