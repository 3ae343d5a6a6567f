// SPDX-License-Identifier: MIT
#pragma once
// One axis: trajectory + scaling + supervision over one hil::Drive. Pure and clock-free: the
// caller hands every update its CycleTime. Single-threaded: every member is called on the
// motion thread; nothing blocks; update() never throws.

#include <cstdint>
#include <system_error>

#include "hil/core/drive.hpp"
#include "hil/core/fault.hpp"
#include "hil/motion/axis_config.hpp"
#include "hil/motion/axis_status.hpp"
#include "hil/motion/profile.hpp"
#include "hil/motion/scaling.hpp"
#include "hil/motion/supervision.hpp"

namespace hil::motion {

/// Result of one cycle. `fault` while the axis holds an active fault (state error).
enum class CycleResult : std::uint8_t { ok, fault };

class Axis {
 public:
  /// `config` must have passed validate(); an invalid config puts the axis in error with
  /// MotionFault::invalid_command (never throws).
  Axis(AxisConfig config, hil::DrivePtr drive);

  // Commands. Each returns {} when accepted, or a hil::MotionFault error code when rejected
  // (the axis state is then unchanged). They take effect from the next update(). A move's own
  // `limits` may only lower the configured ones (else invalid_command).
  std::error_code enable();   ///< request(enable), wait for operation_enabled (enable_timeout)
  std::error_code disable();  ///< request(disable); motion is dropped
  std::error_code reset();    ///< clear the axis fault; request(fault_reset) if the drive is faulted
  std::error_code home();     ///< request(home) when the drive supports homing
  /// Absolute move (units). Rotary: `position` is taken modulo and `direction` picks the way.
  std::error_code move_absolute(double position, Direction direction = Direction::shortest,
                                std::optional<Limits> limits = {});
  /// Relative to the last target (drift-free: fractional increments carry over).
  std::error_code move_relative(double distance, std::optional<Limits> limits = {});
  /// Run at `velocity` (units/s, signed) until stop(); brakes to land exactly on a soft limit.
  std::error_code move_velocity(double velocity, std::optional<Limits> limits = {});
  std::error_code jog(int direction);  ///< +1 / -1 at jog_velocity until stop()
  std::error_code stop();              ///< controlled stop under the configured limits
  std::error_code quick_stop();        ///< stop at quick_stop_deceleration
  /// Coupled motion (hil/motion/coupling.hpp): the next update() commands `position_inc` (drive
  /// increments, unwrapped, backlash added as usual) with feed-forward velocity and acceleration
  /// (inc/s, inc/s^2) instead of a planned trajectory. Call it once per cycle while coupled; the
  /// axis is `moving` and supervised as in any move (feed = |velocity|). stop() / quick_stop()
  /// end the coupling with a ramp under the axis' limits. Rejected (invalid_command) on drives
  /// that run their own profile, for non-finite values, and in the states check_can_move refuses.
  std::error_code follow(std::int64_t position_inc, double velocity_inc_per_s, double acceleration_inc_per_s2);
  /// An offset (units, signed) of the set-point the drive gets that the axis does not count as its
  /// command: the position equivalent of an offset of an analog command value in a proportional
  /// position loop of gain K_v (a velocity offset v is v / K_v), i.e. a drive's drift and a
  /// controller's drift compensation (WF 725/726 MD 35, docs/wf725.md "Drift"). The following
  /// error, the in-position and standstill checks are against the command without it, so at rest
  /// the axis shows a following error of -offset. Applied from the next update() while the axis
  /// commands the drive (not while disabled, enabling or homing: the set-point follows the actual
  /// there). Rejected (invalid_command) on drives that run their own profile and for non-finite
  /// values.
  std::error_code set_setpoint_offset(double offset);
  [[nodiscard]] double setpoint_offset() const noexcept { return setpoint_offset_; }
  /// A fault from the layer above (a coupling's CouplingFault, a controller's device error):
  /// the axis goes to error with its configured reaction, as for a supervision fault. The first
  /// fault stays; reset() clears it.
  void raise_fault(hil::Fault fault);

  /// One cycle: drive.read -> trajectory + supervision -> drive.write. Never throws.
  CycleResult update(const hil::CycleTime& cycle);

