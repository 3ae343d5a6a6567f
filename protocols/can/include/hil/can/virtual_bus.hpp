// SPDX-License-Identifier: MIT
#pragma once
// In-process virtual CAN bus: any number of participants (VirtualChannel, a hil::can::Channel),
// deterministic delivery ordered on the injected clock, SocketCAN-like receive filters and
// loopback, bounded queues with counters, and fault injection (drop, delay, duplicate, reorder,
// corrupt, bus-off). CANopen masters and mock nodes run on it in one process.
//
// Executor contract (read this before using the bus):
//  * The bus and all its channels belong to ONE thread (or strand). Nothing here locks.
//  * send() never calls a receive handler. It stamps the frame with its send time
//    t_send = max(clock.now(), time of the frame being delivered, if called from a handler) and
//    queues it for delivery at t_due = t_send + latency (+ injected delay).
//  * deliver(now) hands every queued frame with t_due <= now to the receive handlers of all
//    other attached participants (and to the sender if it asked for loopback), in (t_due, send
//    order) order, passing t_due as the receive time. Frames sent by handlers during deliver()
//    whose t_due <= now are delivered in the same call (so a zero-latency SDO exchange completes
//    in one call); the number of frames per call is bounded (VirtualBusOptions) so two nodes
//    answering each other forever cannot hang the caller. A nested deliver() from a handler
//    returns 0 and does nothing.
//  * The receive order is identical for every participant and every run: the bus is
//    deterministic given the same sends at the same clock readings.
//  * run_until(clock, end) is the virtual-time driver: it advances a VirtualClock from event to
//    event, so handlers that read the clock see each frame's own delivery time.
//  * On real time (the socketcand hub) set_wakeup_handler() lets an Asio timer call deliver()
//    exactly when the next frame is due (see hil/can/io/bus_runner.hpp); there is no polling.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/can/channel.hpp"
#include "hil/can/filter.hpp"
#include "hil/can/frame.hpp"
#include "hil/core/clock.hpp"

namespace hil::can {

class VirtualChannel;

struct VirtualBusOptions {
  Duration latency{0};                             ///< send -> delivery delay for every frame
  std::size_t max_in_flight = 1u << 16;            ///< bus-wide bound on queued frames (no_buffer_space beyond)
  std::size_t max_deliveries_per_call = 1u << 20;  ///< frames one deliver() call may hand out
};

struct ParticipantOptions {
  bool receive_own = false;              ///< loopback of own frames (CAN_RAW_RECV_OWN_MSGS)
  FilterSet filters{};                   ///< CAN_RAW_FILTER / CAN_RAW_ERR_FILTER semantics
  std::size_t tx_queue_capacity = 4096;  ///< this participant's frames in flight (txqueuelen)
};

/// Bus-wide counters (per-participant ones are Channel::stats()).
struct VirtualBusStats {
  std::uint64_t sent = 0;                ///< frames accepted by send()
  std::uint64_t delivered = 0;           ///< frames taken off the queue (each fans out to N receivers)
  std::uint64_t receptions = 0;          ///< handler calls
  std::uint64_t filtered = 0;            ///< receptions suppressed by a receiver's filters
  std::uint64_t rejected_full = 0;       ///< send() refused: participant or bus queue full
  std::uint64_t rejected_bus_off = 0;    ///< send() refused: sender or bus in bus-off
  std::uint64_t lost_bus_off = 0;        ///< receptions lost because the receiver was bus-off
  std::uint64_t dropped = 0;             ///< fault: dropped
  std::uint64_t delayed = 0;             ///< fault: delayed
  std::uint64_t duplicated = 0;          ///< fault: extra copies queued
  std::uint64_t reordered = 0;           ///< fault: held behind the next frame
  std::uint64_t corrupted = 0;           ///< fault: payload/id altered
  std::uint64_t deliver_limit_hits = 0;  ///< deliver() calls that stopped at max_deliveries_per_call
};

enum class FaultAction : std::uint8_t {
  drop,       ///< the frame never reaches any receiver
  delay,      ///< delivered `delay` later than its due time
  duplicate,  ///< `copies` extra copies delivered right after it
  reorder,    ///< held back and delivered right after the next frame sent on the bus
  corrupt,    ///< `mutate` applied (default: byte 0 inverted, or id bit 0 for a frame without data)
};

/// One fault rule. A frame "matches" when `match` is empty or returns true. With nth == 0 every
/// matching frame is hit; with nth == n only the n-th matching frame after installation (1-based).
/// After `times` hits the rule expires.
struct FrameFault {
  FaultAction action = FaultAction::drop;
  std::function<bool(const Frame&)> match{};
  std::uint64_t nth = 0;
  std::uint64_t times = std::numeric_limits<std::uint64_t>::max();
  Duration delay{0};
  std::uint32_t copies = 1;
  std::function<void(Frame&)> mutate{};
};

class VirtualBus {
 public:
  /// `clock` stamps send times; it must outlive the bus. Thread: see the executor contract above.
  explicit VirtualBus(const Clock& clock, std::string name = "vbus", VirtualBusOptions options = {});
  ~VirtualBus();
  VirtualBus(const VirtualBus&) = delete;
  VirtualBus& operator=(const VirtualBus&) = delete;

  /// Attach a participant. The channel detaches itself when destroyed; a channel that outlives
  /// its bus returns network_down from send().
  [[nodiscard]] std::unique_ptr<VirtualChannel> attach(std::string participant_name, ParticipantOptions options = {});

