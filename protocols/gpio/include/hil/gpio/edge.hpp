// SPDX-License-Identifier: MIT
#pragma once
// One timestamped level change on one line of a line bank: the unit of a step/dir schedule,
// of a mock's recording and of the real-line writer's input.

#include <cstdint>

namespace hil::gpio {

struct Edge {
  std::int64_t t_ns = 0;   ///< when, in ns on the run's hil::Clock timeline
  std::uint16_t line = 0;  ///< index into the output bank (not a chip offset)
  bool level = false;      ///< logical level after the edge (active-low is applied by the backend)

  friend bool operator==(const Edge&, const Edge&) = default;
};

}  // namespace hil::gpio
