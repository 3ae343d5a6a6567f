// SPDX-License-Identifier: MIT
// CLM1.4 master encoder 2 (C004-C007, §8.4: "the same for master encoder 2"; digest §3.10): its
// count, travel and velocity as master encoder 1's, for FUN's channel 6 (V042 / V043) and the
// override of VEO source 6 [decided]. The encoder overrides of VEO sources 5 and 6.
#include <algorithm>
#include <cmath>

#include "hil/controllers/clm14/controller.hpp"

namespace hil::controllers::clm14 {

void Controller::attach_master_encoder2(MasterEncoderPort* port) {
  me2_ = MasterIn{};
  me2_.port = port;
}

bool Controller::master2_available() const noexcept {
  return me2_.port != nullptr && settings_.me2.used();
}

double Controller::master2_position() const noexcept {
  const auto& me = settings_.me2;
  if (!me.used()) return 0.0;
  return static_cast<double>(me2_.count) * me.feed_constant / (static_cast<double>(me.pulses) * 4.0);
}

double Controller::master2_velocity() const noexcept {
  const auto& me = settings_.me2;
  if (!me.used()) return 0.0;
  return me2_.velocity * me.feed_constant / (static_cast<double>(me.pulses) * 4.0);
}

void Controller::update_master2_in() {
  if (me2_.port == nullptr) return;
  const std::int64_t raw = me2_.input.update(me2_.port->count());
  me2_.count = settings_.me2.inverted ? -raw : raw;
  me2_.record(settings_.cycle_ms, true);  // the same window as master encoder 1 and the axes
}

double Controller::encoder_override(int axis) const {
  const auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  const auto& f = follow_[static_cast<std::size_t>(axis - 1)];
  const double vmax = settings_.axes[static_cast<std::size_t>(axis - 1)].vmax;
  const double v = a.override_encoder == 2 ? master2_velocity() : master_velocity();
  return std::abs(v) / vmax * to_double(f.factor);
}

}  // namespace hil::controllers::clm14
