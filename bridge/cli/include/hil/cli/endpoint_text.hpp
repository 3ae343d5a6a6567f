// SPDX-License-Identifier: MIT
#pragma once
// TCP endpoints on the command line, one way in every command (docs/cli.md, "Endpoints"):
// `HOST:PORT` or `tcp://HOST:PORT` (`[V6]:PORT` for IPv6). CAN buses are `--bus URL`, serial devices
// `--port DEVICE`.

#include <string_view>

namespace hil::cli {

/// "tcp://HOST:PORT" -> "HOST:PORT"; any other text unchanged.
[[nodiscard]] constexpr std::string_view strip_tcp_scheme(std::string_view text) noexcept {
  constexpr std::string_view scheme = "tcp://";
  return text.starts_with(scheme) ? text.substr(scheme.size()) : text;
}

}  // namespace hil::cli
