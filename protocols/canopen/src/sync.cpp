// SPDX-License-Identifier: MIT
#include "hil/canopen/sync.hpp"

namespace hil::canopen {

can::Frame make_sync(std::optional<std::uint8_t> counter) noexcept {
  if (counter) return frame_of(cob_sync, {*counter});
  return frame_of(cob_sync, std::span<const std::uint8_t>{});
}

std::optional<SyncMessage> parse_sync(const can::Frame& f, std::uint32_t cob_id) noexcept {
  if (f.id != (cob_id & 0x7FF) || f.extended || f.rtr || f.error || f.dlc > 1) return std::nullopt;
  if (f.dlc == 0) return SyncMessage{};
  if (f.data[0] == 0 || f.data[0] > 240) return std::nullopt;
  return SyncMessage{f.data[0]};
}

void SyncProducer::configure(Duration period, std::uint8_t overflow, TimePoint start) noexcept {
  period_ = period;
  overflow_ = (overflow >= 2 && overflow <= 240) ? overflow : 0;
  counter_ = 0;
  next_ = start;
}

bool SyncProducer::step(TimePoint now) {
  if (period_ <= Duration::zero() || now < next_) return false;
  next_ += period_;
  if (next_ <= now) next_ = now + period_ - ((now - next_) % period_);
  if (overflow_ != 0) {
    counter_ = static_cast<std::uint8_t>(counter_ >= overflow_ ? 1 : counter_ + 1);
    sink_(make_sync(counter_));
  } else {
    sink_(make_sync());
  }
  return true;
}

}  // namespace hil::canopen