  /// Deliver every frame due at or before `now` (see contract). Returns frames taken off the queue.
  std::size_t deliver(TimePoint now);
  /// Deliver exactly one frame if one is due at or before `now`. Returns whether it did.
  bool step(TimePoint now);
  /// Virtual-time driver: advance `clock` frame by frame up to `end`, delivering each frame at its
  /// due time, then leave the clock at `end`. Returns frames delivered.
  std::size_t run_until(VirtualClock& clock, TimePoint end);
  /// Due time of the earliest queued frame, if any.
  [[nodiscard]] std::optional<TimePoint> next_due() const noexcept;
  [[nodiscard]] std::size_t in_flight() const noexcept { return fifo_.size() + delayed_.size() + held_.size(); }

  /// Called whenever a queued frame makes the earliest due time earlier than announced before
  /// (from inside send()). Used by real-time runners to arm a timer. Must not call send().
  void set_wakeup_handler(std::function<void(TimePoint)> handler) { wakeup_ = std::move(handler); }

  /// Fault injection. Returns an id for remove_fault()/fault_hits().
  std::size_t inject(FrameFault fault);
  void remove_fault(std::size_t id) noexcept;
  void clear_faults() noexcept;
  [[nodiscard]] std::uint64_t fault_hits(std::size_t id) const noexcept;

  /// Whole-bus bus-off: every send() returns network_down, queued frames are lost at delivery.
  /// Participants whose error mask has error_class::bus_off get an error frame on entry and one
  /// with error_class::restarted on recovery.
  void set_bus_off(bool off);
  [[nodiscard]] bool bus_off() const noexcept { return bus_off_; }
  /// Queue an error frame (e.g. make_error_frame(error_class::controller, ...)) for every
  /// participant whose error mask selects its class.
  void inject_error_frame(const Frame& error_frame);

  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  [[nodiscard]] const VirtualBusOptions& options() const noexcept { return options_; }
  [[nodiscard]] const VirtualBusStats& stats() const noexcept { return stats_; }
  [[nodiscard]] std::size_t participant_count() const noexcept;
  void set_latency(Duration latency) noexcept { options_.latency = latency; }

 private:
  friend class VirtualChannel;
  static constexpr std::uint32_t broadcast = std::numeric_limits<std::uint32_t>::max();
  struct Pending {
    TimePoint due;
    std::uint64_t seq;
    Frame frame;
    std::uint32_t sender;  ///< participant index, or broadcast for bus-generated frames
    std::uint32_t target;  ///< one receiver, or broadcast
  };
  struct Later {
    bool operator()(const Pending& a, const Pending& b) const noexcept {
      return a.due != b.due ? a.due > b.due : a.seq > b.seq;
    }
  };
  struct FaultSlot {
    FrameFault fault;
    std::uint64_t matched = 0;
    std::uint64_t hits = 0;
    bool active = true;
  };

  std::error_code send_from(VirtualChannel& ch, const Frame& frame);
  void enqueue(Pending p);
  void push_queue(Pending p);
  void detach(VirtualChannel& ch) noexcept;
  void notify_channel_bus_off(VirtualChannel& ch, bool off);
  [[nodiscard]] TimePoint send_time() const noexcept;
  bool pop_due(TimePoint now, Pending& out);
  void fan_out(const Pending& p);

  const Clock& clock_;
  std::string name_;
  VirtualBusOptions options_;
  std::vector<VirtualChannel*> participants_;  ///< index = participant id; nullptr once detached
  std::deque<Pending> fifo_;                   ///< due times non-decreasing
  std::vector<Pending> delayed_;               ///< min-heap on (due, seq)
  std::vector<Pending> held_;                  ///< reorder: waiting for the next frame
  std::vector<FaultSlot> faults_;
  std::function<void(TimePoint)> wakeup_;
  std::optional<TimePoint> announced_;
  std::uint64_t seq_ = 0;
  bool delivering_ = false;
  TimePoint delivering_at_{};
  bool bus_off_ = false;
  VirtualBusStats stats_;
};

/// One participant of a VirtualBus. Thread: the bus's thread.
class VirtualChannel final : public Channel {
 public:
  ~VirtualChannel() override;
  VirtualChannel(const VirtualChannel&) = delete;
  VirtualChannel& operator=(const VirtualChannel&) = delete;

  [[nodiscard]] std::string_view name() const noexcept override { return name_; }
  /// Queue a frame (see the bus contract). Errors: invalid_argument (dlc > 8 or id out of range),
  /// no_buffer_space (tx queue or bus queue full; counted in tx_dropped), network_down (bus-off).
  std::error_code send(const Frame& frame) override;
  /// Runs inside VirtualBus::deliver() on the bus's thread. May call send() on any channel. Must
  /// not replace its own channel's handler while it runs.
  void set_receive_handler(ReceiveHandler handler) override { handler_ = std::move(handler); }
  [[nodiscard]] ChannelStats stats() const noexcept override;

  void set_filters(FilterSet filters);
  [[nodiscard]] const FilterSet& filters() const noexcept { return options_.filters; }
  void set_receive_own(bool on) noexcept { options_.receive_own = on; }
  /// Put this participant into (or out of) bus-off: it neither sends (network_down) nor receives.
  void set_bus_off(bool off);
  [[nodiscard]] bool bus_off() const noexcept { return bus_off_; }
  /// Frames of this participant queued on the bus.
  [[nodiscard]] std::size_t in_flight() const noexcept { return in_flight_; }
  [[nodiscard]] VirtualBus* bus() const noexcept { return bus_; }

 private:
  friend class VirtualBus;
  VirtualChannel(VirtualBus& bus, std::uint32_t index, std::string name, ParticipantOptions options);

  VirtualBus* bus_;
  std::uint32_t index_;
  std::string name_;
  ParticipantOptions options_;
  bool accept_all_ = true;  ///< fast path: default filters
  bool bus_off_ = false;
  std::size_t in_flight_ = 0;
  ReceiveHandler handler_;
  ChannelStats stats_;
};

}  // namespace hil::can
