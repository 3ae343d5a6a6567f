// SPDX-License-Identifier: MIT
#pragma once
// Internal to the `can` CLI module: one function per subcommand.
#include <CLI/CLI.hpp>

#include "hil/cli/context.hpp"

namespace hil::cli::can_cmd {

void add_hub(CLI::App& can, Context& ctx);
void add_dump(CLI::App& can, Context& ctx);
void add_send(CLI::App& can, Context& ctx);
void add_replay(CLI::App& can, Context& ctx);

/// The help text shared by every --bus option.
inline constexpr const char* bus_help =
    "CAN bus: an interface (vcan0, can0), socketcand://HOST[:PORT]/BUS (socketcand daemon or `hilbridge can hub`)";

}  // namespace hil::cli::can_cmd
