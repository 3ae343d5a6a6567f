// SPDX-License-Identifier: MIT
// WF 725/726 open-loop control (AK, MD 4 = 3/4; docs/wf725.md "Open-loop control"): the module
// outputs speed levels (X3 = level x 100 mV, DL 4 in BCD) and switches them down at the travel
// differences MD 45-48 of the remaining distance, which it measures on the encoder (the actual
// position of the simulated or real drive). The motion core runs the drive by velocity steps
// under the MD 1/MD 2 voltage ramps (WF 726) or the drive's own acceleration. Errors: 21 (PEH
// window left again), 22 (PEH timeout from the output of speed 0), 95/96 and 15/16 on the actual
// position, 7A (4th G group, in wf725_controller_program.cpp).
#include <fmt/format.h>

#include <cmath>

#include "hil/controllers/s5/wf725_controller.hpp"

namespace hil::controllers::s5 {

Wf725OpenLoopStages Wf725Controller::ol_stages() const noexcept {
  Wf725OpenLoopStages s;
  for (int i = 0; i < 3; ++i) s.levels[static_cast<std::size_t>(i)] = static_cast<int>(md_.integer(42 + i));
  for (int i = 0; i < 4; ++i) s.distances_um[static_cast<std::size_t>(i)] = static_cast<double>(md_.integer(45 + i));
  return s;
}

double Wf725Controller::ol_acceleration(int md) const noexcept {
  // MD 1 (increase) / MD 2 (decrease) in mV/s exist on the WF 726 only; 0 = step change.
  const double a = wf725_ramp_acceleration(opt_.drive, md_.series == 726 ? static_cast<double>(md_.get(md)) : 0.0);
  return std::min(a, axis(0).config().limits.acceleration);
}

double Wf725Controller::unwrapped_mm() const noexcept {
  const auto& c = axis(0).config();
  return static_cast<double>(axis(0).status().position_inc) * static_cast<double>(c.inc_per_unit.den) /
         static_cast<double>(c.inc_per_unit.num);
}

bool Wf725Controller::ol_command(int level, TimePoint now) {
  auto& ax = axis(0);
  const int before = ol_.level;
  ol_.level = level;
  if (level == 0) {
    ol_stop();
    ol_.zero = true;
    ol_.zero_at = now;
    return true;
  }
  motion::Limits lim = ax.config().limits;
  lim.acceleration = ol_acceleration(level > before ? 1 : 2);
  positioning_ = true;
  if (const auto ec = ax.move_velocity(ol_.dir * wf725_level_velocity(opt_.drive, level), lim)) {
    ol_ = OpenLoop{};
    raise_wf(ec == hil::MotionFault::not_enabled ? 0x13 : 0x62, now, ec.message());
    return false;
  }
  return true;
}

void Wf725Controller::ol_stop() {
  // Speed 0 on the MD 2 ramp: re-plan the running velocity under the decrease ramp, then stop.
  auto& ax = axis(0);
  const auto& st = ax.status();
  if (st.state != motion::AxisState::moving && st.state != motion::AxisState::stopping) return;
  motion::Limits lim = ax.config().limits;
  lim.acceleration = ol_acceleration(2);
  const double v = st.command_velocity;
  if (std::abs(v) > 0.0 && std::abs(v) <= lim.velocity) (void)ax.move_velocity(v, lim);
  (void)ax.stop();
}

bool Wf725Controller::ol_go(double target_mm, std::int64_t level, TimePoint now, motion::Direction dir) {
  // A positioning: target in machine coordinates; the distance is measured on the actual value.
  double delta = target_mm - machine_mm();
  if (md_.rotary()) {
    const double mod = static_cast<double>(md_.integer(18)) * wf_db::um;
    delta = std::fmod(delta, mod);
    if (dir == motion::Direction::positive && delta < 0) delta += mod;
    if (dir == motion::Direction::negative && delta > 0) delta -= mod;
    if (dir == motion::Direction::shortest) {
      if (delta > mod / 2) delta -= mod;
      if (delta < -mod / 2) delta += mod;
    }
  }
  ol_ = OpenLoop{};
  ol_.active = ol_.positioning = true;
  ol_.dir = delta >= 0 ? 1 : -1;
  ol_.programmed = static_cast<int>(std::clamp<std::int64_t>(level, 1, 99));  // F above 99 is reduced to 99
  ol_.target = unwrapped_mm() + delta;
  const int start = wf725_open_loop_level(ol_stages(), ol_.programmed, std::abs(delta) / wf_db::um);
  ol_history_.push_back({start, std::abs(delta) / wf_db::um});
  return ol_command(start, now);
}

bool Wf725Controller::ol_run(int direction, std::int64_t level, TimePoint now) {
  // An endless run at one level (set up, reference point approach) until stopped.
  ol_ = OpenLoop{};
  ol_.active = true;
  ol_.dir = direction;
  ol_.programmed = static_cast<int>(std::clamp<std::int64_t>(level, 1, 99));
  return ol_command(ol_.programmed, now);
}

bool Wf725Controller::ol_done() const noexcept {
  if (!ol_.active) return true;
  const auto& st = axis(0).status();
  const bool rest = !st.busy && st.state == motion::AxisState::standstill;
  return ol_.zero && rest && (!ol_.positioning || ol_.peh);
}

void Wf725Controller::ol_cycle(TimePoint now) {
  if (!ol_.active) return;
  const auto& st = axis(0).status();
  if (st.state == motion::AxisState::disabled || st.state == motion::AxisState::error) {
    ol_ = OpenLoop{};
    return;
  }
  const double window = static_cast<double>(md_.integer(33)) * wf_db::um;
  if (!ol_.positioning) {
    if (!ol_.zero && st.state == motion::AxisState::standstill && !st.busy) ol_.zero = true;
    return;
  }
  const double remaining = (ol_.target - unwrapped_mm()) * ol_.dir;
  if (!ol_.zero) {
    const int level = std::min(ol_.level, wf725_open_loop_level(ol_stages(), ol_.programmed, remaining / wf_db::um));
    if (level != ol_.level) {
      ol_history_.push_back({level, remaining / wf_db::um});
      (void)ol_command(level, now);
    }
    return;
  }
  const bool rest = !st.busy && st.state == motion::AxisState::standstill;
  const bool inside = std::abs(remaining) <= window + 1e-9;
  if (ol_.peh) {
    // §6.2.1 error 21: open loop, the PEH window already reached is left again.
    if (!inside) {
      ol_.peh = false;
      raise_wf(0x21, now,
               fmt::format("{:.0f} µm from the target, MD 33 = {}", -remaining / wf_db::um, md_.integer(33)));
      abort_job();
    }
    return;
  }
  if (rest && inside) {
    ol_.peh = true;
    return;
  }
  // §4.3 MD 30: the timer starts with the output of speed 0; the window MD 33 must be reached.
  if (now - ol_.zero_at > std::chrono::milliseconds(md_.integer(30))) {
    raise_wf(0x22, now,
             fmt::format("{:.0f} µm from the target {} ms after speed 0 (MD 33 = {}, MD 48 = {})",
                         -remaining / wf_db::um, md_.integer(30), md_.integer(33), md_.integer(48)));
    abort_job();
    ol_ = OpenLoop{};
  }
}

void Wf725Controller::ol_check_limits(TimePoint now) {
  if (!armed() || md_.rotary()) {
    range_side_ = 0;
    return;
  }
  // §4.3 MD 11-14: open loop checks the actual position. Range limits MD 12/14 -> 15/16 (drive
  // off); pre-limits MD 11/13 reached moving outwards -> 95/96 and speed 0.
  const double a = machine_mm();
  const int side = a < static_cast<double>(md_.integer(12)) * wf_db::um - 1e-9   ? -1
                   : a > static_cast<double>(md_.integer(14)) * wf_db::um + 1e-9 ? 1
                                                                                 : 0;
  if (side != 0 && side != range_side_) {
    abort_job();
    raise_wf(side < 0 ? 0x15 : 0x16, now, fmt::format("actual position {:.3f} mm", a));
  }
  range_side_ = side;
  if (!ol_.active || ol_.zero || side != 0) return;
  const bool minus = ol_.dir < 0 && a <= static_cast<double>(md_.integer(11)) * wf_db::um;
  const bool plus = ol_.dir > 0 && a >= static_cast<double>(md_.integer(13)) * wf_db::um;
  if (!minus && !plus) return;
  abort_job();
  raise_wf(minus ? 0x95 : 0x96, now, fmt::format("actual position {:.3f} mm", a));
}

}  // namespace hil::controllers::s5
