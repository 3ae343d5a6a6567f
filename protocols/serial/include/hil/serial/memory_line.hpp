// SPDX-License-Identifier: MIT
#pragma once
// In-process line: two connected RawLine ends, for tests and virtual-time runs. With a
// VirtualClock, a read that finds nothing advances the clock by its timeout instead of
// waiting (the other end is driven on the same thread); without one, it waits on a condition
// variable (the other end runs on another thread). A per-direction filter injects faults.

#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "hil/serial/byte_stream.hpp"

namespace hil::serial {

/// Called with the bytes of every write before they reach the other end; may change, drop or
/// add bytes (noise, lost characters, parity flips).
using LineFilter = std::function<void(std::vector<std::uint8_t>&)>;

struct MemoryLinePair {
  std::unique_ptr<RawLine> a;
  std::unique_ptr<RawLine> b;
  /// Fault injection: applied to bytes travelling a->b / b->a. Set before use; not thread-safe.
  std::shared_ptr<LineFilter> a_to_b;
  std::shared_ptr<LineFilter> b_to_a;
};

/// `vclock` may be null (real waiting). With a VirtualClock both ends must be used by one thread.
[[nodiscard]] MemoryLinePair make_memory_line(VirtualClock* vclock = nullptr);

}  // namespace hil::serial
