// SPDX-License-Identifier: MIT
#pragma once
// A parameter's value: one entry per field of its template (CLM "03000 10.0" has two fields,
// a WF 725/726 machine datum one).

#include <string>
#include <variant>
#include <vector>

#include "hil/profiles/decimal.hpp"

namespace hil::profiles {

/// A number (numeric, choice, bits, hex fields) or a text (I/O address "I1.00.0", reserved text).
using FieldValue = std::variant<Decimal, std::string>;
using ParamValue = std::vector<FieldValue>;

[[nodiscard]] inline std::string to_string(const FieldValue& v) {
  if (const auto* d = std::get_if<Decimal>(&v)) return d->to_string();
  return std::get<std::string>(v);
}

}  // namespace hil::profiles
