// SPDX-License-Identifier: MIT
#pragma once
// Coupled motion: one slave following a master through a law (electronic gear or cam), plus a
// superimposed move, supervised by the slave's limits and a coupling following-error window.
// Pure, clock-free, cycle-stepped like Axis; update() never throws or allocates.
//
// Use (docs/coupling.md):
//   Coupling c("y", limits);                       // limits in slave increments
//   c.use(Coupling::Law::gear); c.gear().engage({3, 2}, 2000, /*at master*/ 50000);
//   c.start(master_inc, slave_inc);
//   each cycle: const auto& out = c.update(master_inc, period, slave_actual_inc);
//               slave_axis.follow(out.position_inc, out.velocity_inc_per_s, out.acceleration_inc_per_s2);
//               slave_axis.update(cycle);
//
// Limits: the demanded slave path y_k (law + superimposed, increments, before rounding) gives
// v_k = (y_k - y_{k-1})/T and, on v averaged over `acceleration_filter_cycles` cycles,
// a_k = (v̄_k - v̄_{k-1})/T. When |v_k| > velocity or |a_k| > acceleration, or when the slave's
// actual position is more than following_error_window away from last cycle's command, the
// coupling latches a CouplingFault and the output no longer follows the law: it brakes from the
// last output velocity at `acceleration` to rest and holds there. So the output never exceeds
// the limits (it faults instead) - property-tested. reset() re-synchronises the law to the
// held slave position (no jump) and clears the fault.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "hil/core/clock.hpp"
#include "hil/core/fault.hpp"
#include "hil/motion/cam.hpp"
#include "hil/motion/coupling_fault.hpp"
#include "hil/motion/gear.hpp"
#include "hil/motion/superimposed.hpp"

namespace hil::motion {

/// Slave limits in slave increments.
struct SlaveLimits {
  double velocity = std::numeric_limits<double>::infinity();      ///< inc/s
  double acceleration = std::numeric_limits<double>::infinity();  ///< inc/s^2 (also the braking rate after a fault)
  int acceleration_filter_cycles = 1;   ///< moving average of v before differentiating (1 = none; noisy masters)
  double following_error_window = 0.0;  ///< inc; 0 = no coupling following-error monitor
};

/// One cycle's set-point for the slave axis (Axis::follow).
struct CouplingOutput {
  std::int64_t position_inc = 0;
  double position = 0.0;  ///< unrounded, increments
  double velocity_inc_per_s = 0.0;
  double acceleration_inc_per_s2 = 0.0;
  bool faulted = false;
};

class Coupling {
 public:
  enum class Law : std::uint8_t { none, gear, cam };

  explicit Coupling(std::string name = "slave", SlaveLimits limits = {});

  [[nodiscard]] Gear& gear() noexcept { return gear_; }
  [[nodiscard]] CamCoupling& cam() noexcept { return cam_; }
  [[nodiscard]] SuperimposedMove& superimposed() noexcept { return superimposed_; }
  [[nodiscard]] const Gear& gear() const noexcept { return gear_; }
  [[nodiscard]] const CamCoupling& cam() const noexcept { return cam_; }
  [[nodiscard]] const SuperimposedMove& superimposed() const noexcept { return superimposed_; }

  /// Select the law. Law::none holds the slave (plus the superimposed move).
  void use(Law law) noexcept { law_ = law; }
  [[nodiscard]] Law law() const noexcept { return law_; }
  /// Synchronise everything at (master, slave): the gear and the cam continue from here
  /// without a jump (the cam from table position `cam_phase`).
  void start(std::int64_t master_inc, std::int64_t slave_inc, std::int64_t cam_phase = 0) noexcept;

  /// One cycle. `slave_actual_inc`: the slave's actual position for the following-error
  /// monitor (nullopt: not monitored this cycle).
  const CouplingOutput& update(std::int64_t master_inc, hil::Duration period,
                               std::optional<std::int64_t> slave_actual_inc = {}) noexcept;

  [[nodiscard]] const CouplingOutput& output() const noexcept { return out_; }
  [[nodiscard]] const hil::Fault& fault() const noexcept { return fault_; }
  [[nodiscard]] bool faulted() const noexcept { return static_cast<bool>(fault_); }
  /// Clear the fault; the law continues from the held slave position at `master_inc`.
  void reset(std::int64_t master_inc) noexcept;
  [[nodiscard]] const SlaveLimits& limits() const noexcept { return limits_; }
  void set_limits(const SlaveLimits& l) noexcept { limits_ = l; }
  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  /// The law's demanded position last cycle (increments), before limiting.
  [[nodiscard]] double demanded() const noexcept { return demanded_; }

 private:
  void raise(CouplingFault f, std::string text) noexcept;
  [[nodiscard]] double law_position(std::int64_t master_inc) noexcept;

  std::string name_;
  SlaveLimits limits_;
  Law law_ = Law::none;
  Gear gear_{};
  CamCoupling cam_{};
  SuperimposedMove superimposed_{};
  double hold_ = 0.0;  ///< Law::none position
  CouplingOutput out_{};
  hil::Fault fault_{};
  bool first_ = true;
  double demanded_ = 0.0;
  double prev_y_ = 0.0, prev_v_ = 0.0, prev_vf_ = 0.0;
  static constexpr int max_filter = 64;
  double v_hist_[max_filter] = {};
  double v_sum_ = 0.0;
  int v_n_ = 0, v_i_ = 0;
};

}  // namespace hil::motion
