// SPDX-License-Identifier: MIT
#pragma once
// The machine file of an emulator's retrofit mode (`emulate clm14|elg-tape|ip247|wf725 --machine`):
// a scenario whose machine (axes on their transports) the emulated device drives.

#include <fmt/format.h>

#include <asio/io_context.hpp>

#include <expected>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "hil/cli/context.hpp"
#include "hil/core/clock.hpp"
#include "hil/runtime/machine.hpp"
#include "hil/runtime/scenario_loader.hpp"

namespace hil::cli::serial_cli {

/// The machine of a machine file, built on its transports, and what it runs on. A retrofit mode
/// derives from it and adds what binds the device to the axes.
struct MachineFile {
  asio::io_context io;
  SteadyClock clock;
  hil::runtime::Scenario scenario;
  std::unique_ptr<RunEnvironment> env;
  std::optional<hil::runtime::Machine> machine;
};

/// Builds `scenario` into a new R (a MachineFile): `check` says what is wrong with the scenario
/// for this device (empty: nothing), before any transport is opened.
template <class R>
std::expected<std::unique_ptr<R>, std::string> build_machine(
    hil::runtime::Scenario scenario, const TransportRegistry& registry,
    const std::function<std::string(const hil::runtime::Scenario&)>& check) {
  auto r = std::make_unique<R>();
  r->scenario = std::move(scenario);
  if (auto why = check(r->scenario); !why.empty()) return std::unexpected(why);
  r->env = std::make_unique<RunEnvironment>(
      RunEnvironment{r->clock, false, &r->io, r->scenario.file, r->scenario.period, false, {}});
  auto m = hil::runtime::Machine::build(r->scenario, registry, *r->env);
  if (!m) return std::unexpected(m.error().describe());
  r->machine.emplace(std::move(*m));
  return r;
}

/// Loads `file` (a scenario) and builds it (build_machine).
template <class R>
std::expected<std::unique_ptr<R>, std::string> load_machine(
    const std::string& file, const TransportRegistry& registry,
    const std::function<std::string(const hil::runtime::Scenario&)>& check) {
  auto sc = hil::runtime::load_scenario(file);
  if (!sc) return std::unexpected(sc.error().describe());
  return build_machine<R>(std::move(*sc), registry, check);
}

}  // namespace hil::cli::serial_cli
