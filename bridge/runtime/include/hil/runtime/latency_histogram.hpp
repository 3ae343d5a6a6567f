// SPDX-License-Identifier: MIT
#pragma once
// Wake-up latency statistics of the real-time cycle scheduler: min, max, mean and percentiles
// from a fixed-size histogram (1 µs buckets up to 20 ms, exact min/max), so recording never
// allocates on the cyclic path.

#include <array>
#include <cstdint>

#include "hil/core/clock.hpp"

namespace hil::runtime {

class LatencyHistogram {
 public:
  static constexpr Duration bucket_width = std::chrono::microseconds(1);
  static constexpr std::size_t bucket_count = 20'000;  ///< 0..20 ms; later samples go to the overflow bucket

  /// Record one sample. Negative values count as 0. Cyclic path: O(1), no allocation, never throws.
  void add(Duration d) noexcept;
  void clear() noexcept;

  [[nodiscard]] std::uint64_t count() const noexcept { return count_; }
  [[nodiscard]] Duration min() const noexcept { return count_ ? min_ : Duration{}; }
  [[nodiscard]] Duration max() const noexcept { return count_ ? max_ : Duration{}; }
  [[nodiscard]] Duration mean() const noexcept;
  /// The smallest bucket upper edge below which `fraction` (0..1) of the samples lie, clamped to
  /// [min, max]; exact to one bucket (1 µs). 0 when empty.
  [[nodiscard]] Duration percentile(double fraction) const noexcept;
  /// Samples in [lo, hi) at bucket resolution (lo and hi are rounded down to a bucket edge);
  /// samples of 20 ms and more count in [20 ms, hi) when hi is beyond it.
  [[nodiscard]] std::uint64_t count_between(Duration lo, Duration hi) const noexcept;

 private:
  std::array<std::uint32_t, bucket_count + 1> buckets_{};
  std::uint64_t count_ = 0;
  Duration sum_{};
  Duration min_{};
  Duration max_{};
};

}  // namespace hil::runtime
