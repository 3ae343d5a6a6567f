// SPDX-License-Identifier: MIT
#pragma once
// What a CLI module gets: the root app, the shared `emulate` parent command, the transport
// registry (so `hilbridge run` can build drives of every transport) and the exit code.
// A module lives in bridge/cli/<name>/ and defines `void hil::cli::register_<name>(Context&)`.

#include <CLI/CLI.hpp>

#include "hil/core/transport.hpp"

namespace hil::cli {

struct Context {
  CLI::App& app;                  ///< `hilbridge`
  CLI::App& emulate;              ///< `hilbridge emulate <endpoint>`: mock endpoints
  TransportRegistry& transports;  ///< filled by modules; used by run/test
  int exit_code = 0;              ///< set by a command's callback; returned by main
};

}  // namespace hil::cli
