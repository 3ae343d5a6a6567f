// SPDX-License-Identifier: MIT
#pragma once
// The bus behind a Modbus I/O link: polls a digital I/O terminal's coils and discrete inputs
// (FC 1 / FC 2) and writes its coils (FC 5 / FC 15) following two BitPlans. Backends:
// SimModbusIoBus (the in-process simulated terminal, synchronous, on the cycle's time) and
// TcpModbusIoBus (libmodbus on a worker thread, for a real terminal).
//
// Thread: fetch() and put() are called on the cycle thread; they never block on the network,
// never throw and never allocate (a backend with a worker exchanges small buffers under a lock
// held only for a copy).

#include <cstdint>
#include <span>
#include <string>

#include "hil/core/clock.hpp"
#include "hil/modbus/bit_plan.hpp"
#include "hil/modbus/error.hpp"

namespace hil::controllers {

/// The state of the link to the terminal, as of a fetch().
struct ModbusIoStatus {
  std::uint64_t polls = 0;   ///< answered polls so far (0: no valid input yet)
  std::uint64_t errors = 0;  ///< failed polls, writes and connects so far
  /// The newest attempt's error; `none` once a poll is answered again.
  modbus::ModbusError error = modbus::ModbusError::none;
  /// How old the inputs are: since the start of the last answered poll (before the first one:
  /// since the bus started), on the backend's clock.
  Duration age{};
  bool connected = false;
};

class ModbusIoBus {
 public:
  virtual ~ModbusIoBus() = default;
  /// Copy the newest input values (one byte 0/1 per bit of the read plan's blocks, flattened;
  /// `inputs.size()` == read plan bits) and the link status. `now` = the cycle time.
  virtual void fetch(TimePoint now, std::span<std::uint8_t> inputs, ModbusIoStatus& status) noexcept = 0;
  /// The coil values wanted (one byte 0/1 per bit of the write plan's blocks, flattened). A
  /// backend writes the blocks that changed since they were last written (all of them after a
  /// reconnect: the terminal may have cleared its outputs).
  virtual void put(TimePoint now, std::span<const std::uint8_t> outputs) noexcept = 0;
  /// "simulated terminal" / "tcp://192.168.0.30:502 unit 1", for messages.
  [[nodiscard]] virtual const std::string& describe() const noexcept = 0;
};

}  // namespace hil::controllers
