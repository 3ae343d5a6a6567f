// SPDX-License-Identifier: MIT
#include "hil/canopen/heartbeat.hpp"

#include <algorithm>

namespace hil::canopen {

void HeartbeatProducer::set_period(Duration period, TimePoint now) noexcept {
  period_ = period;
  next_ = now + period;
}

void HeartbeatProducer::step(TimePoint now, NmtState state) {
  if (period_ <= Duration::zero() || now < next_) return;
  // Catch up without bursting: one heartbeat per step, schedule from the due time.
  next_ += period_;
  if (next_ <= now) next_ = now + period_;
  if (!muted_) sink_(make_heartbeat(node_, state));
}

HeartbeatConsumer::Entry* HeartbeatConsumer::find(NodeId node) noexcept {
  for (auto& e : entries_)
    if (e.node == node) return &e;
  return nullptr;
}
const HeartbeatConsumer::Entry* HeartbeatConsumer::find(NodeId node) const noexcept {
  for (const auto& e : entries_)
    if (e.node == node) return &e;
  return nullptr;
}

void HeartbeatConsumer::set_consumer(NodeId node, Duration timeout) {
  if (timeout <= Duration::zero() || !is_valid_node_id(node)) {
    std::erase_if(entries_, [node](const Entry& e) { return e.node == node; });
    return;
  }
  if (auto* e = find(node)) {
    e->timeout = timeout;
    return;
  }
  Entry e{};
  e.node = node;
  e.timeout = timeout;
  entries_.push_back(e);
}

bool HeartbeatConsumer::on_frame(const can::Frame& f, TimePoint now) {
  const auto msg = parse_error_control(f);
  if (!msg) return false;
  auto* e = find(msg->node);
  if (e == nullptr) return false;
  const bool was_timed_out = e->timed_out;
  const auto previous = e->state;
  e->last = now;
  e->timed_out = false;
  if (msg->state == NmtState::initialising) {
    // Boot-up: monitoring restarts with the node's first heartbeat after it.
    e->active = false;
    e->state = msg->state;
    handler_(msg->node, HeartbeatEvent::boot_up, msg->state);
    return true;
  }
  e->active = true;
  e->state = msg->state;
  if (was_timed_out) handler_(msg->node, HeartbeatEvent::resumed, msg->state);
  if (previous != msg->state) handler_(msg->node, HeartbeatEvent::state_changed, msg->state);
  return true;
}

void HeartbeatConsumer::step(TimePoint now) {
  for (auto& e : entries_) {
    if (!e.active || e.timed_out) continue;
    if (now - e.last > e.timeout) {
      e.timed_out = true;
      handler_(e.node, HeartbeatEvent::timeout, e.state.value_or(NmtState::initialising));
    }
  }
}

std::optional<NmtState> HeartbeatConsumer::state(NodeId node) const noexcept {
  const auto* e = find(node);
  return e ? e->state : std::nullopt;
}

bool HeartbeatConsumer::timed_out(NodeId node) const noexcept {
  const auto* e = find(node);
  return e != nullptr && e->timed_out;
}

void HeartbeatConsumer::rearm(NodeId node) noexcept {
  if (auto* e = find(node)) {
    e->active = false;
    e->timed_out = false;
    e->state.reset();
  }
}

void NodeGuardMaster::guard(NodeId node, Duration guard_time, std::uint8_t life_time_factor, TimePoint now) {
  std::erase_if(entries_, [node](const Entry& e) { return e.node == node; });
  if (guard_time <= Duration::zero() || life_time_factor == 0) return;
  Entry e{};
  e.node = node;
  e.guard_time = guard_time;
  e.factor = life_time_factor;
  e.next_request = now;
  e.last_answer = now;
  entries_.push_back(e);
}

bool NodeGuardMaster::on_frame(const can::Frame& f, TimePoint now) {
  const auto msg = parse_error_control(f);
  if (!msg) return false;
  for (auto& e : entries_) {
    if (e.node != msg->node) continue;
    if (!e.first && msg->toggle != e.expect_toggle) {
      // CiA 301: a response with an unchanged toggle bit is treated as not received.
      handler_(e.node, Event::toggle_error, msg->state);
      return true;
    }
    e.first = false;
    e.expect_toggle = !msg->toggle;
    e.last_answer = now;
    if (e.lost) {
      e.lost = false;
      handler_(e.node, Event::resumed, msg->state);
    }
    if (e.state != msg->state) {
      e.state = msg->state;
      handler_(e.node, Event::state, msg->state);
    }
    return true;
  }
  return false;
}

void NodeGuardMaster::step(TimePoint now) {
  for (auto& e : entries_) {
    if (now >= e.next_request) {
      sink_(make_guard_request(e.node));
      e.next_request = now + e.guard_time;
    }
    if (!e.lost && now - e.last_answer > e.guard_time * e.factor) {
      e.lost = true;
      handler_(e.node, Event::lost, e.state.value_or(NmtState::initialising));
    }
  }
}

}  // namespace hil::canopen
