// SPDX-License-Identifier: MIT
#pragma once
// Electronic gear: slave = ratio x master, exactly. Pure, clock-free, allocation-free.
//
// The slave position is held as an integer plus a remainder over the ratio's denominator
// (slave = whole + rem/den, 0 <= rem < den), advanced by the master's integer difference each
// cycle: no rounding, so a constant ratio never drifts (docs/coupling.md, "Gear").
//
// A ratio change (engage = 0 -> r, disengage = r -> 0, any r0 -> r1) is a GearTransition: it
// starts at once or when the master reaches a position, and it either steps or ramps the ratio
// linearly over a master distance L. Over the ramp (u = master travel from its start, l = +-L in
// the master's direction)   slave(u) = s0 + r0 u + (r1 - r0) u^2 / (2 l),
// whose slope dslave/dmaster goes from r0 to r1; it is evaluated exactly in 128-bit integers.
// When the ramp completes, the remainder is re-expressed over den(r1), rounded down: one
// transition may lose less than 1/den(r1) increment, never more, and steady gearing is exact.

#include <cstdint>
#include <optional>
#include <system_error>

#include "hil/motion/gear_ratio.hpp"

namespace hil::motion {

struct GearTransition {
  GearRatio to;                               ///< the ratio after the transition
  std::int64_t ramp_master_inc = 0;           ///< master distance of the ratio ramp (>= 0); 0 = step
  std::optional<std::int64_t> at_master_inc;  ///< start when the master reaches this position; else at once
};

enum class GearPhase : std::uint8_t {
  steady,   ///< following at ratio()
  armed,    ///< a transition waits for its master position
  ramping,  ///< the ratio is ramping
};

class Gear {
 public:
  /// A gear at `ratio` (default 0: disengaged). valid(ratio) is required (else ratio 0).
  explicit Gear(GearRatio ratio = {}) noexcept;

  /// Synchronise: from now on the slave is `slave_inc` when the master is `master_inc`. A queued
  /// transition that has not started stays queued ("at once" then means from `master_inc`); a
  /// running ramp is cut short and its end ratio taken.
  void start(std::int64_t master_inc, std::int64_t slave_inc) noexcept;

  /// Queue a transition (replaces one that has not started; a running ramp is finished first:
  /// the new one is rejected while ramping). Returns CouplingFault::invalid for a bad ratio or
  /// a negative ramp, or when a ramp is running.
  std::error_code change(const GearTransition& t) noexcept;
  std::error_code engage(GearRatio r, std::int64_t ramp_master_inc = 0,
                         std::optional<std::int64_t> at_master_inc = {}) noexcept {
    return change({r, ramp_master_inc, at_master_inc});
  }
  std::error_code disengage(std::int64_t ramp_master_inc = 0, std::optional<std::int64_t> at_master_inc = {}) noexcept {
    return change({GearRatio{0, 1}, ramp_master_inc, at_master_inc});
  }

  /// One cycle: the new master position (increments). Returns the slave position (increments,
  /// including the fraction). O(1); the steady path is one multiply and one divide.
  double update(std::int64_t master_inc) noexcept;

  [[nodiscard]] std::int64_t slave_inc() const noexcept { return whole_; }  ///< floor of the exact position
  [[nodiscard]] double slave_position() const noexcept { return static_cast<double>(whole_) + frac(); }
  [[nodiscard]] GearRatio ratio() const noexcept { return ratio_; }  ///< the ratio in force (r0 while ramping)
  /// dslave/dmaster now (the ramp's momentary slope while ramping).
  [[nodiscard]] double slope() const noexcept { return slope_; }
  [[nodiscard]] GearPhase phase() const noexcept { return phase_; }
  [[nodiscard]] std::int64_t master_inc() const noexcept { return master_; }
  [[nodiscard]] bool engaged() const noexcept { return ratio_.num != 0 || phase_ != GearPhase::steady; }

 private:
  [[nodiscard]] double frac() const noexcept;
  void advance_steady(std::int64_t master_inc) noexcept;
  void begin_ramp(std::int64_t at_master) noexcept;
  void eval_ramp(std::int64_t master_inc) noexcept;
  void finish_ramp() noexcept;

  GearRatio ratio_{};
  std::int64_t master_ = 0;
  std::int64_t whole_ = 0;  ///< slave = whole_ + rem_/ratio_.den (steady)
  std::int64_t rem_ = 0;
  GearPhase phase_ = GearPhase::steady;
  GearTransition pending_{};
  bool pending_at_once_ = false;
  double slope_ = 0.0;
  // Ramp state: slave = s0_whole_ + N(u)/D with u = master - p_, D > 0.
  std::int64_t p_ = 0;         ///< master position where the ramp starts
  std::int64_t s0_whole_ = 0;  ///< slave whole part at p_
  std::int64_t s0_rem_ = 0;    ///< remainder over ratio_.den at p_
  std::int64_t ell_ = 0;       ///< signed ramp length (master direction); 0 = direction not yet known
  i128 ramp_num_ = 0;          ///< numerator of the fraction of the current ramp value
  i128 ramp_den_ = 1;
};

}  // namespace hil::motion
