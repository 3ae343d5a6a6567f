// SPDX-License-Identifier: MIT
#pragma once
// The simulated drive server's protocol engine: libmodbus' own server side. Each request ADU
// (framed by the MBAP length, see modbus_server.hpp) first passes modbus::check_request() (the
// device's register map and the length rules libmodbus leaves to modbus_receive()); then
// modbus_reply() serves it against a modbus_mapping_t laid directly over the RegisterTable (no
// copies), or modbus_reply_exception() answers the exception the check found. libmodbus writes
// its reply to a socket, so the responder owns a local socket pair and reads the reply back:
// the server keeps its own Asio write path (pipelining, response-delay injection).
// Not thread-safe: one responder per device, used under the device's mutex.

#include <cstdint>
#include <span>

#include "hil/modbus/register_table.hpp"
#include "hil/modbus/request_handler.hpp"

struct _modbus;  // libmodbus' modbus_t

namespace hil::mocks {

class ModbusResponder {
 public:
  ModbusResponder();
  ~ModbusResponder();
  ModbusResponder(ModbusResponder&& other) noexcept;
  ModbusResponder& operator=(ModbusResponder&& other) noexcept;
  ModbusResponder(const ModbusResponder&) = delete;
  ModbusResponder& operator=(const ModbusResponder&) = delete;

  /// Serve one complete request ADU. `out` must hold modbus::kMaxAduSize bytes. A malformed ADU
  /// gives no response (`size` 0, `error == invalid_request`): the caller closes the connection.
  /// If the local socket pair could not be made, every request gets exception 04 (device failure).
  modbus::HandleResult handle(std::span<const std::uint8_t> adu, modbus::RegisterTable& table,
                              std::span<std::uint8_t> out, const modbus::HandlerOptions& options) noexcept;

 private:
  void release() noexcept;
  _modbus* ctx_ = nullptr;
  int reply_fd_ = -1;  ///< the end libmodbus sends its reply to is ctx_'s socket; this is the other end
};

}  // namespace hil::mocks
