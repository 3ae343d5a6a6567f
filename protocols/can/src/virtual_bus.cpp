// SPDX-License-Identifier: MIT
#include "hil/can/virtual_bus.hpp"

#include <algorithm>
#include <utility>

namespace hil::can {

namespace {
void default_corruption(Frame& f) noexcept {
  if (f.dlc > 0 && !f.rtr)
    f.data[0] = static_cast<std::uint8_t>(~f.data[0]);
  else
    f.id ^= 1u;
}
bool is_default_filter(const FilterSet& fs) noexcept {
  return !fs.join && fs.filters.size() == 1 && fs.filters.front().mask == 0 && !fs.filters.front().inverted;
}
}  // namespace

// ---------------------------------------------------------------------------------------------
// VirtualBus

VirtualBus::VirtualBus(const Clock& clock, std::string name, VirtualBusOptions options)
    : clock_(clock), name_(std::move(name)), options_(options) {}

VirtualBus::~VirtualBus() {
  for (auto* p : participants_)
    if (p != nullptr) p->bus_ = nullptr;
}

std::unique_ptr<VirtualChannel> VirtualBus::attach(std::string participant_name, ParticipantOptions options) {
  // Indices are referenced by queued frames; compact tombstones only while nothing is queued.
  if (!delivering_ && in_flight() == 0) {
    std::erase(participants_, nullptr);
    for (std::size_t i = 0; i < participants_.size(); ++i) participants_[i]->index_ = static_cast<std::uint32_t>(i);
  }
  const auto index = static_cast<std::uint32_t>(participants_.size());
  std::unique_ptr<VirtualChannel> ch(new VirtualChannel(*this, index, std::move(participant_name), std::move(options)));
  participants_.push_back(ch.get());
  return ch;
}

std::size_t VirtualBus::participant_count() const noexcept {
  return static_cast<std::size_t>(
      std::count_if(participants_.begin(), participants_.end(), [](const VirtualChannel* p) { return p != nullptr; }));
}

void VirtualBus::detach(VirtualChannel& ch) noexcept {
  if (ch.index_ < participants_.size() && participants_[ch.index_] == &ch) participants_[ch.index_] = nullptr;
}

TimePoint VirtualBus::send_time() const noexcept {
  const TimePoint now = clock_.now();
  return delivering_ && delivering_at_ > now ? delivering_at_ : now;
}

std::optional<TimePoint> VirtualBus::next_due() const noexcept {
  std::optional<TimePoint> due;
  if (!fifo_.empty()) due = fifo_.front().due;
  if (!delayed_.empty() && (!due || delayed_.front().due < *due)) due = delayed_.front().due;
  return due;
}

void VirtualBus::push_queue(Pending p) {
  if (p.sender != broadcast && p.sender < participants_.size() && participants_[p.sender] != nullptr)
    ++participants_[p.sender]->in_flight_;
  if (fifo_.empty() || fifo_.back().due <= p.due) {
    fifo_.push_back(p);
  } else {
    delayed_.push_back(p);
    std::push_heap(delayed_.begin(), delayed_.end(), Later{});
  }
  if (!delivering_ && wakeup_ && (!announced_ || p.due < *announced_)) {
    announced_ = p.due;
    wakeup_(p.due);
  }
}

void VirtualBus::enqueue(Pending p) {
  // A frame held for reordering goes right behind the next frame sent on the bus.
  std::vector<Pending> release;
  release.swap(held_);
  push_queue(p);
  for (auto& h : release) {
    h.due = std::max(h.due, p.due);
    h.seq = ++seq_;
    if (h.sender != broadcast && h.sender < participants_.size() && participants_[h.sender] != nullptr)
      --participants_[h.sender]->in_flight_;  // re-counted by push_queue
    push_queue(h);
  }
}

std::error_code VirtualBus::send_from(VirtualChannel& ch, const Frame& frame) {
  if (!is_valid(frame)) return std::make_error_code(std::errc::invalid_argument);
  if (bus_off_ || ch.bus_off_) {
    ++stats_.rejected_bus_off;
    return std::make_error_code(std::errc::network_down);
  }
  if (ch.in_flight_ >= ch.options_.tx_queue_capacity || in_flight() >= options_.max_in_flight) {
    ++stats_.rejected_full;
    ++ch.stats_.tx_dropped;
    return std::make_error_code(std::errc::no_buffer_space);
  }
  ++stats_.sent;
  ++ch.stats_.tx_frames;

  Pending p{send_time() + options_.latency, ++seq_, frame, ch.index_, broadcast};
  bool drop = false;
  bool hold = false;
  std::uint32_t copies = 0;
  for (auto& slot : faults_) {
    if (!slot.active) continue;
    if (slot.fault.match && !slot.fault.match(p.frame)) continue;
    ++slot.matched;
    if (slot.fault.nth != 0 && slot.matched != slot.fault.nth) continue;
    ++slot.hits;
    if (slot.hits >= slot.fault.times || slot.fault.nth != 0) slot.active = false;
    switch (slot.fault.action) {
      case FaultAction::drop:
        drop = true;
        break;
      case FaultAction::delay:
        p.due += slot.fault.delay;
        ++stats_.delayed;
        break;
      case FaultAction::duplicate:
        copies += slot.fault.copies;
        break;
      case FaultAction::reorder:
        hold = true;
        break;
      case FaultAction::corrupt:
        if (slot.fault.mutate)
          slot.fault.mutate(p.frame);
        else
          default_corruption(p.frame);
        ++stats_.corrupted;
        break;
    }
  }
  if (drop) {
    ++stats_.dropped;
    return {};
  }
  if (hold) {
    ++stats_.reordered;
    if (ch.index_ < participants_.size()) ++ch.in_flight_;
    held_.push_back(p);
  } else {
    enqueue(p);
  }
  for (std::uint32_t i = 0; i < copies; ++i) {
    ++stats_.duplicated;
    Pending c = p;
    c.seq = ++seq_;
    if (hold) {
      held_.push_back(c);
      ++ch.in_flight_;
    } else {
      push_queue(c);
    }
  }
  return {};
}

bool VirtualBus::pop_due(TimePoint now, Pending& out) {
  const bool fifo_ok = !fifo_.empty() && fifo_.front().due <= now;
  const bool heap_ok = !delayed_.empty() && delayed_.front().due <= now;
  if (!fifo_ok && !heap_ok) return false;
  if (fifo_ok && (!heap_ok || !Later{}(fifo_.front(), delayed_.front()))) {
    out = fifo_.front();
    fifo_.pop_front();
  } else {
    std::pop_heap(delayed_.begin(), delayed_.end(), Later{});
    out = delayed_.back();
    delayed_.pop_back();
  }
  if (out.sender != broadcast && out.sender < participants_.size() && participants_[out.sender] != nullptr)
    --participants_[out.sender]->in_flight_;
  return true;
}

void VirtualBus::fan_out(const Pending& p) {
  ++stats_.delivered;
  const std::size_t n = participants_.size();  // joiners during this frame do not see it
  for (std::size_t i = 0; i < n; ++i) {
    VirtualChannel* rx = participants_[i];
    if (rx == nullptr) continue;
    if (p.target != broadcast && p.target != i) continue;
    if (i == p.sender && !rx->options_.receive_own) continue;
    if (bus_off_ || rx->bus_off_) {
      if (p.target == broadcast) ++stats_.lost_bus_off;
      // The bus-off notification itself still reaches its target.
      if (!(p.frame.error && p.target == i)) continue;
    }
    if (!(rx->accept_all_ && !p.frame.error) && !rx->options_.filters.accepts(p.frame)) {
      ++stats_.filtered;
      continue;
    }
    ++rx->stats_.rx_frames;
    if (p.frame.error) ++rx->stats_.error_frames;
    if (!rx->handler_) continue;
    ++stats_.receptions;
    rx->handler_(p.frame, p.due);
  }
}

std::size_t VirtualBus::deliver(TimePoint now) {
  if (delivering_) return 0;
  delivering_ = true;
  std::size_t count = 0;
  Pending p;
  while (count < options_.max_deliveries_per_call && pop_due(now, p)) {
    delivering_at_ = p.due;
    fan_out(p);
    ++count;
  }
  if (count == options_.max_deliveries_per_call && next_due() && *next_due() <= now) ++stats_.deliver_limit_hits;
  delivering_ = false;
  announced_.reset();
  if (wakeup_) {
    if (auto due = next_due()) {
      announced_ = due;
      wakeup_(*due);
    }
  }
  return count;
}

bool VirtualBus::step(TimePoint now) {
  if (delivering_) return false;
  const auto saved = options_.max_deliveries_per_call;
  options_.max_deliveries_per_call = 1;
  const bool did = deliver(now) == 1;
  options_.max_deliveries_per_call = saved;
  return did;
}

std::size_t VirtualBus::run_until(VirtualClock& clock, TimePoint end) {
  std::size_t count = 0;
  while (auto due = next_due()) {
    if (*due > end) break;
    clock.advance_to(*due);
    const std::size_t n = deliver(*due);
    count += n;
    if (n == 0) break;  // nested call from a handler
  }
  clock.advance_to(end);
  return count;
}

std::size_t VirtualBus::inject(FrameFault fault) {
  faults_.push_back(FaultSlot{std::move(fault)});
  return faults_.size() - 1;
}
void VirtualBus::remove_fault(std::size_t id) noexcept {
  if (id < faults_.size()) faults_[id].active = false;
}
void VirtualBus::clear_faults() noexcept {
  for (auto& f : faults_) f.active = false;
}
std::uint64_t VirtualBus::fault_hits(std::size_t id) const noexcept {
  return id < faults_.size() ? faults_[id].hits : 0;
}

void VirtualBus::notify_channel_bus_off(VirtualChannel& ch, bool off) {
  const std::uint32_t cls = off ? error_class::bus_off : error_class::restarted;
  if ((ch.options_.filters.error_mask & cls) == 0) return;
  push_queue(Pending{send_time() + options_.latency, ++seq_, make_error_frame(cls), broadcast, ch.index_});
}

void VirtualBus::set_bus_off(bool off) {
  if (off == bus_off_) return;
  bus_off_ = off;
  for (auto* p : participants_)
    if (p != nullptr && !p->bus_off_) notify_channel_bus_off(*p, off);
}

void VirtualBus::inject_error_frame(const Frame& error_frame) {
  Frame f = error_frame;
  f.error = true;
  push_queue(Pending{send_time() + options_.latency, ++seq_, f, broadcast, broadcast});
}

// ---------------------------------------------------------------------------------------------
// VirtualChannel

VirtualChannel::VirtualChannel(VirtualBus& bus, std::uint32_t index, std::string name, ParticipantOptions options)
    : bus_(&bus),
      index_(index),
      name_(std::move(name)),
      options_(std::move(options)),
      accept_all_(is_default_filter(options_.filters)) {}

VirtualChannel::~VirtualChannel() {
  if (bus_ != nullptr) bus_->detach(*this);
}

std::error_code VirtualChannel::send(const Frame& frame) {
  if (bus_ == nullptr) return std::make_error_code(std::errc::network_down);
  return bus_->send_from(*this, frame);
}

ChannelStats VirtualChannel::stats() const noexcept {
  ChannelStats s = stats_;
  s.bus_off = bus_off_ || (bus_ != nullptr && bus_->bus_off());
  return s;
}

void VirtualChannel::set_filters(FilterSet filters) {
  options_.filters = std::move(filters);
  accept_all_ = is_default_filter(options_.filters);
}

void VirtualChannel::set_bus_off(bool off) {
  if (off == bus_off_) return;
  bus_off_ = off;
  if (bus_ != nullptr && !bus_->bus_off_) bus_->notify_channel_bus_off(*this, off);
}

}  // namespace hil::can
