// SPDX-License-Identifier: MIT
#pragma once
// The server's request rules as a pure function (what may be served), ahead of libmodbus'
// modbus_reply() (which serves it). Supported: FC 1, 2, 5, 15 (when the device has coils /
// discrete inputs), 3, 4, 6, 16, 22, 23; anything else answers exception 01. Check order follows libmodbus and the
// spec's state diagrams (MB spec §6): PDU length and quantity/byte-count errors give 03 before address errors give 02.

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
  std::size_t size = 0;                   ///< response ADU bytes in `out`; 0 = no response (malformed ADU)
  std::uint8_t function = 0;              ///< request function code (0 when the ADU was malformed)
  ModbusError error = ModbusError::none;  ///< exception sent, or invalid_request for a bad ADU
  std::uint16_t written_first = 0;        ///< holding registers written by this request
  std::uint16_t written_count = 0;
  std::uint16_t coils_written_first = 0;  ///< coils written by this request (FC 5/15)
  std::uint16_t coils_written_count = 0;
};

/// What a request asks for, and whether this device may serve it. Pure: no sockets, no state.
/// These are the checks libmodbus' modbus_reply() does not make (or makes only after reading
/// fields it trusts modbus_receive() to have framed): the PDU length per function code, the
/// quantities and byte counts (03), the device's register map with absent and read-only
/// registers (02), the supported function codes (01) and, with `strict_unit`, the unit (0B).
/// A request that passes is served by modbus_reply(); see hil::mocks::ModbusResponder.
struct RequestCheck {
  std::uint8_t function = 0;              ///< request function code (0 when the ADU is malformed)
  ModbusError error = ModbusError::none;  ///< the exception to answer, or invalid_request: no answer, close
  std::uint16_t written_first = 0;        ///< holding registers the request writes (when error == none)
  std::uint16_t written_count = 0;
  std::uint16_t coils_written_first = 0;  ///< coils the request writes (FC 5/15, when error == none)
  std::uint16_t coils_written_count = 0;
};

/// Check one complete request ADU (as delimited by check_frame()). A malformed ADU (size
/// disagrees with the MBAP length, protocol id != 0) gives `invalid_request`.
[[nodiscard]] RequestCheck check_request(std::span<const std::uint8_t> adu, const RegisterTable& table,
                                         const HandlerOptions& options) noexcept;

}  // namespace hil::modbus
