// SPDX-License-Identifier: MIT
#pragma once
// Bus URLs, the one syntax every `--bus` option of hilbridge accepts (pure parser):
//   vcan0, can0, slcan0 ...          a SocketCAN interface (1..15 of [A-Za-z0-9_.-])
//   socketcan:NAME                   the same, explicit
//   socketcand://HOST[:PORT]/BUS     a socketcand server (the daemon or `hilbridge can hub`);
//                                    PORT defaults to 29536; HOST may be [IPv6]
//   virtual:NAME                     an in-process VirtualBus (shared by name within one process)
// Opening one: hil/can/io/make_channel.hpp.

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>

namespace hil::can {

struct BusUrl {
  enum class Kind : std::uint8_t { socketcan, socketcand, virtual_bus };
  Kind kind = Kind::socketcan;
  std::string name;  ///< interface (socketcan), bus on the server (socketcand), bus name (virtual)
  std::string host;  ///< socketcand only
  std::uint16_t port = 29536;
  /// Canonical text form (parse_bus_url(to_string()) gives the same BusUrl).
  [[nodiscard]] std::string to_string() const;
  friend bool operator==(const BusUrl&, const BusUrl&) = default;
};

/// Parse a bus URL. The error is a complete sentence naming the text and the accepted forms.
[[nodiscard]] std::expected<BusUrl, std::string> parse_bus_url(std::string_view text);

}  // namespace hil::can
