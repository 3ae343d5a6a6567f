// SPDX-License-Identifier: MIT
#include "hil/controllers/analog_stimulus.hpp"

#include <algorithm>

#include "hil/controllers/controller.hpp"

namespace hil::controllers {

double analog_value_at(const std::vector<AnalogStep>& steps, double initial, Duration t) noexcept {
  double v = initial;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const AnalogStep& s = steps[i];
    if (t < s.at) break;
    // The ramp runs until its end or until the next step takes over, whichever comes first.
    Duration until = t;
    if (i + 1 < steps.size() && steps[i + 1].at <= t) until = steps[i + 1].at;
    const Duration in = until - s.at;
    if (s.ramp <= Duration::zero() || in >= s.ramp) {
      v = s.value;
    } else {
      const double f = static_cast<double>(in.count()) / static_cast<double>(s.ramp.count());
      v += (s.value - v) * f;
    }
  }
  return v;
}

void AnalogSchedule::read(TimePoint now, IoImage&) noexcept {
  if (!origin_) origin_ = now;
  const Duration t = now - *origin_;
  if (steps_.empty() || t < steps_.front().at) return;
  controller_.set_analog(handle_, analog_value_at(steps_, initial_, t));
}

Duration AnalogSchedule::last_change() const noexcept {
  Duration last{};
  for (const AnalogStep& s : steps_) last = std::max(last, s.at + s.ramp);
  return last;
}

}  // namespace hil::controllers
