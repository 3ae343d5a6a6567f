// SPDX-License-Identifier: MIT
#pragma once
// Device kinds of the `io_links:` entries, loaded apart from the rest of the scenario loader
// (one function per kind's device map and one per bit). Internal to the loader; errors are
// hil::yaml::Failure (file, line, column, key path, what was expected).

#include "hil/config/yaml_field.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime::detail {

using yaml::Field;  // the one YAML-reading idiom (hil::config)

/// `modbus: {bus, unit, poll, timeout, stale_after, listen, status}`.
ModbusLinkDevice load_modbus_device(const Field& m);
/// An `inputs:` / `outputs:` value of a modbus link: {discrete_input: N} or {coil: N}.
ModbusLinkBit load_modbus_bit(const Field& f, bool input);

}  // namespace hil::runtime::detail
