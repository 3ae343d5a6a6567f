// SPDX-License-Identifier: MIT
#pragma once
// One CANopen master on one CAN channel, shared by every CiA 402 axis on that bus. Binds the
// master to a hil::can::Channel (frames in through the channel's receive handler, out through
// send()) and routes the master's events (boot, EMCY, heartbeat) to the axes by node-ID.
// Thread: the channel's executor (for the virtual bus: the motion thread).

#include <functional>
#include <map>
#include <memory>

#include "hil/can/channel.hpp"
#include "hil/canopen/master.hpp"

namespace hil::cia402 {

class Cia402Drive;

struct NetworkStats {
  std::uint64_t tx_errors = 0;  ///< send() refused (queue full, bus-off)
  std::error_code last_tx_error;
};

class Network {
 public:
  /// `channel` must outlive the network.
  Network(can::Channel& channel, canopen::MasterOptions options);
  ~Network();
  Network(const Network&) = delete;
  Network& operator=(const Network&) = delete;

  [[nodiscard]] canopen::Master& master() noexcept { return master_; }
  [[nodiscard]] can::Channel& channel() noexcept { return channel_; }
  /// Start the master (SYNC, heartbeat) and boot every node added so far.
  void start(TimePoint now);
  /// SYNC, timeouts, boot progress. Call once per cycle (and more often if you like).
  void step(TimePoint now) { master_.step(now); }
  [[nodiscard]] const NetworkStats& stats() const noexcept { return stats_; }

  /// Axis registration (done by Cia402Drive itself).
  void attach(canopen::NodeId node, Cia402Drive* drive) { drives_[node] = drive; }
  void detach(canopen::NodeId node) noexcept { drives_.erase(node); }

 private:
  can::Channel& channel_;
  canopen::Master master_;
  std::map<canopen::NodeId, Cia402Drive*> drives_;
  NetworkStats stats_;
};

}  // namespace hil::cia402
