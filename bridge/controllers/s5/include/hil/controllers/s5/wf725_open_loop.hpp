// SPDX-License-Identifier: MIT
#pragma once
// Open-loop control (AK, MD 4 = 3/4) of a WF 725/726 axis (digest wf725-726.md §1.3, §3.5 MD 1/2,
// MD 10, MD 42-48): staged positioning with speed levels 1..99 (X3 voltage = level x 100 mV, DL 4 =
// the level in BCD), switched down at the travel differences MD 45 >= MD 46 >= MD 47 >= MD 48 of
// the remaining distance, speed 0 at MD 48; the cut-off point outputs A/B/C (X7 outputs 1-3) and
// output function 4 "last but one cut-off point". The staircase figure of the manual is lost:
// the decisions are in docs/wf725.md, "Open-loop control". Pure.

#include <array>
#include <cstdint>

namespace hil::controllers::s5 {

/// The speed stages of MD 42-48.
struct Wf725OpenLoopStages {
  std::array<int, 3> levels{87, 52, 10};                       ///< MD 42, 43, 44 (1..99)
  std::array<double, 4> distances_um{50000, 25000, 5000, 55};  ///< MD 45, 46, 47, 48 (µm)
};

/// The speed level for `remaining_um` of travel left (towards the target; <= 0 at or past it):
/// the programmed level until MD 45, then MD 42 below MD 45, MD 43 below MD 46, MD 44 below
/// MD 47, 0 at MD 48 and below ("below" = remaining <= the travel difference). A stage never
/// raises the speed: a programmed level lower than the stage's stays (decision).
[[nodiscard]] int wf725_open_loop_level(const Wf725OpenLoopStages& s, int programmed, double remaining_um) noexcept;

/// The cut-off point outputs (X7 outputs 1-3, digest §1.4) and MD 10 function 4 during a
/// positioning with `remaining_um` left: A is 1 until MD 46, B until MD 47, C until MD 48 (the
/// last travel difference switches the output to zero, §3.5); the last-but-one cut-off point
/// (WF 726) is 1 from MD 47 on.
struct Wf725CutOffOutputs {
  bool a = false, b = false, c = false, last_but_one = false;
};
[[nodiscard]] Wf725CutOffOutputs wf725_cut_off_outputs(const Wf725OpenLoopStages& s, double remaining_um) noexcept;

/// The drive behind X3 as the simulation sees it (controller options `open_loop_speed`,
/// `open_loop_acceleration`): speed at 10 V and its own acceleration limit.
struct Wf725OpenLoopDrive {
  double speed_at_10v_mm_min = 10000.0;  ///< mm/min (deg/min) at 10 V = level 100
  double acceleration = 1000.0;          ///< mm/s^2: the drive's own ramp (a step of the voltage)
};

/// Velocity (mm/s) of speed level 0..99: level x 100 mV on X3.
[[nodiscard]] constexpr double wf725_level_velocity(const Wf725OpenLoopDrive& d, int level) noexcept {
  return static_cast<double>(level) * 100.0 / 10000.0 * d.speed_at_10v_mm_min / 60.0;
}
/// Command voltage (mV) of a speed level.
[[nodiscard]] constexpr int wf725_level_mv(int level) noexcept {
  return level * 100;
}
/// The acceleration (mm/s^2) of a voltage ramp MD 1/MD 2 in mV/s on this drive; 0 (step change)
/// or a ramp steeper than the drive: the drive's own acceleration.
[[nodiscard]] double wf725_ramp_acceleration(const Wf725OpenLoopDrive& d, double mv_per_s) noexcept;
/// A level 0..99 as the BCD byte of DL 4.
[[nodiscard]] constexpr std::uint8_t wf725_level_bcd(int level) noexcept {
  return static_cast<std::uint8_t>(((level / 10) % 10) << 4 | (level % 10));
}

}  // namespace hil::controllers::s5
