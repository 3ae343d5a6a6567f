// SPDX-License-Identifier: MIT
// Fuzz the Modbus bus and listen-address parsers (scenario io_links `bus:` / `listen:`): any text
// gives a value or an error, never a crash; every accepted value prints back to a text that
// parses to the same value.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/modbus/bus_address.hpp"

namespace {
void require(bool ok) {
  if (!ok) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hil::modbus;
  if (size == 0) return 0;
  const std::uint8_t flags = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  if (auto bus = parse_bus_address(text)) {
    const auto again = parse_bus_address(bus->to_string());
    require(again && *again == *bus);
    require(bus->kind == BusAddress::Kind::sim || bus->endpoint.port != 0);
  } else {
    require(!bus.error().empty());
  }
  const bool port_required = flags & 1;
  const bool allow_zero = flags & 2;
  if (auto ep = parse_endpoint(text, port_required, 502, allow_zero)) {
    require(!ep->host.empty());
    require(allow_zero || ep->port != 0);
    const auto again = parse_endpoint(ep->to_string(), true, 502, allow_zero);
    require(again && *again == *ep);
  } else {
    require(!ep.error().empty());
  }
  return 0;
}
