// SPDX-License-Identifier: MIT
#pragma once
// Modbus faults as error codes. Values 1..11 *are* the Modbus exception codes (Modbus
// Application Protocol v1.1b3 §7); values from 0x100 are link-level conditions that never appear
// on the wire (timeouts, lost connections, malformed replies). Category name: "modbus".

#include <cstdint>
#include <optional>
#include <system_error>

namespace hil::modbus {

enum class ModbusError : int {
  none = 0,
  // Exception codes (MB spec §7, libmodbus MODBUS_EXCEPTION_*).
  illegal_function = 0x01,
  illegal_data_address = 0x02,
  illegal_data_value = 0x03,
  server_device_failure = 0x04,
  acknowledge = 0x05,
  server_device_busy = 0x06,
  negative_acknowledge = 0x07,
  memory_parity_error = 0x08,
  gateway_path_unavailable = 0x0A,
  gateway_target_failed = 0x0B,
  // Link-level (not on the wire).
  timeout = 0x101,           ///< no (complete) response within the response timeout
  connection_lost = 0x102,   ///< peer closed or reset the TCP connection
  connect_failed = 0x103,    ///< TCP connect refused / unreachable
  invalid_response = 0x104,  ///< reply with wrong TID, unit, function or length
  invalid_request = 0x105,   ///< malformed MBAP header (server side: connection closed)
};

const std::error_category& modbus_category() noexcept;
inline std::error_code make_error_code(ModbusError e) noexcept {
  return {static_cast<int>(e), modbus_category()};
}

/// True for the values that are Modbus exception codes (1..8, 10, 11).
[[nodiscard]] constexpr bool is_exception_code(int v) noexcept {
  return (v >= 1 && v <= 8) || v == 10 || v == 11;
}

/// The exception for a wire byte, or nullopt when the byte is not a defined exception code.
[[nodiscard]] constexpr std::optional<ModbusError> exception_from_code(std::uint8_t code) noexcept {
  if (!is_exception_code(code)) return std::nullopt;
  return static_cast<ModbusError>(code);
}

/// Map a libmodbus errno (EMBX* = MODBUS_ENOBASE + code, ETIMEDOUT, ECONNRESET, EMBBADDATA ...)
/// onto ModbusError. Pure; the caller passes `errno` after a failed libmodbus call.
[[nodiscard]] ModbusError from_libmodbus_errno(int err) noexcept;

}  // namespace hil::modbus

template <>
struct std::is_error_code_enum<hil::modbus::ModbusError> : std::true_type {};

namespace hil::modbus {
/// Category "modbus-drive": the value is the drive's own fault-code register (CiA 402 error
/// code 603Fh for cia402 profiles, the vendor's fault number otherwise). The profile's
/// fault_texts give the text.
const std::error_category& drive_fault_category() noexcept;
inline std::error_code make_drive_fault_code(std::uint32_t code) noexcept {
  return {static_cast<int>(code), drive_fault_category()};
}
}  // namespace hil::modbus
