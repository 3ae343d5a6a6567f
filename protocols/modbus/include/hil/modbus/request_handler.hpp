// SPDX-License-Identifier: MIT
#pragma once
// The server's request processing as a pure function: one request ADU in, one response ADU out,
// against a RegisterTable. No sockets, clocks or allocation. Supported: FC 3, 4, 6, 16, 22, 23;
// anything else answers exception 01. Check order follows libmodbus and the spec's state
// diagrams (MB spec §6): PDU length and quantity/byte-count errors give 03 before address errors
// give 02; FC 23 writes before it reads (MB spec §6.17).

#include <cstddef>
#include <cstdint>
#include <span>

#include "hil/modbus/adu.hpp"
#include "hil/modbus/error.hpp"
#include "hil/modbus/register_table.hpp"

namespace hil::modbus {

struct HandlerOptions {
  std::uint8_t unit_id = 1;
  /// false (default, like libmodbus' TCP server): answer any unit id. true: answer only
  /// `unit_id`, 0 and 0xFF; other units get exception 0B (gateway target failed to respond).
  bool strict_unit = false;
};

struct HandleResult {
  std::size_t size = 0;          ///< response ADU bytes in `out`; 0 = no response (malformed ADU)
  std::uint8_t function = 0;     ///< request function code (0 when the ADU was malformed)
  ModbusError error = ModbusError::none;  ///< exception sent, or invalid_request for a bad ADU
  std::uint16_t written_first = 0;        ///< holding registers written by this request
  std::uint16_t written_count = 0;
};

/// Process one complete request ADU (as delimited by check_frame()). `out` must hold
/// kMaxAduSize bytes. A malformed ADU (size disagrees with the MBAP length, protocol id != 0)
/// produces no response and `error == invalid_request`; the caller closes the connection.
HandleResult handle_request(std::span<const std::uint8_t> adu, RegisterTable& table, std::span<std::uint8_t> out,
                            const HandlerOptions& options) noexcept;

}  // namespace hil::modbus
