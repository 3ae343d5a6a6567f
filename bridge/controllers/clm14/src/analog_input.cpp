// SPDX-License-Identifier: MIT
// CLM1.4 analog inputs: the B017 moving average and the override factor (digest §5.6).
#include "hil/controllers/clm14/analog_input.hpp"

#include <algorithm>

namespace hil::controllers::clm14 {

void AnalogAverage::reset(int code, int millivolts) {
  code_ = std::clamp(code, 0, 9);
  history_.assign(std::size_t{1} << (code_ + 3), millivolts);
  next_ = 0;
  sum_ = static_cast<std::int64_t>(millivolts) * static_cast<std::int64_t>(history_.size());
}

void AnalogAverage::push(int millivolts) noexcept {
  if (history_.empty()) return;
  sum_ += millivolts - history_[next_];
  history_[next_] = millivolts;
  next_ = (next_ + 1) % history_.size();
}

double AnalogAverage::millivolts() const noexcept {
  // N is a power of two: the quotient is exact in binary floating point.
  return history_.empty() ? 0.0 : static_cast<double>(sum_) / static_cast<double>(history_.size());
}

double analog_override(double millivolts) noexcept {
  return std::clamp(millivolts / 10000.0, 0.0, 1.0);
}

}  // namespace hil::controllers::clm14
