// SPDX-License-Identifier: MIT
#pragma once
// CiA 402 / CiA 301 error codes (0x603F, EMCY error code). The error_code value IS the 16-bit
// code; category "cia402"; message() = the table's text ("0x7305 Incremental sensor 1 fault").

#include <cstdint>
#include <string_view>
#include <system_error>

namespace hil::cia402 {

/// Well-known codes (CiA 402-2 annex / CiA 301 table 21). Any 16-bit code is valid as a value.
enum class ErrorCode : std::uint16_t {
  none = 0x0000,
  generic = 0x1000,
  continuous_over_current = 0x2310,
  short_circuit = 0x2320,
  dc_link_over_voltage = 0x3210,
  dc_link_under_voltage = 0x3220,
  excess_temperature_device = 0x4210,
  excess_temperature_motor = 0x4310,
  power_section = 0x5400,
  motor_blocked = 0x7121,
  sensor_1 = 0x7305,
  communication = 0x8100,
  heartbeat = 0x8130,
  pdo_length = 0x8210,
  following_error = 0x8611,
  reference_limit = 0x8612,
  software = 0x6100,
};

/// Text of a code from the table (exact codes first, then the code's group); never empty.
[[nodiscard]] std::string_view describe(std::uint16_t code) noexcept;
/// Error register (0x1001) bits for a code: generic + current/voltage/temperature/communication/profile.
[[nodiscard]] std::uint8_t error_register_for(std::uint16_t code) noexcept;

const std::error_category& cia402_category() noexcept;
inline std::error_code make_error_code(ErrorCode c) noexcept {
  return {static_cast<int>(static_cast<std::uint16_t>(c)), cia402_category()};
}
inline std::error_code make_cia402_error(std::uint16_t code) noexcept {
  return {static_cast<int>(code), cia402_category()};
}

}  // namespace hil::cia402

template <>
struct std::is_error_code_enum<hil::cia402::ErrorCode> : std::true_type {};
