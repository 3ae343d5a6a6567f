// SPDX-License-Identifier: MIT
#pragma once
// Emergency objects (CiA 301 §7.2.7): COB-ID 0x080+id, 8 bytes
// [error code LE16, error register (0x1001), 5 manufacturer-specific bytes]. Error code 0x0000
// is "error reset / no error".

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string_view>

#include "hil/can/frame.hpp"
#include "hil/canopen/cob_id.hpp"
#include "hil/core/clock.hpp"

namespace hil::canopen {

/// Error register bits (object 0x1001, CiA 301 §7.5.2.2).
namespace error_register {
inline constexpr std::uint8_t generic = 0x01;
inline constexpr std::uint8_t current = 0x02;
inline constexpr std::uint8_t voltage = 0x04;
inline constexpr std::uint8_t temperature = 0x08;
inline constexpr std::uint8_t communication = 0x10;
inline constexpr std::uint8_t device_profile = 0x20;
inline constexpr std::uint8_t manufacturer = 0x80;
}  // namespace error_register

/// A few CiA 301 emergency error codes the stack itself raises.
namespace emcy_code {
inline constexpr std::uint16_t error_reset = 0x0000;
inline constexpr std::uint16_t can_overrun = 0x8110;
inline constexpr std::uint16_t heartbeat = 0x8130;   ///< life guard or heartbeat error
inline constexpr std::uint16_t pdo_length = 0x8210;  ///< PDO not processed due to length error
inline constexpr std::uint16_t pdo_length_exceeded = 0x8220;
inline constexpr std::uint16_t rpdo_timeout = 0x8250;
}  // namespace emcy_code

struct EmcyMessage {
  NodeId node = 0;
  std::uint16_t code = 0;
  std::uint8_t error_register = 0;
  std::array<std::uint8_t, 5> manufacturer{};
  friend bool operator==(const EmcyMessage&, const EmcyMessage&) = default;
};

[[nodiscard]] can::Frame make_emcy(const EmcyMessage& m) noexcept;
/// A data frame on 0x081..0x0FF with DLC 8. Shorter frames are rejected (CiA 301 fixes DLC 8).
[[nodiscard]] std::optional<EmcyMessage> parse_emcy(const can::Frame& f) noexcept;

/// EMCY producer with inhibit time (0x1015, multiples of 100 µs): messages raised inside the
/// inhibit window are queued (bounded, oldest kept) and sent by step().
class EmcyProducer {
 public:
  EmcyProducer(NodeId node, FrameSink sink) : node_(node), sink_(std::move(sink)) {}
  void set_inhibit(Duration inhibit) noexcept { inhibit_ = inhibit; }
  void set_muted(bool muted) noexcept { muted_ = muted; }
  void raise(std::uint16_t code, std::uint8_t error_register, std::array<std::uint8_t, 5> mfr, TimePoint now);
  void step(TimePoint now);
  [[nodiscard]] std::size_t pending() const noexcept { return queue_.size(); }

 private:
  NodeId node_;
  FrameSink sink_;
  Duration inhibit_{};
  std::optional<TimePoint> last_{};
  std::deque<EmcyMessage> queue_;
  bool muted_ = false;
};

}  // namespace hil::canopen
