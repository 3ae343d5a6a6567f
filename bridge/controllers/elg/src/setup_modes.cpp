// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/setup_modes.hpp"

#include "hil/motion/zero_mark.hpp"

#include "edge.hpp"

namespace hil::controllers::elg {
namespace {
using detail::rising;
}  // namespace

std::int64_t SetupModes::override_percent(int position) const noexcept {
  if (position < 2 || position > 16) return 0;  // position 1: 0 %, always a hard stop (7.1)
  return md_.override_percent[static_cast<std::size_t>(position - 2)];
}

void SetupModes::abort() noexcept {
  state_ = SetupState::idle;
  command_ = {};
  direction_ = 0;
}

std::optional<Alarm> SetupModes::start(const PanelSignals& p, std::int64_t c_set, int direction) {
  const std::int64_t pct = override_percent(p.override_position);
  // Rapid traverse and REF take the override only with "rapid traverse override active"; 0 %
  // always stops (7.1, 7.3).
  const std::int64_t rapid_pct = pct == 0 ? 0 : (p.rapid_override ? pct : 100);
  std::int64_t md = 0, percent = pct;
  switch (p.mode) {
    case PanelMode::jog:
      md = p.rapid ? md_.rapid_speed : md_.jog_speed;
      percent = p.rapid ? rapid_pct : pct;
      break;
    case PanelMode::inc:
      md = md_.inc_speed;
      break;
    case PanelMode::ref:
      md = md_.ref_speed;
      percent = rapid_pct;
      break;
    case PanelMode::automatic:
      return std::nullopt;
  }
  // 2035: the set speed (MD x override) above the axis' maximum speed MD 280*; C does not move.
  if (md * percent > md_.max_speed * 100) {
    abort();
    return Alarm::program_speed_too_high;
  }
  direction_ = direction;
  const double v = md_speed_counts_per_s(md, percent);
  switch (p.mode) {
    case PanelMode::jog:
      state_ = SetupState::jogging;
      command_ = {SetupCommand::Kind::velocity, 0, direction * v};
      break;
    case PanelMode::inc:
      state_ = SetupState::incrementing;
      // dS = n * 2 MS from C's set value (7.2): exact, independent of where C settled.
      command_ = {SetupCommand::Kind::position, c_set + direction * p.inc_factor * 2, v};
      break;
    case PanelMode::ref:
      state_ = p.ref_cam ? SetupState::ref_to_zero_mark : SetupState::ref_to_cam;
      command_ = {SetupCommand::Kind::velocity, 0,
                  direction * (p.ref_cam ? md_speed_counts_per_s(md_.ref_cutoff_speed, percent) : v)};
      break;
    case PanelMode::automatic:
      break;
  }
  return std::nullopt;
}

std::optional<Alarm> SetupModes::run_ref(const PanelSignals& p, std::int64_t c_actual) {
  const std::int64_t pct = override_percent(p.override_position);
  const std::int64_t percent = pct == 0 ? 0 : (p.rapid_override ? pct : 100);
  const auto behind_cam = static_cast<Alarm>(static_cast<int>(Alarm::stop_behind_reference_cams) + md_.axis_index);
  if (state_ == SetupState::ref_to_cam) {
    if (p.mode != PanelMode::ref) {  // a mode change before the cam: the approach just ends
      abort();
      return std::nullopt;
    }
    if (p.ref_cam) {
      state_ = SetupState::ref_to_zero_mark;
      last_actual_ = c_actual;
    } else {
      command_.velocity_counts_per_s = direction_ * md_speed_counts_per_s(md_.ref_speed, percent);
      return std::nullopt;
    }
  }
  // Behind the cam: MD 284* to the next zero mark. Stopping here (override 0 %, a mode change)
  // leaves C between cam and zero mark: 184* (10.2).
  if (p.mode != PanelMode::ref || percent == 0) {
    abort();
    return behind_cam;
  }
  command_.velocity_counts_per_s = direction_ * md_speed_counts_per_s(md_.ref_cutoff_speed, percent);
  const motion::ZeroMarkGrid grid{md_.zero_mark_counts, 0};
  const std::optional<std::int64_t> mark = direction_ > 0   ? grid.passed_forward(last_actual_, c_actual)
                                           : direction_ < 0 ? grid.passed_backward(last_actual_, c_actual)
                                                            : std::nullopt;
  last_actual_ = c_actual;
  if (mark) {
    // Reference point reached: the actual value at the zero mark becomes MD 240* (7.3).
    offset_ = md_.ref_coordinate - *mark;
    referenced_ = true;
    abort();
  }
  return std::nullopt;
}

std::optional<Alarm> SetupModes::step(const PanelSignals& p, std::int64_t c_set, std::int64_t c_actual,
                                      bool c_in_position, bool coupled, bool blocked) {
  std::optional<Alarm> alarm;
  const bool plus_edge = rising(p.key_plus, last_.key_plus), minus_edge = rising(p.key_minus, last_.key_minus);
  const bool setting_up = p.mode != PanelMode::automatic;
  if (blocked) {
    // JOG, INC and REF are not available while coupled (4.1): the key is not accepted.
    if (coupled && setting_up && (plus_edge || minus_edge)) ++refusals_;
    if (state_ == SetupState::ref_to_zero_mark)
      alarm = static_cast<Alarm>(static_cast<int>(Alarm::stop_behind_reference_cams) + md_.axis_index);
    abort();
    last_ = p;
    return alarm;
  }
  switch (state_) {
    case SetupState::idle: {
      if (p.mode == PanelMode::jog) {
        // JOG moves while one key is held; a key held across a refusal needs a new press.
        const bool plus = p.key_plus && !p.key_minus, minus = p.key_minus && !p.key_plus;
        const bool fresh = last_.mode != PanelMode::jog;
        if ((plus && (!last_.key_plus || fresh)) || (minus && (!last_.key_minus || fresh)))
          alarm = start(p, c_set, plus ? 1 : -1);
      } else if (p.mode == PanelMode::inc && plus_edge != minus_edge) {
        alarm = start(p, c_set, plus_edge ? 1 : -1);
      } else if (p.mode == PanelMode::ref && plus_edge != minus_edge) {
        const int wanted = md_.ref_minus ? -1 : 1;
        if ((plus_edge ? 1 : -1) != wanted)
          ++refusals_;  // wrong direction: not accepted, no motion (7.3)
        else
          alarm = start(p, c_set, wanted);
      }
      break;
    }
    case SetupState::jogging: {
      const bool held = direction_ > 0 ? (p.key_plus && !p.key_minus) : (p.key_minus && !p.key_plus);
      if (p.mode != PanelMode::jog || !held) {
        abort();
        break;
      }
      // Override and rapid key act during the motion; 2035 stops it.
      const int direction = direction_;
      alarm = start(p, c_set, direction);
      break;
    }
    case SetupState::incrementing: {
      if (p.mode != PanelMode::inc) {
        abort();
        break;
      }
      // The override acts during the step; 0 % holds C and the step resumes when it rises.
      command_.velocity_counts_per_s = md_speed_counts_per_s(md_.inc_speed, override_percent(p.override_position));
      if (c_in_position && c_set == command_.target) abort();
      break;
    }
    case SetupState::ref_to_cam:
    case SetupState::ref_to_zero_mark:
      alarm = run_ref(p, c_actual);
      break;
  }
  last_ = p;
  return alarm;
}

}  // namespace hil::controllers::elg
