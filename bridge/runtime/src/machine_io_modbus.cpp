// SPDX-License-Identifier: MIT
// The `modbus:` kind of the scenario's io_links: a Modbus/TCP digital I/O terminal wired to the
// controller's image (docs/controllers.md "Modbus I/O"): the in-process simulated terminal
// (optionally served on TCP to peers) or a real one through libmodbus on a worker thread.
#include <algorithm>

#include <fmt/format.h>

#include "hil/controllers/modbus_io_sim_bus.hpp"
#include "hil/controllers/modbus_io_tcp_bus.hpp"
#include "hil/modbus/bus_address.hpp"
#include "hil/runtime/machine.hpp"

namespace hil::runtime {

std::optional<ConfigError> Machine::make_modbus_link(const Scenario& scenario, const IoLink& link,
                                                     const ModbusLinkDevice& d, const ResolveLinkBit& resolve) {
  const auto fail = [&](std::string key, std::string message) {
    return ConfigError{scenario.file, link.source.line, 0, link.source.path + key, std::move(message)};
  };
  controllers::ModbusIoLinkConfig config;
  config.name = link.source.path;
  config.stale_after = d.stale_after.value_or(d.timeout + 2 * d.poll);
  std::uint32_t coils = 0;
  std::uint32_t discrete_inputs = 0;
  const auto add = [&](const std::vector<IoLinkBit>& bits, bool input,
                       std::vector<controllers::ModbusIoBit>& out) -> std::optional<ConfigError> {
    for (const IoLinkBit& b : bits) {
      auto a = resolve(b, input);
      if (!a) return a.error();
      const auto& m = std::get<ModbusLinkBit>(b.where);
      const auto space = m.coil ? modbus::BitSpace::coil : modbus::BitSpace::discrete_input;
      auto& top = m.coil ? coils : discrete_inputs;
      top = std::max<std::uint32_t>(top, std::uint32_t{m.address} + 1);
      out.push_back({{space, m.address}, *a});
    }
    return std::nullopt;
  };
  if (auto e = add(link.inputs, true, config.inputs)) return e;
  if (auto e = add(link.outputs, false, config.outputs)) return e;
  if (!d.status.empty()) {
    IoLinkBit status;
    status.signal = d.status;
    status.source = d.status_source;
    auto a = resolve(status, true);
    if (!a) return a.error();
    config.status_bit = *a;
  }
  auto plans = controllers::make_io_plans(config);
  if (!plans) return fail(".outputs", plans.error());

  const auto bus = modbus::parse_bus_address(d.bus);
  if (!bus) return fail(".modbus.bus", bus.error());  // the loader checked it already
  std::unique_ptr<controllers::ModbusIoBus> io_bus;
  if (bus->kind == modbus::BusAddress::Kind::sim) {
    // The simulated terminal has at least 64 coils and 64 discrete inputs, and every address the
    // link uses (a peer may use the others).
    controllers::SimTerminalOptions terminal;
    terminal.coils = static_cast<std::uint16_t>(std::min<std::uint32_t>(std::max<std::uint32_t>(coils, 64), 65535));
    terminal.discrete_inputs =
        static_cast<std::uint16_t>(std::min<std::uint32_t>(std::max<std::uint32_t>(discrete_inputs, 64), 65535));
    terminal.unit = static_cast<std::uint8_t>(d.unit);
    if (!d.listen.empty()) {
      const auto ep = modbus::parse_endpoint(d.listen, true, 502, true);
      if (!ep) return fail(".modbus.listen", ep.error());
      terminal.listen = true;
      terminal.listen_host = ep->host;
      terminal.listen_port = ep->port;
    }
    auto sim = controllers::SimModbusIoBus::create(terminal, plans->reads, plans->writes,
                                                   controllers::SimModbusIoBusConfig{d.poll, d.timeout});
    if (!sim) return fail(".modbus.listen", sim.error());
    if (terminal.listen) {
      io_link_notes_.push_back(
          fmt::format("{}: simulated Modbus I/O terminal listening on {} (unit {}; {} coils, {} discrete inputs)",
                      link.source.path, modbus::Endpoint{terminal.listen_host, (*sim)->server().port()}.to_string(),
                      d.unit, terminal.coils, terminal.discrete_inputs));
    }
    io_bus = std::move(*sim);
  } else {
    if (!steady_clock_) steady_clock_ = std::make_unique<SteadyClock>();
    controllers::TcpModbusIoBusConfig tc;
    tc.host = bus->endpoint.host;
    tc.port = bus->endpoint.port;
    tc.unit = d.unit;
    tc.poll = d.poll;
    tc.response_timeout = d.timeout;
    io_bus = std::make_unique<controllers::TcpModbusIoBus>(tc, plans->reads, plans->writes, *steady_clock_);
  }
  auto l = std::make_unique<controllers::ModbusIoLink>(std::move(config), std::move(*plans), std::move(io_bus));
  auto& io = controller_->io();
  io.attach(static_cast<controllers::IoSource&>(*l));
  if (!l->config().outputs.empty()) io.attach(static_cast<controllers::IoSink&>(*l));
  modbus_links_.push_back(ModbusLinkEntry{link.source.path, std::move(l)});
  return std::nullopt;
}

}  // namespace hil::runtime
