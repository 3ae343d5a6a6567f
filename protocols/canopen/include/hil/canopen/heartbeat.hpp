// SPDX-License-Identifier: MIT
#pragma once
// Heartbeat producer and consumer, and the master side of node guarding (CiA 301 §7.2.8.3.2).
// Step functions on injected time: nothing here reads a clock.

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "hil/can/frame.hpp"
#include "hil/canopen/cob_id.hpp"
#include "hil/canopen/nmt.hpp"
#include "hil/core/clock.hpp"

namespace hil::canopen {

/// Produces `7xx#<state>` every producer time (object 0x1017, ms; 0 = off).
class HeartbeatProducer {
 public:
  HeartbeatProducer(NodeId node, FrameSink sink) : node_(node), sink_(std::move(sink)) {}
  /// Change the period (0 disables). The next heartbeat is due one period after `now`.
  void set_period(Duration period, TimePoint now) noexcept;
  [[nodiscard]] Duration period() const noexcept { return period_; }
  /// Emit a heartbeat with `state` if one is due. Call at least once per period.
  void step(TimePoint now, NmtState state);
  /// Suppress output (fault injection: heartbeat loss) without changing the period.
  void set_muted(bool muted) noexcept { muted_ = muted; }

 private:
  NodeId node_;
  FrameSink sink_;
  Duration period_{};
  TimePoint next_{};
  bool muted_ = false;
};

enum class HeartbeatEvent : std::uint8_t {
  boot_up,        ///< `7xx#00` received
  state_changed,  ///< first heartbeat, or a heartbeat with a different state
  timeout,        ///< no heartbeat within the consumer time (reported once per loss)
  resumed,        ///< heartbeat received again after a timeout
};

/// Heartbeat consumer (object 0x1016). Monitoring of a node starts with its first heartbeat
/// (a node that never sent one never times out, CiA 301 §7.2.8.3.2.3).
class HeartbeatConsumer {
 public:
  using Handler = std::function<void(NodeId, HeartbeatEvent, NmtState)>;
  explicit HeartbeatConsumer(Handler handler) : handler_(std::move(handler)) {}

  /// Monitor `node` with consumer time `timeout` (0 removes it). Same encoding as 0x1016:n.
  void set_consumer(NodeId node, Duration timeout);
  /// 0x1016 sub-entry: (node << 16) | time_ms.
  void set_consumer_entry(std::uint32_t entry) {
    set_consumer(static_cast<NodeId>((entry >> 16) & 0x7F), std::chrono::milliseconds(entry & 0xFFFF));
  }
  /// Feed every received frame; returns true if it was a heartbeat of a monitored node.
  bool on_frame(const can::Frame& f, TimePoint now);
  /// Report timeouts that expired at or before `now`.
  void step(TimePoint now);
  /// Last state seen (nullopt if never seen).
  [[nodiscard]] std::optional<NmtState> state(NodeId node) const noexcept;
  [[nodiscard]] bool timed_out(NodeId node) const noexcept;
  /// Forget the first-heartbeat latch (e.g. after an NMT reset of that node).
  void rearm(NodeId node) noexcept;

 private:
  struct Entry {
    NodeId node;
    Duration timeout;
    TimePoint last{};
    std::optional<NmtState> state;
    bool active = false;
    bool timed_out = false;
  };
  Entry* find(NodeId node) noexcept;
  const Entry* find(NodeId node) const noexcept;
  Handler handler_;
  std::vector<Entry> entries_;
};

/// Master side of node guarding: an RTR every guard time (0x100C), a missing or untoggled
/// answer for life-time factor (0x100D) x guard time raises `lost`. Legacy drives only:
/// heartbeat is preferred.
class NodeGuardMaster {
 public:
  enum class Event : std::uint8_t { lost, toggle_error, state, resumed };
  using Handler = std::function<void(NodeId, Event, NmtState)>;
  NodeGuardMaster(FrameSink sink, Handler handler) : sink_(std::move(sink)), handler_(std::move(handler)) {}
  void guard(NodeId node, Duration guard_time, std::uint8_t life_time_factor, TimePoint now);
  bool on_frame(const can::Frame& f, TimePoint now);
  void step(TimePoint now);

 private:
  struct Entry {
    NodeId node;
    Duration guard_time;
    std::uint8_t factor;
    TimePoint next_request{};
    TimePoint last_answer{};
    bool expect_toggle = false;
    bool first = true;
    bool lost = false;
    std::optional<NmtState> state;
  };
  FrameSink sink_;
  Handler handler_;
  std::vector<Entry> entries_;
};

}  // namespace hil::canopen
