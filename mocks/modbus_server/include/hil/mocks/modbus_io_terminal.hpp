// SPDX-License-Identifier: MIT
#pragma once
// A simulated Modbus/TCP digital I/O terminal (a bus coupler with DI and DO modules): coils
// 0..coils-1 (FC 1 read, FC 5/15 write; the terminal's outputs) and discrete inputs
// 0..discrete_inputs-1 (FC 2; the terminal's inputs, set by the simulated field wiring).
// Requests are served by libmodbus (ModbusResponder) against the terminal's RegisterTable, the
// same path as the simulated drive. Not thread-safe: ModbusDriveServer serialises access
// (with_terminal), or a single thread owns it.

#include <cstdint>
#include <span>

#include "hil/mocks/modbus_responder.hpp"
#include "hil/modbus/register_table.hpp"
#include "hil/modbus/request_handler.hpp"

namespace hil::mocks {

struct IoTerminalConfig {
  std::uint16_t coils = 64;            ///< coils 0..coils-1, read-write
  std::uint16_t discrete_inputs = 64;  ///< discrete inputs 0..discrete_inputs-1, read-only on the wire
};

class IoTerminal {
 public:
  explicit IoTerminal(IoTerminalConfig config = {});

  /// Serve one request ADU (see ModbusResponder::handle). Counts the coil writes.
  modbus::HandleResult handle(std::span<const std::uint8_t> adu, std::span<std::uint8_t> out,
                              const modbus::HandlerOptions& options) noexcept;

  [[nodiscard]] const IoTerminalConfig& config() const noexcept { return config_; }
  /// A coil's state (an address outside the terminal reads false).
  [[nodiscard]] bool coil(std::uint16_t address) const noexcept;
  /// Set a coil from the terminal side (tests; a real terminal's outputs change only by requests).
  void set_coil(std::uint16_t address, bool value) noexcept;
  [[nodiscard]] bool discrete_input(std::uint16_t address) const noexcept;
  /// The field wiring: set a discrete input (an address outside the terminal is ignored).
  void set_discrete_input(std::uint16_t address, bool value) noexcept;
  /// Requests that wrote coils (FC 5 and FC 15) and the coils they wrote in total.
  [[nodiscard]] std::uint64_t coil_write_requests() const noexcept { return coil_write_requests_; }
  [[nodiscard]] std::uint64_t coils_written() const noexcept { return coils_written_; }
  [[nodiscard]] modbus::RegisterTable& table() noexcept { return table_; }

 private:
  IoTerminalConfig config_;
  modbus::RegisterTable table_;
  ModbusResponder responder_;
  std::uint64_t coil_write_requests_ = 0;
  std::uint64_t coils_written_ = 0;
};

}  // namespace hil::mocks
