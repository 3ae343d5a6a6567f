// SPDX-License-Identifier: MIT
// Open-loop staged positioning of the WF 725/726 (docs/wf725.md, "Open-loop control").
#include "hil/controllers/s5/wf725_open_loop.hpp"

#include <algorithm>

namespace hil::controllers::s5 {

int wf725_open_loop_level(const Wf725OpenLoopStages& s, int programmed, double remaining_um) noexcept {
  const int p = std::clamp(programmed, 0, 99);
  const auto& d = s.distances_um;
  if (remaining_um <= d[3]) return 0;
  if (remaining_um <= d[2]) return std::min(p, s.levels[2]);
  if (remaining_um <= d[1]) return std::min(p, s.levels[1]);
  if (remaining_um <= d[0]) return std::min(p, s.levels[0]);
  return p;
}

Wf725CutOffOutputs wf725_cut_off_outputs(const Wf725OpenLoopStages& s, double remaining_um) noexcept {
  const auto& d = s.distances_um;
  return {remaining_um > d[1], remaining_um > d[2], remaining_um > d[3], remaining_um <= d[2]};
}

double wf725_ramp_acceleration(const Wf725OpenLoopDrive& d, double mv_per_s) noexcept {
  const double per_mv = d.speed_at_10v_mm_min / 60.0 / 10000.0;  // mm/s per mV
  const double a = mv_per_s * per_mv;
  return a > 0.0 ? std::min(a, d.acceleration) : d.acceleration;
}

}  // namespace hil::controllers::s5
