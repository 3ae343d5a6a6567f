// SPDX-License-Identifier: MIT
#include "hil/modbus/bus_address.hpp"

#include <charconv>

namespace hil::modbus {

namespace {

bool name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
}

bool valid_host(std::string_view s, bool v6) {
  if (s.empty() || s.size() > 253) return false;
  if (v6 && s.find(':') == std::string_view::npos) return false;  // "[%0]" is no IPv6 address
  for (char c : s)
    if (!name_char(c) && !(v6 && (c == ':' || c == '%'))) return false;
  return true;
}

std::unexpected<std::string> bad(std::string_view what, std::string_view text, std::string_view why) {
  return std::unexpected(std::string(what) + " '" + std::string(text) + "': " + std::string(why));
}

std::unexpected<std::string> reason(std::string_view why) {
  return std::unexpected(std::string(why));
}

// The parse, with an error that is only the reason (the callers say what was parsed).
std::expected<Endpoint, std::string> endpoint(std::string_view text, bool port_required, std::uint16_t default_port,
                                              bool allow_port_zero) {
  Endpoint ep;
  ep.port = default_port;
  std::string_view port_text;
  bool has_port = false;
  const bool v6 = text.starts_with("[");
  if (v6) {
    const auto close = text.find(']');
    if (close == std::string_view::npos) return reason("unterminated [IPv6] host");
    ep.host = std::string(text.substr(1, close - 1));
    const auto after = text.substr(close + 1);
    if (!after.empty()) {
      if (after.front() != ':') return reason("expected :PORT after the [IPv6] host");
      port_text = after.substr(1);
      has_port = true;
    }
  } else {
    const auto colon = text.rfind(':');
    ep.host = std::string(text.substr(0, colon));
    if (colon != std::string_view::npos) {
      port_text = text.substr(colon + 1);
      has_port = true;
    }
    if (ep.host.find(':') != std::string::npos) return reason("write IPv6 hosts in brackets: [::1]:502");
  }
  if (ep.host.empty()) return reason("missing host (e.g. 127.0.0.1:1502)");
  if (!valid_host(ep.host, v6))
    return reason(
        "the host has characters no host name or address has (letters, digits, '-', '.'; inside [IPv6] "
        "brackets an address with ':')");
  if (!has_port && port_required) return reason("expected HOST:PORT (e.g. 127.0.0.1:1502)");
  if (has_port) {
    unsigned v = 0;
    const auto [p, ec] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), v);
    const unsigned min = allow_port_zero ? 0 : 1;
    if (port_text.empty() || ec != std::errc{} || p != port_text.data() + port_text.size() || v < min || v > 65535)
      return reason(allow_port_zero ? "the port must be a number 0..65535 (0: any free port)"
                                    : "the port must be a number 1..65535");
    ep.port = static_cast<std::uint16_t>(v);
  }
  return ep;
}

}  // namespace

std::string Endpoint::to_string() const {
  const bool v6 = host.find(':') != std::string::npos;
  return (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

std::string BusAddress::to_string() const {
  return kind == Kind::sim ? std::string("sim") : "tcp://" + endpoint.to_string();
}

std::expected<Endpoint, std::string> parse_endpoint(std::string_view text, bool port_required,
                                                    std::uint16_t default_port, bool allow_port_zero) {
  auto ep = endpoint(text, port_required, default_port, allow_port_zero);
  if (!ep) return bad("bad address", text, ep.error());
  return ep;
}

std::expected<BusAddress, std::string> parse_bus_address(std::string_view text) {
  BusAddress bus;
  if (text == "sim") return bus;
  if (!text.starts_with("tcp://"))
    return bad("bad Modbus bus", text, "expected sim (the simulated terminal) or tcp://HOST[:PORT]");
  auto ep = endpoint(text.substr(6), false, 502, false);
  if (!ep) return bad("bad Modbus bus", text, ep.error());
  bus.kind = BusAddress::Kind::tcp;
  bus.endpoint = std::move(*ep);
  return bus;
}

}  // namespace hil::modbus
