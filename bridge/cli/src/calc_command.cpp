// SPDX-License-Identifier: MIT
#include "hil/cli/calc_command.hpp"

#include <string>

namespace hil::cli {
namespace {

CLI::App* find_subcommand(const CLI::App& app, const std::string& name) {
  try {
    return app.get_subcommand(name);
  } catch (const CLI::OptionNotFound&) {
    return nullptr;
  }
}

}  // namespace

CLI::App* calc_command(Context& ctx) {
  CLI::App* profile = find_subcommand(ctx.app, "profile");
  if (profile == nullptr) return nullptr;
  if (CLI::App* calc = find_subcommand(*profile, "calc")) return calc;
  CLI::App* calc = profile->add_subcommand(
      "calc",
      "Setting-up calculators from a device manual's formulas: `profile calc DEVICE --help` (ip247, wf725-726, "
      "sinumerik-elg). Exit 1 when a value breaks a machine-data rule, 2 on bad use.");
  calc->require_subcommand(1);
  return calc;
}

}  // namespace hil::cli
