// SPDX-License-Identifier: MIT
#include "hil/runtime/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace hil::runtime {

void LatencyHistogram::add(Duration d) noexcept {
  if (d < Duration::zero()) d = Duration::zero();
  const auto idx = static_cast<std::size_t>(d / bucket_width);
  ++buckets_[std::min(idx, bucket_count)];
  if (count_ == 0 || d < min_) min_ = d;
  if (count_ == 0 || d > max_) max_ = d;
  ++count_;
  sum_ += d;
}

void LatencyHistogram::clear() noexcept {
  *this = LatencyHistogram{};
}

Duration LatencyHistogram::mean() const noexcept {
  return count_ ? Duration{sum_.count() / static_cast<Duration::rep>(count_)} : Duration{};
}

Duration LatencyHistogram::percentile(double fraction) const noexcept {
  if (count_ == 0) return Duration{};
  fraction = std::clamp(fraction, 0.0, 1.0);
  const auto wanted =
      std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(fraction * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i <= bucket_count; ++i) {
    seen += buckets_[i];
    if (seen >= wanted) {
      if (i == bucket_count) return max_;
      // Upper edge of the bucket, clamped to the exact extremes.
      const Duration edge = bucket_width * static_cast<Duration::rep>(i + 1);
      return std::clamp(edge, min_, max_);
    }
  }
  return max_;
}

std::uint64_t LatencyHistogram::count_between(Duration lo, Duration hi) const noexcept {
  const auto index = [](Duration d) {
    if (d <= Duration::zero()) return std::size_t{0};
    return static_cast<std::size_t>(std::min<Duration::rep>(d / bucket_width, bucket_count + 1));
  };
  std::uint64_t n = 0;
  for (std::size_t i = index(lo), end = index(hi); i < end && i <= bucket_count; ++i) n += buckets_[i];
  return n;
}

}  // namespace hil::runtime
