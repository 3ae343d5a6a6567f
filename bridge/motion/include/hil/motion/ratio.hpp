// SPDX-License-Identifier: MIT
#pragma once
// Exact rational scaling between user units and drive increments.

#include <cstdint>

namespace hil::motion {

/// Drive increments per user unit = num / den, exactly (e.g. 4096 inc per 5 mm lead -> {4096, 5}).
/// Both must be > 0; the ratio is kept as given (reduced internally by the Scaling).
struct Ratio {
  std::int64_t num = 1;
  std::int64_t den = 1;
};

}  // namespace hil::motion
