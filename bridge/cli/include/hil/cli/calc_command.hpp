// SPDX-License-Identifier: MIT
#pragma once
// `hilbridge profile calc DEVICE ...`: one subcommand per device calculator, added by the device's
// CLI module (ip247 by bridge/cli/s5, sinumerik-elg by bridge/cli/sinumerik).

#include <CLI/CLI.hpp>

#include "hil/cli/context.hpp"

namespace hil::cli {

/// The `profile calc` command, created by the first module that asks; nullptr when the binary has
/// no `profile` command (built without the profile module, which registers before these).
[[nodiscard]] CLI::App* calc_command(Context& ctx);

}  // namespace hil::cli
