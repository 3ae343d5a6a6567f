// SPDX-License-Identifier: MIT
#pragma once
// Device errors at run time: an error of the device's own catalogue (profiles/devices/*/
// errors.yaml through hil::profiles::ErrorCatalogue) with the device's number and text, its
// reaction class and the rule that clears it. A controller raises them from its own logic and,
// through Controller::map_axis_fault, for the motion core's supervision faults (a WF 725/726
// software-limit stop is WF 95/96, not motion:5).
//
// DeviceErrorLatch is the error state machine: raise() latches, acknowledge() clears what the
// given acknowledgement may clear, clear() drops a self-clearing error whose cause went away.
// Every error raised stays in history() for the run's summary, JUnit report and --json.
// Thread: the cycle thread; noexcept members never throw (they may allocate for the text).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "hil/core/clock.hpp"
#include "hil/core/fault.hpp"
#include "hil/profiles/catalogue.hpp"

namespace hil::controllers {

/// What clears an error. Ordered by strength: an acknowledgement clears every error whose rule
/// is at or below it (a reset also clears what an acknowledge would; a power cycle clears all).
enum class AckRule : std::uint8_t {
  self_clearing,  ///< messages: cleared by the device when the cause goes or by the next valid job
  acknowledge,    ///< the device's acknowledge: CLM Clear key / External Clear edge / !CLEAR,
                  ///< WF data code 800C, IP247 next operating command / BA17
  reset,          ///< a reset: WF RESET bit / module restart, ELG-RESET, CLM needs-reset errors
  power_cycle,    ///< only a power cycle (CLM system failure, IP247 hardware fault)
};
[[nodiscard]] std::string_view to_string(AckRule r) noexcept;

/// How an acknowledgement was given (the device maps its keys, bits and commands onto these).
enum class Acknowledgement : std::uint8_t { acknowledge, reset, power_cycle };

/// The rule for a catalogue entry, read from its reaction and acknowledge text: reaction
/// needs_reset -> reset, "power cycle"/"POWER ON RESET only" -> power_cycle, "Self-..."/"Nothing
/// to acknowledge"/"Warning/information" -> self_clearing, anything else -> acknowledge. A
/// device whose texts say otherwise passes its own rule to make_device_error().
[[nodiscard]] AckRule ack_rule_for(const profiles::ErrorEntry& entry) noexcept;

struct DeviceError {
  const profiles::ErrorCatalogue* catalogue = nullptr;  ///< lives as long as its profile
  int code = 0;                                         ///< the device's number (value of fault.code)
  hil::Fault fault;  ///< code in the catalogue's category; text "<catalogue text>: <cause> (<context>)"
  profiles::Reaction reaction = profiles::Reaction::stop;
  AckRule ack = AckRule::acknowledge;
  int axis = -1;          ///< controller axis index it concerns, -1 for the whole device
  std::error_code cause;  ///< the motion-core fault behind it (motion:5), empty for device logic
  TimePoint raised_at{};  ///< controller cycle time it was raised at

  /// As the manual writes the number: "95", "4C", "28" (catalogue code_format).
  [[nodiscard]] std::string code_text() const;
  /// "wf725-726.traversing 96 Pre-limit switch positive (MD 13): ... (axis X)".
  [[nodiscard]] std::string describe() const;
  /// Same device error (catalogue, number, axis).
  [[nodiscard]] bool same(const DeviceError& other) const noexcept {
    return catalogue == other.catalogue && code == other.code && axis == other.axis;
  }
};

/// A device error for `code` of `catalogue`: text, reaction and rule from the catalogue entry
/// (`ack` overrides the rule). A code missing from the catalogue still gives an error (reaction
/// stop, rule acknowledge, text "unknown <catalogue> code N"), so a run never loses a fault.
[[nodiscard]] DeviceError make_device_error(const profiles::ErrorCatalogue& catalogue, int code, TimePoint now,
                                            int axis = -1, std::string_view context = {},
                                            std::optional<AckRule> ack = {});

class DeviceErrorLatch {
 public:
  /// Latches `e` unless the same error is already active (then nothing changes). Returns true
  /// when it was newly latched.
  bool raise(DeviceError e) noexcept;
  /// Clears every active error whose rule is at or below `how`; returns how many were cleared.
  std::size_t acknowledge(Acknowledgement how) noexcept;
  /// Drops an active self-clearing error (the device saw its cause go). Others stay latched.
  bool clear(const profiles::ErrorCatalogue& catalogue, int code, int axis = -1) noexcept;

  [[nodiscard]] std::span<const DeviceError> active() const noexcept { return active_; }
  /// Every error latched since construction, in order (for reports).
  [[nodiscard]] std::span<const DeviceError> history() const noexcept { return history_; }
  [[nodiscard]] bool any() const noexcept { return !active_.empty(); }
  /// An active error with reaction stop, drive_off or needs_reset (motion is inhibited).
  [[nodiscard]] bool blocks_motion() const noexcept;
  /// Same, for axis `axis` (its own errors and the device-wide ones).
  [[nodiscard]] bool blocks_motion(int axis) const noexcept;

 private:
  std::vector<DeviceError> active_;
  std::vector<DeviceError> history_;
};

}  // namespace hil::controllers
