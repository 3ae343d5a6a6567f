// SPDX-License-Identifier: MIT
#pragma once
// Where a Modbus I/O terminal is (pure parsers for the scenario's `io_links: - modbus:` keys):
//   bus:    sim                     the in-process simulated terminal (mocks/modbus_server)
//           tcp://HOST[:PORT]       a Modbus/TCP server; PORT defaults to 502; HOST may be [IPv6]
//   listen: HOST:PORT               where the simulated terminal accepts peers (PORT 0: any free port)
// Host names follow the bus URL rule of hilbridge (hil/can/bus_url.hpp): letters, digits, '-',
// '.', '_'; inside brackets an IPv6 address.

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>

namespace hil::modbus {

struct Endpoint {
  std::string host;  ///< without brackets
  std::uint16_t port = 502;
  /// HOST:PORT, IPv6 hosts in brackets (parse_endpoint(to_string()) gives the same Endpoint).
  [[nodiscard]] std::string to_string() const;
  friend bool operator==(const Endpoint&, const Endpoint&) = default;
};

struct BusAddress {
  enum class Kind : std::uint8_t { sim, tcp };
  Kind kind = Kind::sim;
  Endpoint endpoint;  ///< tcp only
  /// "sim" or "tcp://HOST:PORT" (parse_bus_address(to_string()) gives the same BusAddress).
  [[nodiscard]] std::string to_string() const;
  friend bool operator==(const BusAddress&, const BusAddress&) = default;
};

/// Parse a `bus:` value. The error is a sentence naming the text and the accepted forms.
[[nodiscard]] std::expected<BusAddress, std::string> parse_bus_address(std::string_view text);

/// Parse HOST:PORT (`port_required`) or HOST[:PORT] (else PORT defaults to `default_port`).
/// `allow_port_zero`: port 0 means "any free port" (listen addresses).
[[nodiscard]] std::expected<Endpoint, std::string> parse_endpoint(std::string_view text, bool port_required,
                                                                  std::uint16_t default_port, bool allow_port_zero);

}  // namespace hil::modbus
