// SPDX-License-Identifier: MIT
#include "hil/mocks/legacy/clm14_sim_axes.hpp"

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

}  // namespace hil::mocks::legacy
