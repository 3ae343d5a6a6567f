// SPDX-License-Identifier: MIT
// hilbridge: hardware-in-the-loop bridge to fieldbus drives.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <string_view>

#include "hil/cli/context.hpp"
#include "hil/cli/json_output.hpp"

namespace hil::cli {
void register_all_modules(Context& ctx);  // generated: cli_registry.cpp
}

int main(int argc, char** argv) {
  CLI::App app{
      "hilbridge: hardware-in-the-loop bridge to fieldbus drives.\n"
      "Runs motion scenarios against simulated or real drives over CANopen (SocketCAN), Modbus/TCP,\n"
      "GPIO step/direction and legacy serial links. With no hardware, everything runs on\n"
      "in-process mock endpoints.",
      "hilbridge"};
  app.set_version_flag("--version", std::string("hilbridge ") + HIL_VERSION);
  app.require_subcommand(0, 1);
  auto* emulate = app.add_subcommand("emulate", "Run a mock endpoint (simulated drive, node or legacy controller)");
  emulate->require_subcommand(1);

  hil::TransportRegistry transports;
  hil::cli::Context ctx{app, *emulate, transports};
  hil::cli::register_all_modules(ctx);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help/--version exit 0; every usage error exits 2, as the commands' help texts say
    // (CLI11's own codes, 105..115, are documented nowhere).
    if (app.exit(e) == 0) return 0;
    // A machine reading --json output gets the usage error as JSON too (docs/json.md).
    for (int i = 1; i < argc; ++i)
      if (std::string_view(argv[i]) == "--json" || std::string_view(argv[i]) == "--jsonl") {
        hil::cli::print_json({{"error", e.what()}, {"exit_code", 2}});
        break;
      }
    return 2;
  }
  if (app.get_subcommands().empty()) {
    // `hilbridge` alone runs the bundled demo when the run module is present.
    const auto all = app.get_subcommands([](const CLI::App* s) { return s->get_name() == "run"; });
    if (!all.empty()) {
      try {
        app.parse(std::vector<std::string>{"run"});
      } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;  // usage errors exit 2, as above
      }
    } else {
      fmt::print("{}", app.help());
    }
  }
  return ctx.exit_code;
}
