// SPDX-License-Identifier: MIT
#pragma once
// A CANopen slave node (CiA 301): NMT slave state machine with boot-up, heartbeat producer
// (0x1017), node-guarding responder, SDO server, PDOs, EMCY producer (0x1014/0x1015) and SYNC
// consumer (0x1005), all over one ObjectDictionary. Step function on injected time; the
// application (a device profile such as CiA 402) hooks in through the callbacks.
// Thread: one owner; callbacks run synchronously inside on_frame()/step().

#include <functional>
#include <optional>

#include "hil/canopen/emcy.hpp"
#include "hil/canopen/heartbeat.hpp"
#include "hil/canopen/nmt.hpp"
#include "hil/canopen/object_dictionary.hpp"
#include "hil/canopen/pdo.hpp"
#include "hil/canopen/sdo_server.hpp"
#include "hil/canopen/sync.hpp"

namespace hil::canopen {

class Slave {
 public:
  /// `od` is copied as the power-on defaults for NMT reset node / reset communication.
  Slave(ObjectDictionary od, NodeId node, FrameSink sink, SdoServerOptions sdo = {});
  Slave(const Slave&) = delete;
  Slave& operator=(const Slave&) = delete;

  /// Power on: initialise, send the boot-up message, enter pre-operational.
  void start(TimePoint now);
  bool on_frame(const can::Frame& f, TimePoint now);
  void step(TimePoint now);

  [[nodiscard]] NmtState state() const noexcept { return state_; }
  [[nodiscard]] NodeId node_id() const noexcept { return node_; }
  [[nodiscard]] ObjectDictionary& od() noexcept { return od_; }
  [[nodiscard]] const ObjectDictionary& od() const noexcept { return od_; }
  [[nodiscard]] PdoEngine& pdo() noexcept { return pdo_; }
  [[nodiscard]] SdoServer& sdo() noexcept { return sdo_; }

  /// Raise an EMCY (also sets 0x1001 and the 0x1003 history when present). code 0 = reset.
  void raise_emcy(std::uint16_t code, std::uint8_t error_register, std::array<std::uint8_t, 5> mfr, TimePoint now);

  /// Application hooks.
  std::function<void(std::optional<std::uint8_t> counter, TimePoint now)> on_sync;
  std::function<void(NmtState state)> on_state;
  std::function<void(bool application)> on_reset;  ///< true: reset node, false: reset communication
  /// Heartbeat consumer (0x1016) events about the monitored nodes (usually the master). On a
  /// timeout the slave has already raised EMCY 0x8130.
  std::function<void(NodeId node, HeartbeatEvent event, TimePoint now)> on_heartbeat;

  /// Fault injection: stop heartbeats / guarding answers (the node keeps running).
  void set_heartbeat_muted(bool m) noexcept {
    hb_muted_ = m;
    heartbeat_.set_muted(m);
  }

 private:
  void enter(NmtState s);
  void reset(bool application, TimePoint now);
  void apply_comm_parameters(TimePoint now);

  ObjectDictionary defaults_;
  ObjectDictionary od_;
  NodeId node_;
  FrameSink sink_;
  SdoServer sdo_;
  PdoEngine pdo_;
  HeartbeatProducer heartbeat_;
  EmcyProducer emcy_;
  HeartbeatConsumer consumer_;
  NmtState state_ = NmtState::initialising;
  std::uint32_t sync_cob_ = cob_sync;
  bool guard_toggle_ = false;
  bool hb_muted_ = false;
  bool comm_dirty_ = false;
  TimePoint last_now_{};
};

}  // namespace hil::canopen
