// SPDX-License-Identifier: MIT
#pragma once
// Runs an NcProgram block by block as a step function (one call per cycle, the time passed in).
// A block: R operations, G modes, S and spindle M03/M04/M05, its other M functions (output at the
// start of the block), then its motion, then its dwell (G04 F seconds); the next block starts when
// motion is in position and the dwell has elapsed; the `@` jump is taken at the end of the block.
// M02 and M30 end the program and stop the spindle.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "hil/controllers/elg/nc_program.hpp"

namespace hil::controllers::elg {

/// Absolute targets of the NC's linear axes in mm (nullopt: the axis does not move).
struct NcTargets {
  std::optional<double> x, y, z;
};

/// What the NC commands; the ELG controller implements it on the motion core, tests on ideal axes.
class NcMachine {
 public:
  virtual ~NcMachine() = default;
  /// Starts a move of X/Y/Z to absolute targets, at rapid traverse or at `feed_mm_per_s`.
  virtual void move(const NcTargets& targets, bool rapid, double feed_mm_per_s) = 0;
  /// The last move has ended (all axes in position).
  [[nodiscard]] virtual bool in_position() const = 0;
  /// Current positions of the linear axes in mm (for incremental programming).
  [[nodiscard]] virtual NcTargets position() const = 0;
  /// Spindle (hob B): rpm >= 0, direction +1 (M03), -1 (M04), 0 (M05).
  virtual void spindle(double rpm, int direction) = 0;
  /// An auxiliary M function for the PC/ELG (not M02/M30/M03/M04/M05).
  virtual void m_function(int m) = 0;
};

enum class NcState : std::uint8_t { running, ended, error };

class NcInterpreter {
 public:
  explicit NcInterpreter(NcProgram program);

  /// One cycle at time `now_s` (seconds, monotonic). Never throws.
  NcState step(double now_s, NcMachine& machine);

  [[nodiscard]] NcState state() const noexcept { return state_; }
  [[nodiscard]] double r(int n) const noexcept { return n >= 0 && n < 1000 ? r_[static_cast<std::size_t>(n)] : 0.0; }
  void set_r(int n, double v) noexcept {
    if (n >= 0 && n < 1000) r_[static_cast<std::size_t>(n)] = v;
  }
  /// N number of the block being executed (-1 before the first / after the end).
  [[nodiscard]] int block_number() const noexcept;
  [[nodiscard]] std::uint64_t blocks_executed() const noexcept { return executed_; }
  [[nodiscard]] const std::string& error() const noexcept { return error_; }

 private:
  void start_block(double now_s, NcMachine& machine);
  bool jump_taken(const NcJump& j) const noexcept;

  NcProgram program_;
  std::array<double, 1000> r_{};
  NcState state_ = NcState::running;
  std::size_t pc_ = 0;
  bool in_block_ = false;
  double dwell_until_ = 0.0;
  bool rapid_ = true;     // G0 / G1 (modal)
  bool absolute_ = true;  // G90 / G91
  bool per_rev_ = false;  // G94 / G95
  double feed_ = 0.0;     // F (modal), mm/min or mm/rev
  double spindle_rpm_ = 0.0;
  int spindle_dir_ = 0;
  std::uint64_t executed_ = 0;
  std::string error_;
};

}  // namespace hil::controllers::elg
