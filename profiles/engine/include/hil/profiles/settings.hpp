// SPDX-License-Identifier: MIT
#pragma once
// Settings given by the user for a profile (module variant, resolution when not derivable, tape
// options, …): names per Profile::settings.

#include <functional>
#include <map>
#include <string>

#include "hil/profiles/expression.hpp"

namespace hil::profiles {

using Settings = std::map<std::string, ExprValue, std::less<>>;

}  // namespace hil::profiles
