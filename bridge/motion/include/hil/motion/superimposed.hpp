// SPDX-License-Identifier: MIT
#pragma once
// A superimposed move on a coupled slave (velocity-additive, as the CLM1.4's FOL offset or a
// printing-mark correction): an offset profile in slave increments, planned with the motion
// core's jerk-limited planner and added to the coupling law's output. Pure, clock-free.

#include <system_error>

#include "hil/core/clock.hpp"
#include "hil/motion/limits.hpp"
#include "hil/motion/profile.hpp"

namespace hil::motion {

class SuperimposedMove {
 public:
  /// Move the offset by `distance_inc` (slave increments) under `limits` (inc/s, inc/s^2,
  /// inc/s^3). While a move runs, the new one continues from its state (distances add up).
  /// CouplingFault::invalid for non-finite input or bad limits.
  std::error_code move_by(double distance_inc, const Limits& limits) noexcept;
  /// Advance by one cycle.
  void update(hil::Duration period) noexcept;
  void clear() noexcept { *this = SuperimposedMove{}; }

  [[nodiscard]] double offset() const noexcept { return state_.p; }  ///< slave increments
  [[nodiscard]] double velocity() const noexcept { return state_.v; }
  [[nodiscard]] double acceleration() const noexcept { return state_.a; }
  [[nodiscard]] bool busy() const noexcept { return active_; }
  [[nodiscard]] double target() const noexcept { return target_; }

 private:
  Profile profile_{};
  State state_{};
  double target_ = 0.0;
  double t_ = 0.0;
  std::size_t hint_ = 0;
  bool active_ = false;
};

}  // namespace hil::motion
