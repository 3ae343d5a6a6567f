// SPDX-License-Identifier: MIT
#include "hil/mocks/legacy/clm14_sim_axes.hpp"

#include <algorithm>
#include <cmath>

namespace hil::mocks::legacy {

namespace cc = controllers::clm14;

namespace {

bool same_axis(const cc::AxisSettings& a, const cc::AxisSettings& b) {
  return a.feed_constant == b.feed_constant && a.encoder_pulses == b.encoder_pulses && a.vmax == b.vmax &&
         a.acceleration == b.acceleration && a.jog_velocity == b.jog_velocity && a.reached_window == b.reached_window;
}

}  // namespace

void Clm14SimAxes::rebuild(const cc::Settings& s) {
  for (std::size_t i = 0; i < 4; ++i) {
    Slot& slot = slots_[i];
    const auto& as = s.axes[i];
    if (!as.enabled) {
      slot = Slot{};
      continue;
    }
    if (slot.axis && same_axis(slot.built, as)) continue;
    const double keep_iu = slot.axis ? slot.axis->status().position : 0.0;
    auto cfg = cc::make_axis_config(as, "clm" + std::to_string(i + 1));
    if (!motion::validate(cfg)) {
      slot = Slot{};
      continue;
    }
    SimDriveConfig dc;
    dc.name = "sim:clm" + std::to_string(i + 1);
    dc.plant.kv_per_s = 200.0;
    dc.plant.velocity_feedforward = 1.0;
    dc.plant.max_velocity_inc_per_s = 1e9;
    dc.plant.initial_position_inc =
        std::round(keep_iu * static_cast<double>(cfg.inc_per_unit.num) / static_cast<double>(cfg.inc_per_unit.den));
    dc.homing_time = std::chrono::milliseconds(100);
    slot.axis = std::make_unique<motion::Axis>(cfg, std::make_unique<SimDrive>(dc));
    slot.port = std::make_unique<cc::MotionAxisPort>(*slot.axis);
    slot.built = as;
  }
}

cc::AxisPort* Clm14SimAxes::port(int axis) const {
  if (axis < 1 || axis > 4) return nullptr;
  return slots_[static_cast<std::size_t>(axis - 1)].port.get();
}

void Clm14SimAxes::update(const CycleTime& cycle) {
  for (auto& s : slots_)
    if (s.axis) s.axis->update(cycle);
}

void Clm14SimWheel::rebuild(const cc::Settings& s) {
  const auto& me = s.me1;
  if (!me.used()) {
    axis_.reset();
    encoder_.reset();
    return;
  }
  if (axis_ && built_.pulses == me.pulses && built_.feed_constant == me.feed_constant) return;
  const double keep_iu = axis_ ? axis_->status().position : 0.0;
  auto cfg = cc::master_encoder_config(me, s.axes[0], "me1");
  if (!motion::validate(cfg)) {
    axis_.reset();
    encoder_.reset();
    return;
  }
  SimDriveConfig dc;
  dc.name = "sim:me1";
  dc.plant.kv_per_s = 200.0;
  dc.plant.velocity_feedforward = 1.0;
  dc.plant.max_velocity_inc_per_s = 1e9;
  dc.plant.initial_position_inc =
      std::round(keep_iu * static_cast<double>(cfg.inc_per_unit.num) / static_cast<double>(cfg.inc_per_unit.den));
  axis_ = std::make_unique<motion::Axis>(cfg, std::make_unique<SimDrive>(dc));
  encoder_ = std::make_unique<cc::MotionMasterEncoder>(*axis_);
  built_ = me;
  enabled_ = false;
  (void)axis_->enable();
  if (velocity_ != 0.0) (void)set_velocity(velocity_);
}

bool Clm14SimWheel::set_velocity(double iu_per_s) {
  if (!axis_) return false;
  velocity_ = iu_per_s;
  const auto& l = axis_->config().limits;
  motion::Limits m;
  m.velocity = std::min(std::abs(iu_per_s), l.velocity);
  m.acceleration = l.acceleration;
  if (iu_per_s == 0.0)
    (void)axis_->stop();
  else
    (void)axis_->move_velocity(std::clamp(iu_per_s, -l.velocity, l.velocity), m);
  return true;
}

void Clm14SimWheel::update(const CycleTime& cycle) {
  if (!axis_) return;
  axis_->update(cycle);
  // the drive enables over a few cycles: a velocity asked for before runs once it is enabled
  const bool enabled =
      axis_->status().state == motion::AxisState::standstill || axis_->status().state == motion::AxisState::moving;
  if (enabled && !enabled_ && velocity_ != 0.0) (void)set_velocity(velocity_);
  enabled_ = enabled;
}

}  // namespace hil::mocks::legacy
