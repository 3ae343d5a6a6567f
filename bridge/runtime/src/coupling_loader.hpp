// SPDX-License-Identifier: MIT
#pragma once
// The coupling keys of a scenario (machine.masters / machine.cams / machine.couplings and the
// `couple:` step), loaded apart from the rest of the scenario loader. Internal to the loader;
// errors are hil::yaml::Failure (file, line, column, key path, what was expected).

#include "hil/config/yaml_field.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime::detail {

using yaml::Field;  // the one YAML-reading idiom (hil::config)

/// machine.masters, machine.cams, machine.couplings (after the axes are loaded).
void load_coupling_machine(const Field& machine, Scenario& s);
/// The value of a `couple:` step.
CoupleStep load_couple_step(const Field& v, const Scenario& s);

}  // namespace hil::runtime::detail
