// SPDX-License-Identifier: MIT
// The CLM1.4's homing options 1-4 (manual §7.9, digest §5.7) as a step function in increments.
#include "hil/controllers/clm14/homing.hpp"

#include <algorithm>
#include <cstdlib>

#include "hil/controllers/clm14/error.hpp"

namespace hil::controllers::clm14 {

namespace {
constexpr int cam_too_short = static_cast<int>(ClmError::cam_too_short);
constexpr int no_marker = static_cast<int>(ClmError::no_marker_pulse);
constexpr int marker_position = static_cast<int>(ClmError::marker_pulse_position);
constexpr int marker_high = static_cast<int>(ClmError::marker_high);
constexpr int not_possible = static_cast<int>(ClmError::hom_command);
}  // namespace

HomingStatus Homing::status() const noexcept {
  switch (phase_) {
    case Phase::idle:
      return HomingStatus::idle;
    case Phase::done:
      return HomingStatus::done;
    case Phase::failed:
      return HomingStatus::failed;
    default:
      return HomingStatus::busy;
  }
}

double Homing::v3() const noexcept {
  return std::min(v2(), 10.0 / setup_.cycle_s);  // "V3 <= 10 increments/cycle"
}

double Homing::v4() const noexcept {
  return std::min(v3(), 1.0 / setup_.cycle_s);  // "V4 <= 1 increment/cycle": the marker to ±1 increment
}

bool Homing::beyond(std::int64_t from, std::int64_t pos, std::int64_t limit) const noexcept {
  return limit > 0 && std::llabs(pos - from) > limit;
}

HomingCommand Homing::fail(int code) {
  error_ = code;
  phase_ = Phase::failed;
  return {HomingCommand::Kind::stop, 0.0, 0};
}

HomingCommand Homing::run(double v) {
  return {HomingCommand::Kind::run, v, 0};
}

HomingCommand Homing::stop(Phase next) {
  phase_ = next;
  return {HomingCommand::Kind::stop, 0.0, 0};
}

bool Homing::marker_stuck(const HomingInput& in) {
  if (!in.marker_high) {
    high_since_.reset();
    return false;
  }
  if (!high_since_) high_since_ = in.position_inc;
  // A marker pulse is a fraction of one line wide; high over 1/16 revolution is a stuck line.
  return std::llabs(in.position_inc - *high_since_) * 16 > setup_.revolution_inc;
}

HomingCommand Homing::start(const HomingSetup& setup, const HomingInput& in) {
  setup_ = setup;
  setup_.revolution_inc = std::max<std::int64_t>(setup_.revolution_inc, 4);
  setup_.direction = setup_.direction < 0 ? -1 : 1;
  error_ = 0;
  edge_seen_ = false;
  high_since_.reset();
  switch_last_ = in.home_switch;
  origin_ = in.position_inc;
  const double d = setup_.direction;
  if (setup_.type < 0 || setup_.type > 3) return fail(not_possible);
  if (setup_.type != 1 && !setup_.has_switch) return fail(not_possible);
  switch (setup_.type) {
    case 0:
      phase_ = in.home_switch ? Phase::leave_cam : Phase::seek_cam;
      return run(in.home_switch ? -d * v2() : d * v1());
    case 1:
      phase_ = Phase::first_marker;
      return run(d * std::min(v1(), 10.0 / setup_.cycle_s));
    case 2:
      phase_ = Phase::seek_edge;
      return run(d * v1());
    default:
      phase_ = in.home_switch ? Phase::leave_cam : Phase::seek_edge;
      return run(in.home_switch ? -d * v2() : d * v1());
  }
}

HomingCommand Homing::step(const HomingInput& in) {
  const double d = setup_.direction;
  const std::int64_t pos = in.position_inc;
  const std::int64_t rev = setup_.revolution_inc;
  const bool rising = in.home_switch && !switch_last_;
  switch_last_ = in.home_switch;
  const bool searching_marker = phase_ == Phase::approach || phase_ == Phase::first_marker ||
                                phase_ == Phase::creep_back || phase_ == Phase::creep_second;
  if (searching_marker && marker_stuck(in)) return fail(marker_high);
  switch (phase_) {
    case Phase::seek_cam:
      if (in.home_switch) return stop(Phase::brake_on_cam);
      if (beyond(origin_, pos, setup_.search_limit_inc)) return fail(not_possible);
      return {};
    case Phase::brake_on_cam:
      if (!in.standstill) return {};
      if (!in.home_switch) return fail(cam_too_short);  // braked past the whole cam
      phase_ = Phase::leave_cam;
      origin_ = pos;
      return run(-d * v2());
    case Phase::leave_cam:
      if (!in.home_switch) return stop(Phase::brake_off_cam);
      if (beyond(origin_, pos, setup_.search_limit_inc)) return fail(not_possible);
      return {};
    case Phase::brake_off_cam:
      if (!in.standstill) return {};
      origin_ = pos;
      if (setup_.type == 0) {
        phase_ = Phase::approach;
        edge_seen_ = false;
        high_since_.reset();
        return run(d * v3());
      }
      phase_ = Phase::seek_edge;
      switch_last_ = in.home_switch;
      return run(d * v1());
    case Phase::approach:
      if (!edge_seen_) {
        if (in.home_switch) {
          edge_seen_ = true;
          edge_ = pos;
        } else if (beyond(origin_, pos, setup_.search_limit_inc)) {
          return fail(not_possible);
        }
      } else if (!in.home_switch) {
        return fail(cam_too_short);  // the cam ended before its marker
      }
      if (!edge_seen_) return {};
      if (in.marker && (*in.marker - edge_) * setup_.direction >= 0) {
        edge_marker_ = std::llabs(*in.marker - edge_);
        if (edge_marker_ * 16 < rev || edge_marker_ * 16 > 15 * rev) return fail(marker_position);
        mark_ = *in.marker;
        return stop(Phase::brake_marker);
      }
      if (std::llabs(pos - edge_) > rev) return fail(no_marker);
      return {};
    case Phase::brake_marker:
      if (!in.standstill) return {};
      phase_ = Phase::creep_back;
      origin_ = pos;
      high_since_.reset();
      return run(-d * v4());
    case Phase::creep_back:
      if (in.marker) {
        home_inc_ = *in.marker;
        return stop(Phase::brake_final);
      }
      // Back past the marker by 1/16 revolution without seeing it again.
      if ((mark_ - pos) * setup_.direction * 16 > rev) return fail(no_marker);
      return {};
    case Phase::first_marker:
      if (in.marker) {
        mark_ = *in.marker;
        phase_ = Phase::to_second;
        origin_ = mark_ + setup_.direction * (rev - rev / 32);
        return {HomingCommand::Kind::move, v1(), origin_};
      }
      if (beyond(origin_, pos, rev)) return fail(no_marker);
      return {};
    case Phase::to_second:
      if (in.marker && *in.marker != mark_) {
        home_inc_ = *in.marker;
        return stop(Phase::brake_final);
      }
      if (!in.standstill || std::llabs(pos - origin_) * 64 > rev) return {};
      phase_ = Phase::creep_second;
      high_since_.reset();
      return run(d * v4());
    case Phase::creep_second:
      if (in.marker) {
        home_inc_ = *in.marker;
        return stop(Phase::brake_final);
      }
      if ((pos - origin_) * setup_.direction * 16 > rev) return fail(no_marker);
      return {};
    case Phase::seek_edge:
      if (rising) {
        home_inc_ = pos;  // the switch is sampled once per NC cycle
        return stop(Phase::brake_final);
      }
      if (beyond(origin_, pos, setup_.search_limit_inc)) return fail(not_possible);
      return {};
    case Phase::brake_final:
      if (in.standstill) phase_ = Phase::done;
      return {};
    case Phase::idle:
    case Phase::done:
    case Phase::failed:
      return {};
  }
  return {};
}

}  // namespace hil::controllers::clm14
