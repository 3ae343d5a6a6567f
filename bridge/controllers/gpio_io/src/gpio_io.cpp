// SPDX-License-Identifier: MIT
#include "hil/controllers/gpio_io.hpp"

namespace hil::controllers {

void GpioInputs::read(TimePoint, IoImage& image) noexcept {
  bool failed = false;
  for (const auto& m : map_) {
    const auto v = lines_.get_value(m.line);
    if (!v) {
      ++errors_;
      last_error_ = v.error();
      last_failed_line_ = m.line;
      failed = true;
      image.set(m.bit, false);  // fail-safe: a line that cannot be read reads de-energised
      continue;
    }
    image.set(m.bit, *v != m.active_low);
  }
  if (failed && !failing_) ++outages_;
  failing_ = failed;
}

void GpioOutputs::write(TimePoint, const IoImage& image) noexcept {
  bool failed = false;
  for (std::size_t i = 0; i < map_.size(); ++i) {
    const auto& m = map_[i];
    const bool level = image.get(m.bit) != m.active_low;
    if (written_[i] == static_cast<int>(level)) continue;
    if (const auto ec = lines_.set_value(m.line, level)) {
      ++errors_;
      last_error_ = ec;
      last_failed_line_ = m.line;
      failed = true;
      continue;  // not marked written: tried again next cycle
    }
    written_[i] = level ? 1 : 0;
  }
  if (failed && !failing_) ++outages_;
  failing_ = failed;
}

}  // namespace hil::controllers
