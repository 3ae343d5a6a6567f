// SPDX-License-Identifier: MIT
#include "hil/stepdir/step_planner.hpp"

#include <algorithm>
#include <cmath>

namespace hil::stepdir {

StepPlanner::StepPlanner(const StepTiming& timing, std::shared_ptr<const Ip247Ramp> ramp, std::int64_t backlash_steps,
                         StepLineIndex lines) noexcept
    : timing_(timing),
      ramp_(std::move(ramp)),
      backlash_(std::max<std::int64_t>(0, backlash_steps)),
      lines_(lines),
      min_period_(timing.min_period_ns()),
      first_interval_(ramp_->interval_ns(0)) {
  v_period_ = std::max(min_period_, ramp_->interval_ns(ramp_->table().size()));
  cap_idx_ = static_cast<std::int64_t>(ramp_->table().size() - 1);
}

void StepPlanner::set_mode(PlannerMode m) noexcept {
  if (m == mode_) return;
  if (m == PlannerMode::ramp && moving_) {
    // Continue from the speed we have now.
    last_idx_ = static_cast<std::int64_t>(ramp_->index_for_period(std::max(last_interval_ns_, min_period_)));
  }
  mode_ = m;
}

bool StepPlanner::move_to(std::int64_t target, double f_v_hz) noexcept {
  const auto& p = ramp_->params();
  bool in_range = f_v_hz >= 1.0 && f_v_hz <= p.f_max_hz && std::isfinite(f_v_hz);
  double f = std::isfinite(f_v_hz) ? std::clamp(f_v_hz, p.f_ss_hz, p.f_max_hz) : p.f_ss_hz;
  v_period_ = std::max(min_period_, static_cast<std::int64_t>(std::ceil(1e9 / f)));
  cap_idx_ = static_cast<std::int64_t>(ramp_->index_for_period(v_period_));
  target_ = target;
  return in_range;
}

void StepPlanner::halt() noexcept {
  if (mode_ == PlannerMode::follow || !moving_) {
    stop_now();
    return;
  }
  // Steps still needed to decelerate from the current table index down to f_ss. A halt only
  // ever shortens the move: halting again while braking (a limit switch seen every cycle) must
  // not push the end ahead by the shrinking braking distance, or the axis creeps on at f_ss.
  const std::int64_t brake_end = pos_ + dir_ * (last_idx_ + 1 - backlash_pending_);
  if (dir_ * (brake_end - target_) < 0) target_ = brake_end;
}

void StepPlanner::stop_now() noexcept {
  target_ = pos_;
  moving_ = false;
}

void StepPlanner::set_position(std::int64_t position, int last_direction) noexcept {
  pos_ = target_ = position;
  last_dir_ = last_direction > 0 ? 1 : (last_direction < 0 ? -1 : 0);
  backlash_pending_ = 0;
  moving_ = false;
}

std::int64_t StepPlanner::backlash_after(int d) const noexcept {
  if (last_dir_ == 0) return 0;  // direction unknown: no compensation on the first move (IP247 §4.2.5)
  if (d == last_dir_) return backlash_pending_;
  return backlash_ - backlash_pending_;  // re-take what was already taken up
}

void StepPlanner::start_constraints(std::int64_t now, int d, Candidate& c) const noexcept {
  std::int64_t t = std::max(now, last_edge_);
  if (dir_line_ != d) {
    const std::int64_t td = std::max({now, last_fall_ + timing_.dir_hold_ns, last_edge_});
    c.dir_edge = td;
    t = std::max(t, td + timing_.dir_setup_ns);
  }
  c.rise = std::max({c.rise, t, last_rise_ + min_period_, last_fall_ + timing_.step_space_ns});
}

bool StepPlanner::next_ramp(std::int64_t now, Candidate& c) noexcept {
  if (moving_) {
    const std::int64_t r = (target_ - pos_) * dir_ + backlash_pending_;
    if (r <= 0 && last_idx_ <= 0) {
      moving_ = false;  // at f_ss: stop at once
    } else {
      std::int64_t idx = std::min({last_idx_ + 1, cap_idx_, r - 1});
      idx = std::max(idx, last_idx_ - 1);  // never faster deceleration than the ramp
      c.idx = idx;
      c.d = dir_;
      const std::int64_t iv =
          std::max(ramp_->interval_ns(static_cast<std::size_t>(std::max<std::int64_t>(idx, 0))), v_period_);
      c.rise = last_rise_ + iv;
      return true;
    }
  }
  if (target_ == pos_) return false;
  c.d = target_ > pos_ ? 1 : -1;
  c.start = true;
  c.idx = -1;
  // Start-stop: at least one f_ss period after the previous move's last step.
  c.rise = last_rise_ + first_interval_;
  start_constraints(now, c.d, c);
  return true;
}

bool StepPlanner::next_follow(std::int64_t now, std::int64_t horizon, Candidate& c) noexcept {
  const std::int64_t delta = target_ - pos_;
  int d = delta > 0 ? 1 : (delta < 0 ? -1 : 0);
  std::int64_t bp = 0;
  if (d == 0) {
    if (backlash_pending_ == 0 || last_dir_ == 0) {
      moving_ = false;
      return false;
    }
    d = last_dir_;  // finish taking up backlash toward the position just commanded
    bp = backlash_pending_;
  } else {
    bp = d == last_dir_ ? backlash_pending_ : backlash_after(d);
  }
  const std::int64_t n = (delta < 0 ? -delta : delta) + bp;
  const std::int64_t base = std::max(last_rise_, now);
  c.d = d;
  c.start = !moving_ || d != dir_;
  c.rise = base + std::max<std::int64_t>(1, (horizon - base) / n);
  if (dir_line_ != d || c.start) {
    start_constraints(now, d, c);
  } else {
    c.rise = std::max({c.rise, last_rise_ + min_period_, last_fall_ + timing_.step_space_ns, last_edge_});
  }
  return true;
}

bool StepPlanner::next_step(std::int64_t now, std::int64_t horizon, Candidate& c) noexcept {
  c = Candidate{};
  return mode_ == PlannerMode::ramp ? next_ramp(now, c) : next_follow(now, horizon, c);
}

void StepPlanner::commit(const Candidate& c) noexcept {
  const bool active = !timing_.step_idle_level();
  if (c.dir_edge >= 0) {
    push(c.dir_edge, lines_.dir, timing_.dir_level(c.d));
    dir_line_ = c.d;
  }
  if (c.d != last_dir_) backlash_pending_ = backlash_after(c.d);
  if (c.start) {
    moving_ = true;
    dir_ = c.d;
  }
  if (mode_ == PlannerMode::ramp) last_idx_ = c.idx;
  push(c.rise, lines_.step, active);
  push(c.rise + timing_.step_len_ns, lines_.step, !active);
  if (backlash_pending_ > 0) {
    --backlash_pending_;
    ++backlash_total_;
  } else {
    pos_ += c.d;
  }
  motor_pos_ += c.d;
  ++steps_total_;
  last_dir_ = c.d;
  last_interval_ns_ = c.rise - last_rise_;
  last_rise_ = c.rise;
  last_fall_ = c.rise + timing_.step_len_ns;
  last_edge_ = last_fall_;
  // Done as soon as the last step is out (so moving() is exact without another plan() call).
  const std::int64_t r = (target_ - pos_) * dir_ + backlash_pending_;
  if (mode_ == PlannerMode::ramp ? (r <= 0 && last_idx_ <= 0) : (pos_ == target_ && backlash_pending_ == 0)) {
    moving_ = false;
  }
}

PlanStatus StepPlanner::plan(std::int64_t now_ns, std::int64_t horizon_ns, std::vector<gpio::Edge>& out) {
  for (;;) {
    while (pending_head_ < pending_n_ && pending_[pending_head_].t_ns <= horizon_ns) {
      out.push_back(pending_[pending_head_++]);
    }
    const bool behind = mode_ == PlannerMode::follow && (pos_ != target_ || backlash_pending_ > 0);
    if (pending_head_ < pending_n_) return behind ? PlanStatus::lagging : PlanStatus::ok;
    pending_head_ = pending_n_ = 0;
    Candidate c;
    if (!next_step(now_ns, horizon_ns, c)) return PlanStatus::ok;
    if (c.rise > horizon_ns) return behind ? PlanStatus::lagging : PlanStatus::ok;
    commit(c);
  }
}

}  // namespace hil::stepdir
