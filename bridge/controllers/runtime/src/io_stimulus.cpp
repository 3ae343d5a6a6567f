// SPDX-License-Identifier: MIT
#include "hil/controllers/io_stimulus.hpp"

#include <cmath>

namespace hil::controllers {

void TimedInput::read(TimePoint now, IoImage& image) noexcept {
  if (!origin_) origin_ = now;
  const Duration t = now - *origin_;
  if (t < at_) return;
  if (width_ > Duration::zero() && t >= at_ + width_) {
    image.set(bit_, !value_);
    return;
  }
  image.set(bit_, value_);
}

void ConditionInput::read(TimePoint now, IoImage& image) noexcept {
  if (!fired_) {
    if (!condition_ || !condition_()) return;
    fired_ = now;
  }
  if (width_ > Duration::zero() && now - *fired_ >= width_) {
    image.set(bit_, !value_);
    return;
  }
  image.set(bit_, value_);
}

void PositionCam::read(TimePoint, IoImage& image) noexcept {
  const double p = axis_.status().position;
  active_ = (!from_ || p >= *from_) && (!to_ || p <= *to_);
  image.set(bit_, active_ != active_low_);
}

void RegistrationMark::read(TimePoint now, IoImage& image) noexcept {
  const double p = axis_.status().position;
  if (last_position_) {
    const double a = *last_position_ - position_;
    const double b = p - position_;
    const bool crossed = (a < 0.0 && b >= 0.0) || (a > 0.0 && b <= 0.0);
    if (crossed) {
      const double frac = (a == b) ? 1.0 : a / (a - b);
      const auto dt = std::chrono::duration_cast<Duration>((now - last_t_) * frac);
      const double q = accuracy_ > 0.0 ? std::round(position_ / accuracy_) * accuracy_ : position_;
      if (latches_.size() < latches_.capacity()) latches_.push_back(Latch{last_t_ + dt, q});
      pulse_since_ = now;
    }
  }
  last_position_ = p;
  last_t_ = now;
  const bool on = pulse_since_ && (now == *pulse_since_ || now - *pulse_since_ < width_);
  image.set(bit_, on);
  if (!on) pulse_since_.reset();
}

}  // namespace hil::controllers
