// SPDX-License-Identifier: MIT
#include "hil/mocks/plant.hpp"

#include <algorithm>
#include <cmath>

namespace hil::mocks {

Plant::Plant(PlantConfig config) : config_(config), position_(config.initial_position_inc) {
  config_.encoder_step_inc = std::max<std::int64_t>(1, config_.encoder_step_inc);
  sample_encoder();
}

std::size_t Plant::step(Duration dt, const PlantInput& in) noexcept {
  const double t = to_seconds(dt);
  if (!(t > 0.0)) return 0;
  // Keep Kv * h well inside the explicit integrator's stability region, in a bounded number of
  // equal sub-steps (counted, so a gain or a step of any size always ends).
  const double wanted = std::ceil(t * std::max(1.0 / 2.5e-4, config_.kv_per_s / 0.2));
  const std::size_t n = wanted >= static_cast<double>(max_substeps)
                            ? max_substeps
                            : std::max<std::size_t>(1, static_cast<std::size_t>(wanted));
  const double h = t / static_cast<double>(n);
  const double before = position_;
  for (std::size_t i = 0; i < n; ++i) substep(h, in);
  measured_velocity_ = (position_ - before) / t;
  sample_encoder();
  return n;
}

void Plant::substep(double h, const PlantInput& in) noexcept {
  double v_cmd = 0.0;
  const bool drives = in.powered && !has(PlantFault::not_ready);
  if (drives) {
    if (in.mode == CommandMode::position) {
      const double reading = position_ + offset_;
      // A gain beyond what the sub-step resolves acts as the fastest stable loop (Kv h = 0.2).
      const double kv = std::min(config_.kv_per_s, 0.2 / h);
      v_cmd = kv * (in.position_inc - reading) + config_.velocity_feedforward * in.velocity_inc_per_s;
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
