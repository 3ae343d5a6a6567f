// SPDX-License-Identifier: MIT
#pragma once
// hil::Drive for an open-loop step/dir power stage on GPIO lines, with IP247 semantics:
//   - actual position = steps output (capabilities().closed_loop = false);
//   - enable/reset output (IP247 RS): asserted while disabled, a 100 ms pulse on enable and at the
//     start of a synchronous reference run; ready input (BB) monitored: loss = fault 53 and the
//     reference (synchronisation) is lost;
//   - hardware limits (NO or NC; NC + broken wire = overrun), seen only in the travel direction,
//     fault 25/26 and a direction lock released by moving off the switch;
//   - DriveRequest::home = the IP247 reference-point run (§4.2.3) with cam watchdog (fault 59).
// Faults carry the IP247 error number in category "ip247".
//
// Each write() plans the edges of the window (now, now + period] and hands them to the EdgeSink.
// Profile `motion`: the position command is followed per cycle. Profile `ip247`: the drive is a
// drive-profile drive (capabilities().drive_profile): each DriveCommand::move runs on the IP247
// ramp at its own speed (velocity_inc_per_s = the pulse frequency, clamped to [f_ss, fmax]); a
// raw position command without a move ramps at fmax. Edges go to the EdgeSink (mock: recorded on the virtual clock;
// real: the edge writer thread). Thread: the motion thread only. read/write never block and never throw.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "hil/core/drive.hpp"
#include "hil/core/fault_injection.hpp"
#include "hil/drives/stepdir/config.hpp"
#include "hil/gpio/edge_sink.hpp"
#include "hil/gpio/line_bank.hpp"
#include "hil/stepdir/step_planner.hpp"

namespace hil::drives::stepdir {

enum class HomingPhase : std::uint8_t {
  idle,
  reset_pulse,
  away,
  away_on_cam,
  search,
  search_on_cam,
  creep,
  leave_cam,
  sync,
  done,
};

class StepDirDrive final : public Drive, public FaultInjectable {
 public:
  /// `outputs`: [step, dir, enable?]; `inputs`: [ready?, limit_start?, limit_end?, reference?] in
  /// that order with absent lines skipped (null when there are no inputs). All must outlive the drive.
  StepDirDrive(std::string name, const StepDirConfig& config, std::shared_ptr<const hil::stepdir::Ip247Ramp> ramp,
               gpio::LineBank& outputs, gpio::LineBank* inputs, gpio::EdgeSink& sink);

  [[nodiscard]] std::string_view name() const noexcept override { return name_; }
  [[nodiscard]] DriveCapabilities capabilities() const noexcept override;
  void read(const CycleTime& cycle) override;
  void write(const CycleTime& cycle, const DriveCommand& command) override;
  [[nodiscard]] const DriveFeedback& feedback() const noexcept override { return fb_; }
  bool request(DriveRequest r) override;

  [[nodiscard]] std::vector<std::string> injectable_faults() const override { return injector_names_; }
  bool inject_fault(std::string_view name, bool active) override { return injector_ ? injector_(name, active) : false; }
  void set_fault_injector(std::vector<std::string> names, std::function<bool(std::string_view, bool)> f) {
    injector_names_ = std::move(names);
    injector_ = std::move(f);
  }

  [[nodiscard]] const hil::stepdir::StepPlanner& planner() const noexcept { return planner_; }
  [[nodiscard]] HomingPhase homing_phase() const noexcept { return homing_; }
  [[nodiscard]] int locked_direction() const noexcept { return lock_dir_; }
  [[nodiscard]] std::uint64_t lag_cycles() const noexcept { return lag_cycles_; }
  [[nodiscard]] std::uint64_t input_errors() const noexcept { return input_errors_; }
  /// Energisation-pattern counter (0..patterns-1), zeroed by the reset pulse and by ready rising.
  [[nodiscard]] int pattern_counter() const noexcept;

 private:
  enum class Power : std::uint8_t { disabled, resetting, wait_ready, enabled };
  struct Inputs {
    bool ready = true, limit_start = false, limit_end = false, cam = false;
  };
  void sample_inputs();
  void raise(hil::stepdir::Ip247Error e, std::string what);
  bool limit_actuated(int direction) const noexcept;
  void check_limits(int travel);
  void start_reset_pulse(std::int64_t now);
  void emit_enable(std::int64_t t, bool level);
  void step_homing(std::int64_t now);
  void finish_homing(bool ok);
  /// `ip247` profile: runs DriveCommand::move (position at its velocity, velocity, hold = brake).
  void ramp_to(const DriveMove& move, bool blocked);
  /// Where a move goes (velocity: "far away" in its direction; hold: here).
  [[nodiscard]] std::int64_t move_goal(const DriveMove& move, std::int64_t pos) const noexcept;
  [[nodiscard]] double move_frequency_hz(double velocity_inc_per_s) const noexcept;

  std::string name_;
  StepDirConfig cfg_;
  hil::stepdir::StepPlanner planner_;
  gpio::LineBank& out_;
  gpio::LineBank* in_;
  gpio::EdgeSink& sink_;
  int idx_ready_ = -1, idx_lstart_ = -1, idx_lend_ = -1, idx_ref_ = -1;

  DriveFeedback fb_;
  Power power_ = Power::disabled;
  bool enable_level_ = true;  ///< enable/reset line: true = reset asserted
  std::int64_t reset_release_at_ = -1;
  std::int64_t ready_deadline_ = 0;
  std::int64_t now_ = 0;
  Inputs inputs_;
  bool prev_ready_ = false;
  int lock_dir_ = 0;
  std::int64_t phase_base_ = 0;
  std::int64_t last_pos_ = 0;
  std::uint64_t lag_cycles_ = 0;
  std::uint64_t input_errors_ = 0;
  std::vector<gpio::Edge> batch_;
  std::uint32_t move_id_ = 0;  ///< DriveMove::id of the move the planner runs (ip247 profile)

  HomingPhase homing_ = HomingPhase::idle;
  bool homing_tail_ = false;     ///< report homing_active for one more image after success
  bool homing_braking_ = false;  ///< waiting for the planner to stop before the next phase
  HomingPhase after_brake_ = HomingPhase::idle;
  std::int64_t single_steps_ = 0;
  hil::stepdir::PlannerMode mode_before_homing_ = hil::stepdir::PlannerMode::follow;

  std::vector<std::string> injector_names_;
  std::function<bool(std::string_view, bool)> injector_;
};

}  // namespace hil::drives::stepdir
