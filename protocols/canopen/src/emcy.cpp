// SPDX-License-Identifier: MIT
#include "hil/canopen/emcy.hpp"

namespace hil::canopen {

can::Frame make_emcy(const EmcyMessage& m) noexcept {
  can::Frame f;
  f.id = cob_emcy_base + m.node;
  f.dlc = 8;
  put_le16(&f.data[0], m.code);
  f.data[2] = m.error_register;
  for (std::size_t i = 0; i < 5; ++i) f.data[3 + i] = m.manufacturer[i];
  return f;
}

std::optional<EmcyMessage> parse_emcy(const can::Frame& f) noexcept {
  if (f.extended || f.rtr || f.error || f.dlc != 8) return std::nullopt;
  if (f.id <= cob_emcy_base || f.id > cob_emcy_base + 127) return std::nullopt;
  EmcyMessage m;
  m.node = static_cast<NodeId>(f.id - cob_emcy_base);
  m.code = get_le16(&f.data[0]);
  m.error_register = f.data[2];
  for (std::size_t i = 0; i < 5; ++i) m.manufacturer[i] = f.data[3 + i];
  return m;
}

void EmcyProducer::raise(std::uint16_t code, std::uint8_t reg, std::array<std::uint8_t, 5> mfr, TimePoint now) {
  if (queue_.size() >= 16) return;  // bounded; the error register still carries the state
  queue_.push_back(EmcyMessage{node_, code, reg, mfr});
  step(now);
}

void EmcyProducer::step(TimePoint now) {
  while (!queue_.empty()) {
    if (last_ && now - *last_ < inhibit_) return;
    if (!muted_) sink_(make_emcy(queue_.front()));
    queue_.pop_front();
    last_ = now;
    if (inhibit_ > Duration::zero()) return;
  }
}

}  // namespace hil::canopen
