// SPDX-License-Identifier: MIT
#pragma once
// The `io: - {analog: NAME, value: V, at: T, ramp: D}` entry of a scenario (docs/scenarios.md),
// loaded apart from the rest of the scenario loader. Internal to the loader; errors are
// hil::yaml::Failure (file, line, column, key path, what was expected).

#include "hil/config/yaml_field.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime::detail {

/// An `io:` entry with the key `analog:`. The input's name and range are checked against the
/// device when the machine is built (Machine::attach_io).
AnalogStimulus load_analog_stimulus(const yaml::Field& f);

}  // namespace hil::runtime::detail
