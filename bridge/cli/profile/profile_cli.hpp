// SPDX-License-Identifier: MIT
#pragma once
// Internal to the `profile` CLI module: shared helpers of its commands.

#include <memory>
#include <string>
#include <vector>

#include "hil/profiles/profile.hpp"
#include "hil/profiles/settings.hpp"

namespace hil::cli::profile {

/// Prints the overview of a profile (settings, parameters, constraints, catalogues, decisions).
void print_overview(const hil::profiles::Profile& p);
/// Prints every variant, field, range, default and rule of one parameter.
void print_parameter(const hil::profiles::Profile& p, const hil::profiles::ParamRef& ref);
/// Prints one or all error catalogues.
void print_catalogues(const hil::profiles::Profile& p, const std::string& which);

}  // namespace hil::cli::profile
