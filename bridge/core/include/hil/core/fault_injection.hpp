// SPDX-License-Identifier: MIT
#pragma once
// Optional interface for drives whose far end is a mock (the simulated plant, an in-process
// simulated CiA 402 node, an in-process Modbus drive server, mock GPIO lines). Scenarios and tests
// reach it with dynamic_cast<FaultInjectable*>(&drive); real transports do not implement it.

#include <string>
#include <string_view>
#include <vector>

namespace hil {

class FaultInjectable {
 public:
  virtual ~FaultInjectable() = default;
  /// Names this drive accepts ("encoder", "not_ready", "following_blowup", "heartbeat_loss", ...).
  [[nodiscard]] virtual std::vector<std::string> injectable_faults() const = 0;
  /// Start (`active`) or stop a fault. Returns false for an unknown name.
  virtual bool inject_fault(std::string_view name, bool active) = 0;
};

}  // namespace hil
