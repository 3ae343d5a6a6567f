// SPDX-License-Identifier: MIT
#pragma once
// Escaping text for XML attributes and character data (SVG plot, JUnit report).

#include <string>
#include <string_view>

namespace hil::runtime {

/// Escapes & < > " ' and drops control characters XML 1.0 does not allow.
[[nodiscard]] std::string xml_escape(std::string_view text);

}  // namespace hil::runtime
