// SPDX-License-Identifier: MIT
#pragma once
// The controller entries of `expect:` ({controller: NAME, value: V} and {device_error: CODE}),
// loaded apart from the rest of the scenario loader. Internal to the loader; errors are
// hil::yaml::Failure (file, line, column, key path, what was expected).

#include "hil/config/yaml_field.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime::detail {

/// One `expect:` entry holding `controller:` or `device_error:`.
ControllerExpectation load_controller_expectation(const yaml::Field& f);

/// An expected value as written: a number (`-87654321.654321`), or an integer in hex (`0x73`) or
/// binary (`0b01110011`, `_` allowed between digits). nullopt when it is none of these.
std::optional<double> parse_expected_value(std::string_view text);

}  // namespace hil::runtime::detail
