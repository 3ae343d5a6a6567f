// SPDX-License-Identifier: MIT
#include "hil/controllers/modbus_io_sim_bus.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace hil::controllers {

using modbus::BitSpace;

SimModbusIoBus::SimModbusIoBus(std::unique_ptr<mocks::ModbusDriveServer> server, const modbus::BitPlan& reads,
                               const modbus::BitPlan& writes, SimModbusIoBusConfig config)
    : server_(std::move(server)),
      reads_(reads.blocks),
      writes_(writes.blocks),
      config_(config),
      describe_("simulated terminal"),
      written_(writes.bits, 0) {}

std::expected<std::unique_ptr<SimModbusIoBus>, std::string> SimModbusIoBus::create(const SimTerminalOptions& options,
                                                                                   const modbus::BitPlan& reads,
                                                                                   const modbus::BitPlan& writes,
                                                                                   SimModbusIoBusConfig config) {
  mocks::ModbusServerConfig sc;
  sc.handler.unit_id = options.unit;
  sc.listen_host = options.listen_host;
  sc.port = options.listen_port;
  auto server = std::make_unique<mocks::ModbusDriveServer>(
      mocks::IoTerminal{mocks::IoTerminalConfig{options.coils, options.discrete_inputs}}, sc);
  if (options.listen) {
    if (const auto ec = server->start())
      return std::unexpected(
          fmt::format("the simulated terminal cannot listen on {}:{}: {} (is the port in use? "
                      "port 0 picks a free one)",
                      options.listen_host, options.listen_port, ec.message()));
  }
  return std::make_unique<SimModbusIoBus>(std::move(server), reads, writes, config);
}

void SimModbusIoBus::poll(TimePoint now, std::span<std::uint8_t> inputs) noexcept {
  const modbus::ModbusError err = server_->with_terminal([&](mocks::IoTerminal& t) noexcept {
    const auto& table = t.table();
    for (const auto& b : reads_)
      if (!table.range_ok(b.space, b.first, b.count, false)) return modbus::ModbusError::illegal_data_address;
    std::size_t at = 0;
    for (const auto& b : reads_) {
      const auto values = table.values(b.space);
      std::copy_n(values.begin() + b.first, b.count, inputs.begin() + static_cast<std::ptrdiff_t>(at));
      at += b.count;
    }
    return modbus::ModbusError::none;
  });
  if (err != modbus::ModbusError::none) {
    ++status_.errors;
    status_.error = err;
    return;
  }
  ++status_.polls;
  status_.error = modbus::ModbusError::none;
  stamp_ = now;
}

void SimModbusIoBus::fetch(TimePoint now, std::span<std::uint8_t> inputs, ModbusIoStatus& status) noexcept {
  if (!started_) {
    started_ = true;
    start_ = now;
    next_poll_ = now;
  }
  if (attempt_ && now >= *attempt_ + config_.response_timeout) {
    ++status_.errors;
    status_.error = modbus::ModbusError::timeout;
    status_.connected = false;
    attempt_.reset();
    next_poll_ = now;
  }
  if (!attempt_ && now >= next_poll_) {
    next_poll_ = now + config_.poll;
    if (answering_) {
      if (!status_.connected) rewrite_all_ = true;
      status_.connected = true;
      poll(now, inputs);
    } else {
      attempt_ = now;
    }
  }
  status_.age = now - (status_.polls > 0 ? stamp_ : start_);
  status = status_;
  if (status.error == modbus::ModbusError::none) status.error = write_error_;
}

void SimModbusIoBus::put(TimePoint, std::span<const std::uint8_t> outputs) noexcept {
  if (!answering_ || !status_.connected || writes_.empty()) return;
  const bool all = rewrite_all_;
  rewrite_all_ = false;
  server_->with_terminal([&](mocks::IoTerminal& t) noexcept {
    auto& table = t.table();
    std::size_t at = 0;
    write_error_ = modbus::ModbusError::none;
    for (const auto& b : writes_) {
      const auto from = static_cast<std::ptrdiff_t>(at);
      at += b.count;
      if (!all && std::equal(outputs.begin() + from, outputs.begin() + from + b.count, written_.begin() + from))
        continue;
      if (!table.range_ok(b.space, b.first, b.count, true)) {
        ++status_.errors;
        write_error_ = modbus::ModbusError::illegal_data_address;  // reported by fetch until a write succeeds
        continue;
      }
      for (std::uint16_t i = 0; i < b.count; ++i)
        table.set(BitSpace::coil, static_cast<std::uint16_t>(b.first + i),
                  outputs[static_cast<std::size_t>(from) + i] != 0);
      std::copy_n(outputs.begin() + from, b.count, written_.begin() + from);
    }
  });
}

}  // namespace hil::controllers
