// SPDX-License-Identifier: MIT
#include "hil/mocks/plant.hpp"

#include <algorithm>
#include <cmath>

namespace hil::mocks {

Plant::Plant(PlantConfig config) : config_(config), position_(config.initial_position_inc) {
  config_.encoder_step_inc = std::max<std::int64_t>(1, config_.encoder_step_inc);
  sample_encoder();
}

void Plant::step(Duration dt, const PlantInput& in) noexcept {
  double left = to_seconds(dt);
  if (!(left > 0.0)) return;
  // Keep Kv * h well inside the explicit integrator's stability region.
  const double h_max = std::min(2.5e-4, 0.2 / std::max(config_.kv_per_s, 1e-9));
  while (left > 0.0) {
    const double h = std::min(left, h_max);
    substep(h, in);
    left -= h;
  }
  sample_encoder();
}

void Plant::substep(double h, const PlantInput& in) noexcept {
  double v_cmd = 0.0;
  const bool drives = in.powered && !has(PlantFault::not_ready);
  if (drives) {
    if (in.mode == CommandMode::position) {
      const double reading = position_ + offset_;
      v_cmd = config_.kv_per_s * (in.position_inc - reading) + config_.velocity_feedforward * in.velocity_inc_per_s;
    } else {
      v_cmd = in.velocity_inc_per_s;
    }
    v_cmd = std::clamp(v_cmd, -config_.max_velocity_inc_per_s, config_.max_velocity_inc_per_s);
  }
  if (has(PlantFault::following_blowup)) v_cmd = 0.0;  // jammed: the stage no longer moves the load
  const double alpha = config_.velocity_lag_s > 0.0 ? 1.0 - std::exp(-h / config_.velocity_lag_s) : 1.0;
  const double v_new = velocity_ + (v_cmd - velocity_) * alpha;
  position_ += 0.5 * (velocity_ + v_new) * h;
  velocity_ = v_new;
}

void Plant::sample_encoder() noexcept {
  if (has(PlantFault::encoder)) return;  // frozen reading
  const double step = static_cast<double>(config_.encoder_step_inc);
  encoder_ = static_cast<std::int64_t>(std::floor((position_ + offset_) / step + 1e-9)) * config_.encoder_step_inc;
}

void Plant::set_position(double position_inc) noexcept {
  offset_ = position_inc - position_;
  sample_encoder();
}

void Plant::inject(PlantFault f, bool active) noexcept {
  if (f == PlantFault::none) {
    faults_ = 0;
    return;
  }
  if (active)
    faults_ |= bit(f);
  else
    faults_ &= ~bit(f);
}

PlantFault Plant::fault() const noexcept {
  for (auto f : {PlantFault::encoder, PlantFault::not_ready, PlantFault::following_blowup})
    if (has(f)) return f;
  return PlantFault::none;
}

}  // namespace hil::mocks
