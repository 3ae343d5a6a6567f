// SPDX-License-Identifier: MIT
#pragma once
// The coupling keys of a scenario (machine.masters / machine.cams / machine.couplings and the
// `couple:` step), loaded apart from the rest of the scenario loader. Internal to the loader;
// errors are LoadFailure (file, line, key path, what was expected).

#include "hil/runtime/scenario.hpp"
#include "yaml_reader.hpp"

namespace hil::runtime::detail {

/// machine.masters, machine.cams, machine.couplings (after the axes are loaded).
void load_coupling_machine(const Field& machine, Scenario& s);
/// The value of a `couple:` step.
CoupleStep load_couple_step(const Field& v, const Scenario& s);

}  // namespace hil::runtime::detail
