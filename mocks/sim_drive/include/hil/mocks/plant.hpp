// SPDX-License-Identifier: MIT
#pragma once
// Physics of a servo axis, the mock endpoint behind every transport mock (the simulated CiA 402
// node, the Modbus drive server, the `sim` transport). Pure: the caller steps it with dt.
//
//   position loop  v_cmd = Kv * (p_cmd - p) + ff * v_ff        (position mode)
//                  v_cmd = v_target                              (velocity mode)
//   limit          |v_cmd| <= v_max
//   velocity loop  first order, time constant `velocity_lag_s`  (exact exponential step)
//   encoder        reading = floor(p / encoder_step) * encoder_step, as integer increments
//
// Without feed-forward the steady following error at speed v is v / Kv, the classic value the
// WF 725/726 speed-dependent window (1.5 v / Kv) is built on.

#include <cstddef>
#include <cstdint>

#include "hil/core/clock.hpp"
#include "hil/core/drive.hpp"
#include "hil/core/fault.hpp"

namespace hil::mocks {

struct PlantConfig {
  double kv_per_s = 50.0;                 ///< position loop gain Kv (1/s)
  double max_velocity_inc_per_s = 5.0e6;  ///< velocity limit of the power stage
  double velocity_lag_s = 0.002;          ///< velocity loop time constant (0 = ideal)
  double velocity_feedforward = 0.0;      ///< 0..1, share of the commanded velocity fed forward
  std::int64_t encoder_step_inc = 1;      ///< encoder quantisation (>= 1)
  double initial_position_inc = 0.0;
};

struct PlantInput {
  bool powered = false;  ///< power stage on; off = coast to rest through the lag
  CommandMode mode = CommandMode::position;
  double position_inc = 0.0;
  double velocity_inc_per_s = 0.0;  ///< target (velocity mode) or feed-forward (position mode)
};

class Plant {
 public:
  explicit Plant(PlantConfig config = {});

  /// Most sub-steps one step() takes, whatever `dt` and the gain (a gain beyond 0.2 / h acts as
  /// 0.2 / h): a run on virtual time never stalls in the plant.
  static constexpr std::size_t max_substeps = 20'000;

  /// Advance by `dt` (any length; long steps are sub-stepped for stability). Returns the number
  /// of sub-steps taken (at most max_substeps).
  std::size_t step(Duration dt, const PlantInput& in) noexcept;

  /// Encoder reading in increments (frozen while the encoder fault is injected).
  [[nodiscard]] std::int64_t encoder_position_inc() const noexcept { return encoder_; }
  /// True mechanical position and velocity (unquantised), for tests and traces.
  [[nodiscard]] double position_inc() const noexcept { return position_; }
  [[nodiscard]] double velocity_inc_per_s() const noexcept { return velocity_; }
  /// The velocity a drive reports as its actual value: the mean over the last step() (position
  /// change / dt, unquantised), as a drive derives it from its encoder over one cycle. The
  /// instantaneous velocity_inc_per_s() at the end of a cycle is not that: with the set point held
  /// for the cycle, the loop slows towards it within the cycle, so the end-of-cycle value reads a
  /// few per cent under a steady feed (38.7 for 40 mm/s at Kv 200, 2 ms).
  [[nodiscard]] double measured_velocity_inc_per_s() const noexcept { return measured_velocity_; }

  /// Re-reference: the current mechanical position reads `position_inc` from now on (homing).
  void set_position(double position_inc) noexcept;

  void inject(PlantFault f, bool active = true) noexcept;
  [[nodiscard]] bool has(PlantFault f) const noexcept { return (faults_ & bit(f)) != 0; }
  /// The first active fault in order encoder, not_ready, following_blowup; `none` when clear.
  [[nodiscard]] PlantFault fault() const noexcept;

  [[nodiscard]] const PlantConfig& config() const noexcept { return config_; }

 private:
  static constexpr unsigned bit(PlantFault f) noexcept { return 1u << static_cast<unsigned>(f); }
  void substep(double dt_s, const PlantInput& in) noexcept;
  void sample_encoder() noexcept;

  PlantConfig config_;
  double position_ = 0.0;
  double velocity_ = 0.0;
  double measured_velocity_ = 0.0;
  double offset_ = 0.0;  ///< reading = mechanical + offset (set_position)
  std::int64_t encoder_ = 0;
  unsigned faults_ = 0;
};

}  // namespace hil::mocks
