// SPDX-License-Identifier: MIT
#pragma once
// Configuration of one step/dir axis (a scenario's `drive:` block with `transport: stepdir`).
// Keys and defaults are documented in docs/stepdir.md.

#include <chrono>
#include <cstdint>
#include <expected>
#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "hil/config/yaml_config.hpp"
#include "hil/core/config_error.hpp"
#include "hil/gpio/line_config.hpp"
#include "hil/stepdir/ip247_ramp.hpp"
#include "hil/stepdir/step_planner.hpp"
#include "hil/stepdir/timing.hpp"

namespace hil::drives::stepdir {

/// Output bank order (index = role) and input bank order.
enum OutputLine : std::uint16_t { out_step = 0, out_dir = 1, out_enable = 2 };
enum InputLine : std::uint16_t { in_ready = 0, in_limit_start = 1, in_limit_end = 2, in_reference = 3 };

struct HomingConfig {
  int direction = -1;                       ///< reference direction: +1 forward ("right"), -1 backward (IP247 default)
  double speed_hz = 1'000.0;                ///< reference speed; f_ss < f_ref <= fmax (MD error 17)
  std::int64_t coordinate = 0;              ///< position given to the reference point (steps)
  bool sync = false;                        ///< continue to the pattern-counter zero after leaving the cam
  int patterns = 4;                         ///< energisation patterns, 4..40 (MD error 10)
  std::int64_t cam_watchdog_steps = 2'500;  ///< error 59 when the cam is not left within this many single steps
};

/// Mock switches for runs without a chip: actuated as a function of the motor steps output.
struct MockSwitches {
  std::optional<std::int64_t> limit_start_at;                ///< limit start actuated at motor position <= this
  std::optional<std::int64_t> limit_end_at;                  ///< limit end actuated at motor position >= this
  std::optional<std::pair<std::int64_t, std::int64_t>> cam;  ///< reference cam actuated within [a, b]
  std::int64_t initial_position = 0;                         ///< plant position at start (steps)
  bool ready = true;                                         ///< ready (BB) input level at start
};

struct StepDirConfig {
  hil::stepdir::StepTiming timing;
  hil::stepdir::Ip247RampParams ramp;
  hil::stepdir::PlannerMode profile = hil::stepdir::PlannerMode::follow;  ///< `motion` (follow) or `ip247` (ramp)
  std::int64_t backlash_steps = 0;
  bool limits_normally_closed = false;  ///< IP247 MD n+33: NC ("neg") or NO ("pos")
  std::chrono::nanoseconds reset_pulse{std::chrono::milliseconds(100)};
  std::chrono::nanoseconds ready_timeout{std::chrono::milliseconds(1000)};
  HomingConfig homing;
  std::optional<std::string> chip;                                       ///< absent: mock lines
  std::chrono::nanoseconds writer_spin{std::chrono::microseconds(200)};  ///< real lines: spin this close to an edge
  std::chrono::nanoseconds writer_late{std::chrono::microseconds(50)};   ///< real lines: lateness counted as late
  int writer_rt_priority = 0;  ///< real lines: SCHED_FIFO priority of the writer thread (0 = off)
  gpio::LineSpec step, dir;
  std::optional<gpio::LineSpec> enable, ready, limit_start, limit_end, reference;
  MockSwitches mock;
};

/// Parse and validate `drive:` (MD errors become ConfigErrors naming the key and the IP247 code).
[[nodiscard]] std::expected<StepDirConfig, ConfigError> parse_stepdir_config(const YAML::Node& drive,
                                                                             const hil::yaml::Where& where);

}  // namespace hil::drives::stepdir