  [[nodiscard]] const AxisStatus& status() const noexcept { return status_; }
  /// The drive's digital inputs as its feedback shows them now (after the last update(): read in
  /// that cycle). CiA 402 0x60FD layout (hil::digital_input); 0 when the drive has none
  /// (DriveCapabilities::digital_inputs).
  [[nodiscard]] std::uint32_t digital_inputs() const noexcept { return drive_->feedback().digital_inputs; }
  /// Set the bits of `mask` of the digital outputs to those of `value`; every later update()
  /// carries them in DriveCommand::digital_outputs (0x60FE sub 1 layout), in any axis state: an
  /// output is not motion. The drive applies the bits of its digital_output_mask.
  void set_digital_outputs(std::uint32_t mask, std::uint32_t value) noexcept {
    digital_outputs_ = (digital_outputs_ & ~mask) | (value & mask);
  }
  [[nodiscard]] std::uint32_t digital_outputs() const noexcept { return digital_outputs_; }
  [[nodiscard]] hil::Drive& drive() noexcept { return *drive_; }
  [[nodiscard]] const AxisConfig& config() const noexcept { return config_; }
  [[nodiscard]] const Scaling& scaling() const noexcept { return scaling_; }
  /// The active profile (for diagnostics and tests). Time 0 = the update that planned it.
  [[nodiscard]] const Profile& profile() const noexcept { return profile_; }

 private:
  enum class Mode : std::uint8_t { hold, position, velocity, velocity_to_limit, stopping, external };
  [[nodiscard]] std::error_code check_can_move() const;
  [[nodiscard]] std::error_code start_position(std::int64_t target_inc, const Limits& limits);
  void raise(std::error_code code, std::string text);
  void react_to_fault();
  void plan_stop(const Limits& limits, Mode after);
  void hold_at_actual();
  void step_trajectory(const hil::CycleTime& cycle);
  void finish_profile();
  [[nodiscard]] Limits effective(const std::optional<Limits>& limits) const;
  [[nodiscard]] Limits quick_stop_limits() const;
  /// The move a drive-profile drive executes (DriveCapabilities::drive_profile); a new id each call.
  void set_drive_move(hil::DriveMove::Kind kind, std::int64_t target_inc, double velocity, const Limits& limits);

  AxisConfig config_;
  hil::DrivePtr drive_;
  Scaling scaling_;
  AxisStatus status_{};
  Profile profile_{};
  std::size_t profile_hint_ = 0;
  Mode mode_ = Mode::hold;
  bool profile_active_ = false;
  hil::TimePoint profile_start_{};       ///< the update the profile was planned at (its t = 0)
  Limits active_limits_{};               ///< limits of the active move (stop() brakes under them)
  Limits entry_limits_{};                ///< upper envelope of the limits the current state was planned under
  std::int64_t last_drive_cmd_inc_ = 0;  ///< command written last cycle (backlash included)
  int home_cycles_ = 0;
  bool home_seen_active_ = false;
  double cmd_p_ = 0.0, cmd_v_ = 0.0, cmd_a_ = 0.0;  ///< command state, units (unwrapped)
  std::int64_t cmd_inc_ = 0;                        ///< commanded position without backlash
  std::int64_t target_inc_ = 0;                     ///< last target (unwrapped), increments
  double relative_carry_inc_ = 0.0;                 ///< fractional increments carried between relative moves
  double limit_target_ = 0.0;                       ///< soft limit a velocity move is landing on
  double programmed_feed_ = 0.0;                    ///< |peak velocity| of the active move (dynamic window)
  double backlash_offset_ = 0.0;                    ///< units currently added to the drive command
  double backlash_goal_ = 0.0;                      ///< 0 after positive motion, -backlash after negative
  Supervisor supervisor_;
  bool drive_profile_ = false;  ///< the drive runs its own trajectory from drive_move_
  hil::DriveMove drive_move_{};
  hil::TimePoint enable_started_{};
  bool first_cycle_ = true;
  hil::TimePoint last_now_{};
  double ext_v_inc_ = 0.0, ext_a_inc_ = 0.0;  ///< feed-forward of the coupled set-point (Mode::external)
  std::uint32_t digital_outputs_ = 0;         ///< DriveCommand::digital_outputs of every write
  double setpoint_offset_ = 0.0;              ///< set_setpoint_offset(): units, not part of the command
};

}  // namespace hil::motion
