// SPDX-License-Identifier: MIT
#pragma once
// Turns axis commands into a schedule of timestamped step/dir edges. Pure and clock-free: the
// caller passes the time window; the planner keeps its own step timeline across windows, so a
// pulse that straddles a window boundary finishes in the next one.
//
// Two ways to time steps:
//   - ramp:   IP247 profile. move_to(target, f_v) runs a move along the Ip247Ramp table: jump to
//             f_ss, exponential acceleration cut at f_v, mirrored deceleration whose braking point
//             comes from the step count left (interval k = table[min(k, steps_left - 1)]), stop at
//             once from f_ss. A new target mid-move re-plans without a frequency jump (at most one
//             table step down per step; a target behind the braking distance is overshot, then
//             approached in reverse). An absolute target is always hit exactly.
//   - follow: the position command from the motion core (already jerk-limited) is spread evenly
//             over the window, limited by the timing rules; steps that do not fit are carried to
//             the next window (status `lagging`), never dropped.
// In both, every reversal first adds `backlash_steps` motor steps that do not change position().
// Timing rules (StepTiming) hold for every edge this planner emits.
//
// Thread: single-threaded (the motion cycle). Allocation: only `out` grows.

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "hil/gpio/edge.hpp"
#include "hil/stepdir/ip247_ramp.hpp"
#include "hil/stepdir/timing.hpp"

namespace hil::stepdir {

enum class PlannerMode : std::uint8_t { ramp, follow };
enum class PlanStatus : std::uint8_t {
  ok,
  lagging,  ///< follow mode: the command needs more steps than the timing rules allow in this window
};

/// Output-bank indices of the step and dir lines.
struct StepLineIndex {
  std::uint16_t step = 0;
  std::uint16_t dir = 1;
};

/// A window end that never comes ("plan the whole move").
inline constexpr std::int64_t plan_forever_ns = INT64_MAX / 4;

class StepPlanner {
 public:
  StepPlanner(const StepTiming& timing, std::shared_ptr<const Ip247Ramp> ramp, std::int64_t backlash_steps = 0,
              StepLineIndex lines = {}) noexcept;

  void set_mode(PlannerMode m) noexcept;
  [[nodiscard]] PlannerMode mode() const noexcept { return mode_; }

  /// Ramp mode: go to absolute `target` (steps) at up to `f_v_hz`, clamped to [f_ss, fmax].
  /// Returns false when f_v had to be clamped (IP247 warning 7); the move runs anyway.
  bool move_to(std::int64_t target, double f_v_hz) noexcept;
  /// Follow mode: the position to reach by the end of the next window.
  void follow(std::int64_t target) noexcept { target_ = target; }
  /// Ramp mode: brake along the ramp now (IP247 stop); never lengthens the move (halting again
  /// while braking keeps the end). Follow mode: same as stop_now().
  void halt() noexcept;
  /// No more new steps (a pulse already begun still ends properly).
  void stop_now() noexcept;

  /// Emit every edge with time <= horizon_ns into `out` (appended, time-ordered). New motion
  /// starts no earlier than now_ns. Call with non-decreasing windows.
  PlanStatus plan(std::int64_t now_ns, std::int64_t horizon_ns, std::vector<gpio::Edge>& out);

  /// Position in steps (excluding backlash steps), of every step planned so far.
  [[nodiscard]] std::int64_t position() const noexcept { return pos_; }
  [[nodiscard]] std::int64_t target() const noexcept { return target_; }
  /// Motor steps with sign, including backlash take-up.
  [[nodiscard]] std::int64_t motor_position() const noexcept { return motor_pos_; }
  [[nodiscard]] bool moving() const noexcept { return moving_ || pending_head_ < pending_n_; }
  /// Direction of the current/last move (+1 forward, -1 backward, 0 none yet).
  [[nodiscard]] int direction() const noexcept { return dir_; }
  /// Direction of the last step output (0 = unknown, e.g. after set_position).
  [[nodiscard]] int last_step_direction() const noexcept { return last_dir_; }
  [[nodiscard]] std::int64_t backlash_pending() const noexcept { return backlash_pending_; }
  [[nodiscard]] std::uint64_t steps_total() const noexcept { return steps_total_; }
  [[nodiscard]] std::uint64_t backlash_steps_total() const noexcept { return backlash_total_; }
  [[nodiscard]] std::int64_t last_interval_ns() const noexcept { return last_interval_ns_; }
  [[nodiscard]] std::int64_t last_step_ns() const noexcept { return last_rise_; }
  [[nodiscard]] const StepTiming& timing() const noexcept { return timing_; }
  [[nodiscard]] const Ip247Ramp& ramp() const noexcept { return *ramp_; }

  /// Set the position (reference point). `last_direction` 0 = unknown (IP247 "set reference":
  /// the first move then takes up no backlash), else the direction the axis came from.
  void set_position(std::int64_t position, int last_direction) noexcept;

 private:
  struct Candidate {
    std::int64_t rise = 0;
    std::int64_t dir_edge = -1;  ///< time of a dir edge before the step, or -1
    std::int64_t idx = -1;
    int d = 0;
    bool start = false;
  };
  bool next_step(std::int64_t now, std::int64_t horizon, Candidate& c) noexcept;
  bool next_ramp(std::int64_t now, Candidate& c) noexcept;
  bool next_follow(std::int64_t now, std::int64_t horizon, Candidate& c) noexcept;
  void start_constraints(std::int64_t now, int d, Candidate& c) const noexcept;
  void commit(const Candidate& c) noexcept;
  [[nodiscard]] std::int64_t backlash_after(int d) const noexcept;
  void push(std::int64_t t, std::uint16_t line, bool level) noexcept { pending_[pending_n_++] = {t, line, level}; }

  StepTiming timing_;
  std::shared_ptr<const Ip247Ramp> ramp_;
  std::int64_t backlash_ = 0;
  StepLineIndex lines_;
  std::int64_t min_period_ = 0;
  std::int64_t first_interval_ = 0;
  PlannerMode mode_ = PlannerMode::ramp;

  std::int64_t pos_ = 0;
  std::int64_t motor_pos_ = 0;
  std::int64_t target_ = 0;
  std::int64_t v_period_ = 0;  ///< ramp mode: period of the commanded frequency
  std::int64_t cap_idx_ = 0;   ///< ramp mode: table index where f_v is reached
  bool moving_ = false;
  int dir_ = 0;
  int last_dir_ = 0;
  int dir_line_ = 1;  ///< direction the dir line shows now
  std::int64_t last_idx_ = -1;
  std::int64_t backlash_pending_ = 0;

  std::int64_t last_rise_ = INT64_MIN / 4;
  std::int64_t last_fall_ = INT64_MIN / 4;
  std::int64_t last_edge_ = INT64_MIN / 4;
  std::int64_t last_interval_ns_ = 0;
  std::uint64_t steps_total_ = 0;
  std::uint64_t backlash_total_ = 0;

  std::array<gpio::Edge, 4> pending_{};
  std::uint8_t pending_n_ = 0;
  std::uint8_t pending_head_ = 0;
};

}  // namespace hil::stepdir
