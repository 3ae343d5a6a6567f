// SPDX-License-Identifier: MIT
#pragma once
// Internal to the `profile` CLI module: shared helpers of its commands.

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hil/profiles/profile.hpp"
#include "hil/profiles/settings.hpp"

namespace hil::cli::profile {

/// Prints the overview of a profile (settings, parameters, constraints, catalogues, decisions).
void print_overview(const hil::profiles::Profile& p);
/// Prints every variant, field, range, default and rule of one parameter.
void print_parameter(const hil::profiles::Profile& p, const hil::profiles::ParamRef& ref);
/// Prints one or all error catalogues.
void print_catalogues(const hil::profiles::Profile& p, const std::string& which);
/// The profile's rules that name the parameter `ref`.
[[nodiscard]] std::vector<const hil::profiles::Constraint*> rules_of(const hil::profiles::Profile& p,
                                                                     const hil::profiles::ParamRef& ref);

// `profile show --json` (profile_json.cpp; schemas in docs/json.md).
[[nodiscard]] nlohmann::json overview_json(const hil::profiles::Profile& p);
[[nodiscard]] nlohmann::json parameter_json(const hil::profiles::Profile& p, const hil::profiles::ParamRef& ref);
[[nodiscard]] nlohmann::json catalogues_json(const hil::profiles::Profile& p, const std::string& which);
/// Every catalogue entry with this code (array, empty when none).
[[nodiscard]] nlohmann::json error_codes_json(const hil::profiles::Profile& p, const std::string& code);

}  // namespace hil::cli::profile
