// SPDX-License-Identifier: MIT
#include "hil/canopen/slave.hpp"

namespace hil::canopen {

Slave::Slave(ObjectDictionary od, NodeId node, FrameSink sink, SdoServerOptions sdo)
    : defaults_(od),
      od_(std::move(od)),
      node_(node),
      sink_(std::move(sink)),
      sdo_(od_, node, sink_, sdo),
      pdo_(od_, sink_),
      heartbeat_(node, sink_),
      emcy_(node, sink_),
      consumer_([this](NodeId id, HeartbeatEvent e, NmtState) {
        if (e == HeartbeatEvent::timeout)
          raise_emcy(emcy_code::heartbeat, error_register::communication, {}, last_now_);
        if (on_heartbeat) on_heartbeat(id, e, last_now_);
      }) {
  for (const std::uint16_t idx : {std::uint16_t{0x1005}, std::uint16_t{0x1014}, std::uint16_t{0x1015},
                                  std::uint16_t{0x1016}, std::uint16_t{0x1017}})
    od_.add_observer(idx, [this](const Variable&) { comm_dirty_ = true; });
  pdo_.set_error_handler(
      [this](std::uint16_t code, std::uint32_t) { raise_emcy(code, error_register::communication, {}, last_now_); });
}

void Slave::enter(NmtState s) {
  if (s == state_) return;
  state_ = s;
  pdo_.set_active(s == NmtState::operational);
  if (on_state) on_state(s);
}

void Slave::apply_comm_parameters(TimePoint now) {
  comm_dirty_ = false;
  sync_cob_ = od_.find(0x1005, 0) ? static_cast<std::uint32_t>(od_.get_int(0x1005, 0)) & 0x7FF : cob_sync;
  heartbeat_.set_period(std::chrono::milliseconds(od_.get_int(0x1017, 0)), now);
  emcy_.set_inhibit(std::chrono::microseconds(100 * od_.get_int(0x1015, 0)));
  for (NodeId id = 1; id <= 127; ++id) consumer_.set_consumer(id, Duration::zero());
  for (std::uint8_t sub = 1; sub < 128 && od_.find(0x1016, sub) != nullptr; ++sub)
    consumer_.set_consumer_entry(static_cast<std::uint32_t>(od_.get_int(0x1016, sub)));
}

void Slave::start(TimePoint now) {
  last_now_ = now;
  state_ = NmtState::initialising;
  pdo_.load_from_od();
  pdo_.set_active(false);
  apply_comm_parameters(now);
  if (!hb_muted_) sink_(make_heartbeat(node_, NmtState::initialising));
  enter(NmtState::preoperational);
}

void Slave::reset(bool application, TimePoint now) {
  for (const auto& [key, def] : defaults_.variables()) {
    if (!application && (def.index < 0x1000 || def.index > 0x1FFF)) continue;
    if (auto* v = od_.find(def.index, def.sub)) v->value = def.value;
  }
  if (on_reset) on_reset(application);
  start(now);
}

void Slave::raise_emcy(std::uint16_t code, std::uint8_t reg, std::array<std::uint8_t, 5> mfr, TimePoint now) {
  if (od_.find(0x1001, 0)) od_.set_int(0x1001, 0, reg);
  if (code != 0 && od_.find(0x1003, 0)) {
    // Pre-defined error field: newest at sub 1; sub 0 = number of errors.
    const auto n = od_.get_int(0x1003, 0);
    std::int64_t max = 0;
    while (od_.find(0x1003, static_cast<std::uint8_t>(max + 1))) ++max;
    for (auto i = std::min<std::int64_t>(n + 1, max); i > 1; --i)
      od_.set_int(0x1003, static_cast<std::uint8_t>(i), od_.get_int(0x1003, static_cast<std::uint8_t>(i - 1)));
    if (max > 0) {
      od_.set_int(0x1003, 1, code);
      od_.set_int(0x1003, 0, std::min<std::int64_t>(n + 1, max));
    }
  }
  if (state_ == NmtState::stopped) return;  // EMCY is not sent in Stopped (CiA 301 table 84)
  emcy_.raise(code, reg, mfr, now);
}

bool Slave::on_frame(const can::Frame& f, TimePoint now) {
  last_now_ = now;
  if (auto nmt = parse_nmt(f)) {
    if (nmt->node != 0 && nmt->node != node_) return true;
    switch (nmt->command) {
      case NmtCommand::start:
        enter(NmtState::operational);
        break;
      case NmtCommand::stop:
        enter(NmtState::stopped);
        break;
      case NmtCommand::enter_preoperational:
        enter(NmtState::preoperational);
        break;
      case NmtCommand::reset_node:
        reset(true, now);
        break;
      case NmtCommand::reset_communication:
        reset(false, now);
        break;
    }
    return true;
  }
  if (consumer_.on_frame(f, now)) return true;
  if (f.rtr && f.id == cob_heartbeat_base + node_) {  // node guarding request
    if (!hb_muted_) {
      sink_(make_guard_response(node_, state_, guard_toggle_));
      guard_toggle_ = !guard_toggle_;
    }
    return true;
  }
  if (state_ == NmtState::stopped || state_ == NmtState::initialising) return false;
  if (auto s = parse_sync(f, sync_cob_)) {
    pdo_.apply_sync_rpdos(now);
    if (on_sync) on_sync(s->counter, now);
    pdo_.send_sync_tpdos(s->counter, now);
    return true;
  }
  if (sdo_.on_frame(f, now)) {
    if (comm_dirty_) apply_comm_parameters(now);
    return true;
  }
  return pdo_.on_frame(f, now);
}

void Slave::step(TimePoint now) {
  last_now_ = now;
  if (comm_dirty_) apply_comm_parameters(now);
  if (state_ == NmtState::initialising) return;
  heartbeat_.step(now, state_);
  consumer_.step(now);
  sdo_.step(now);
  emcy_.step(now);
  pdo_.step(now);
}

}  // namespace hil::canopen
