// SPDX-License-Identifier: MIT
#pragma once
// Where a drive sends a planned batch of edges: the mock records them at their timestamps
// (virtual time), the real-line writer outputs them on time on its own thread.

#include <span>

#include "hil/gpio/edge.hpp"

namespace hil::gpio {

class EdgeSink {
 public:
  virtual ~EdgeSink() = default;
  /// Take a time-ordered batch. Motion thread; non-blocking; never throws.
  virtual void output(std::span<const Edge> edges) noexcept = 0;
};

}  // namespace hil::gpio
