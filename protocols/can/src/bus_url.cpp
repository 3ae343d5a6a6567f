// SPDX-License-Identifier: MIT
#include "hil/can/bus_url.hpp"

#include <charconv>

namespace hil::can {

namespace {

constexpr std::string_view forms =
    "expected an interface name (vcan0), socketcan:NAME, socketcand://HOST[:PORT]/BUS or virtual:NAME";

bool name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
}

bool valid_name(std::string_view s, std::size_t max) {
  if (s.empty() || s.size() > max) return false;
  for (char c : s)
    if (!name_char(c)) return false;
  return true;
}

// A host name or IPv4 address (letters, digits, '-', '.', '_'), or inside brackets an IPv6 address
// (hex digits, ':', '.', and a '%zone' of name characters): what to_string() can write back.
bool valid_host(std::string_view s, bool v6) {
  if (!v6) return valid_name(s, 253);
  if (s.empty() || s.size() > 253 || s.find(':') == std::string_view::npos) return false;  // "[%0]": no IPv6
  for (char c : s)
    if (!name_char(c) && c != ':' && c != '%') return false;
  return true;
}

std::unexpected<std::string> bad(std::string_view text, std::string_view why) {
  return std::unexpected("bad bus URL '" + std::string(text) + "': " + std::string(why));
}

}  // namespace

std::string BusUrl::to_string() const {
  switch (kind) {
    case Kind::socketcan:
      return name;
    case Kind::virtual_bus:
      return "virtual:" + name;
    case Kind::socketcand: {
      const bool v6 = host.find(':') != std::string::npos;
      return "socketcand://" + (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port) + "/" + name;
    }
  }
  return name;
}

std::expected<BusUrl, std::string> parse_bus_url(std::string_view text) {
  BusUrl url;
  if (text.starts_with("virtual:")) {
    url.kind = BusUrl::Kind::virtual_bus;
    url.name = std::string(text.substr(8));
    if (!valid_name(url.name, 64)) return bad(text, "a virtual bus name has 1..64 characters of [A-Za-z0-9_.-]");
    return url;
  }
  if (text.starts_with("socketcan:")) {
    url.name = std::string(text.substr(10));
    if (!valid_name(url.name, 15)) return bad(text, "an interface name has 1..15 characters of [A-Za-z0-9_.-]");
    return url;
  }
  if (text.starts_with("socketcand://")) {
    url.kind = BusUrl::Kind::socketcand;
    auto rest = text.substr(13);
    const auto slash = rest.find('/');
    if (slash == std::string_view::npos)
      return bad(text, "missing /BUS after the host (e.g. socketcand://127.0.0.1:29536/can0)");
    auto authority = rest.substr(0, slash);
    url.name = std::string(rest.substr(slash + 1));
    if (!valid_name(url.name, 16)) return bad(text, "the bus name after '/' has 1..16 characters of [A-Za-z0-9_.-]");
    std::string_view port_text;
    if (authority.starts_with("[")) {
      const auto close = authority.find(']');
      if (close == std::string_view::npos) return bad(text, "unterminated [IPv6] host");
      url.host = std::string(authority.substr(1, close - 1));
      auto after = authority.substr(close + 1);
      if (!after.empty()) {
        if (after.front() != ':') return bad(text, "expected :PORT after the [IPv6] host");
        port_text = after.substr(1);
      }
    } else {
      const auto colon = authority.rfind(':');
      url.host = std::string(authority.substr(0, colon));
      if (colon != std::string_view::npos) port_text = authority.substr(colon + 1);
      if (url.host.find(':') != std::string::npos) return bad(text, "write IPv6 hosts in brackets: [::1]:29536");
    }
    if (url.host.empty()) return bad(text, "missing host");
    if (!valid_host(url.host, authority.starts_with("[")))
      return bad(text,
                 "the host has characters no host name or address has (letters, digits, '-', '.'; inside "
                 "[IPv6] brackets an address with ':')");
    if (authority.find(':') != std::string_view::npos && port_text.empty() && !authority.starts_with("["))
      return bad(text, "empty port after ':'");
    if (!port_text.empty()) {
      unsigned v = 0;
      auto [p, ec] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), v);
      if (ec != std::errc{} || p != port_text.data() + port_text.size() || v == 0 || v > 65535)
        return bad(text, "the port must be a number 1..65535");
      url.port = static_cast<std::uint16_t>(v);
    }
    return url;
  }
  if (text.find("://") != std::string_view::npos)
    return bad(text, std::string("unknown scheme; ") + std::string(forms));
  url.name = std::string(text);
  if (!valid_name(url.name, 15)) return bad(text, forms);
  return url;
}

}  // namespace hil::can
