// SPDX-License-Identifier: MIT
#include "hil/mocks/modbus_io_terminal.hpp"

namespace hil::mocks {

using modbus::BitSpace;

IoTerminal::IoTerminal(IoTerminalConfig config) : config_(config) {
  if (config_.coils > 0) table_.define(BitSpace::coil, 0, config_.coils, modbus::Access::read_write);
  if (config_.discrete_inputs > 0)
    table_.define(BitSpace::discrete_input, 0, config_.discrete_inputs, modbus::Access::read_only);
}

modbus::HandleResult IoTerminal::handle(std::span<const std::uint8_t> adu, std::span<std::uint8_t> out,
                                        const modbus::HandlerOptions& options) noexcept {
  auto r = responder_.handle(adu, table_, out, options);
  if (r.coils_written_count > 0) {
    ++coil_write_requests_;
    coils_written_ += r.coils_written_count;
  }
  return r;
}

bool IoTerminal::coil(std::uint16_t address) const noexcept {
  return address < config_.coils && table_.get(BitSpace::coil, address);
}

void IoTerminal::set_coil(std::uint16_t address, bool value) noexcept {
  if (address < config_.coils) table_.set(BitSpace::coil, address, value);
}

bool IoTerminal::discrete_input(std::uint16_t address) const noexcept {
  return address < config_.discrete_inputs && table_.get(BitSpace::discrete_input, address);
}

void IoTerminal::set_discrete_input(std::uint16_t address, bool value) noexcept {
  if (address < config_.discrete_inputs) table_.set(BitSpace::discrete_input, address, value);
}

}  // namespace hil::mocks
