// SPDX-License-Identifier: MIT
#pragma once
// The `plc:` step of a scenario (docs/scenarios.md "PLC steps"), loaded apart from the rest of the
// scenario loader. Internal to the loader; errors are hil::yaml::Failure (file, line, column, key
// path, what was expected).

#include <string>

#include "hil/config/yaml_field.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime::detail {

/// The value of a `plc:` step: `{write|wait|expect: {db, dw, value|dd|dl|dr|bit [, state]}}`.
/// `name` gets the step's short text ("plc write DB10 DW4").
PlcStep load_plc_step(const yaml::Field& v, std::string& name);

}  // namespace hil::runtime::detail
