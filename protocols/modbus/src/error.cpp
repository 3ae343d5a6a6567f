// SPDX-License-Identifier: MIT
#include "hil/modbus/error.hpp"

#include <cerrno>
#include <string>

#include <fmt/format.h>

namespace hil::modbus {
namespace {

// libmodbus: MODBUS_ENOBASE 112345678; EMBBADCRC = EMBXGTAR + 1 ... EMBBADSLAVE = EMBXGTAR + 6.
constexpr int kLibmodbusErrnoBase = 112345678;
constexpr int kLibmodbusLastErrno = kLibmodbusErrnoBase + 0x0B + 6;

class ModbusCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "modbus"; }
  std::string message(int v) const override {
    switch (static_cast<ModbusError>(v)) {
      case ModbusError::none:
        return "no error";
      case ModbusError::illegal_function:
        return "exception 01 illegal function: the drive does not support this function code";
      case ModbusError::illegal_data_address:
        return "exception 02 illegal data address: register not present or not writable; check the profile's addresses";
      case ModbusError::illegal_data_value:
        return "exception 03 illegal data value: quantity, byte count or value rejected";
      case ModbusError::server_device_failure:
        return "exception 04 server device failure: the drive failed while executing the request";
      case ModbusError::acknowledge:
        return "exception 05 acknowledge: long-running request accepted, poll later";
      case ModbusError::server_device_busy:
        return "exception 06 server device busy: retry later";
      case ModbusError::negative_acknowledge:
        return "exception 07 negative acknowledge: request cannot be performed";
      case ModbusError::memory_parity_error:
        return "exception 08 memory parity error in the drive";
      case ModbusError::gateway_path_unavailable:
        return "exception 0A gateway path unavailable: check the unit id / gateway routing";
      case ModbusError::gateway_target_failed:
        return "exception 0B gateway target device failed to respond: check the unit id";
      case ModbusError::timeout:
        return "no response within the response timeout: check the drive is powered and reachable";
      case ModbusError::connection_lost:
        return "connection lost: the drive closed or reset the TCP connection";
      case ModbusError::connect_failed:
        return "connect failed: nothing listens at the drive's address/port";
      case ModbusError::invalid_response:
        return "invalid response: wrong transaction id, unit, function or length";
      case ModbusError::invalid_request:
        return "malformed request: bad MBAP header (protocol id or length)";
    }
    return fmt::format("unknown modbus error {}", v);
  }
};

class DriveFaultCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "modbus-drive"; }
  std::string message(int v) const override {
    return fmt::format("drive fault code 0x{:04X} (see the drive manual / the profile's fault_texts)", v);
  }
};

}  // namespace

const std::error_category& drive_fault_category() noexcept {
  static const DriveFaultCategory c;
  return c;
}

const std::error_category& modbus_category() noexcept {
  static const ModbusCategory c;
  return c;
}

ModbusError from_libmodbus_errno(int err) noexcept {
  if (err > kLibmodbusErrnoBase && err <= kLibmodbusErrnoBase + 0x0B) {
    auto e = exception_from_code(static_cast<std::uint8_t>(err - kLibmodbusErrnoBase));
    return e ? *e : ModbusError::invalid_response;
  }
  if (err > kLibmodbusErrnoBase + 0x0B && err <= kLibmodbusLastErrno) return ModbusError::invalid_response;
  switch (err) {
    case ETIMEDOUT:
      return ModbusError::timeout;
    case ECONNREFUSED:
    case EHOSTUNREACH:
    case ENETUNREACH:
    case EINPROGRESS:
      return ModbusError::connect_failed;
    default:
      return ModbusError::connection_lost;
  }
}

}  // namespace hil::modbus
