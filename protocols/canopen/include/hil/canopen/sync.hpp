// SPDX-License-Identifier: MIT
#pragma once
// SYNC (CiA 301 §7.2.5): COB-ID 0x080, DLC 0, or DLC 1 with a counter 1..overflow when the
// synchronous counter overflow value (0x1019) is 2..240.

#include <cstdint>
#include <optional>

#include "hil/can/frame.hpp"
#include "hil/canopen/cob_id.hpp"
#include "hil/core/clock.hpp"

namespace hil::canopen {

struct SyncMessage {
  std::optional<std::uint8_t> counter;  ///< absent when DLC 0
};

[[nodiscard]] can::Frame make_sync(std::optional<std::uint8_t> counter = std::nullopt) noexcept;
/// Accepts 0x080 with DLC 0 or 1 (a counter of 0 is invalid and rejected); nullopt otherwise.
[[nodiscard]] std::optional<SyncMessage> parse_sync(const can::Frame& f, std::uint32_t cob_id = cob_sync) noexcept;

/// SYNC producer: period (0x1006, µs) and counter overflow (0x1019). step(now) emits SYNC frames
/// at now >= due, keeping the phase (due += period); missed periods are skipped, not burst.
class SyncProducer {
 public:
  explicit SyncProducer(FrameSink sink) : sink_(std::move(sink)) {}
  /// `overflow` 0 = no counter; 1 and 241..255 are reserved and treated as 0... per CiA 301
  /// only 2..240 enable the counter.
  void configure(Duration period, std::uint8_t overflow, TimePoint start) noexcept;
  /// Returns true when a SYNC was sent; `counter` (if used) is the value sent.
  bool step(TimePoint now);
  [[nodiscard]] Duration period() const noexcept { return period_; }
  [[nodiscard]] std::uint8_t last_counter() const noexcept { return counter_; }
  [[nodiscard]] TimePoint next_due() const noexcept { return next_; }

 private:
  FrameSink sink_;
  Duration period_{};
  std::uint8_t overflow_ = 0;
  std::uint8_t counter_ = 0;
  TimePoint next_{};
};

}  // namespace hil::canopen
