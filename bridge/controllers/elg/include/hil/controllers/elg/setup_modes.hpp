// SPDX-License-Identifier: MIT
#pragma once
// The setting-up modes of the drive axis C with the coupling OFF (manual ch. 7; digest §4.4):
// JOG at MD 288* (rapid MD 292*), INC steps of n * 2 MS at MD 300*, REF at MD 296* to the
// deceleration cam and at MD 284* behind it to the zero mark, where the actual value becomes
// MD 240*. All speeds scaled by the 16-position feed override (MD 100-114, position 1 = 0 % =
// hard stop). Pure and clock-free: the gearbox steps it once per ELG cycle with the machine
// control panel signals and C's actual value, and applies the command it returns.
//
// Refusals, with the manual's reaction (docs/elg.md, "Setting-up modes"):
// - while coupled, JOG/INC/REF are not available (4.1): the keys are ignored, no alarm;
// - a REF key in the wrong direction is not accepted and no motion starts (7.3);
// - a set speed above MD 280* raises 2035 "PROGRAM SPEED TOO HIGH" and C does not traverse;
// - a reference approach that stops between the cam and the zero mark raises 184*.
// [I] decisions: the mode-switch codes, the zero-mark spacing, the override's action on REF.

#include <array>
#include <cstdint>
#include <optional>

#include "hil/controllers/elg/alarm.hpp"

namespace hil::controllers::elg {

/// [I] Mode-switch code in the upper half of marker byte M n (12.4.3; the manual gives no codes).
enum class PanelMode : std::uint8_t { automatic = 0, jog = 1, inc = 2, ref = 3 };

/// The machine control panel as the PC passes it to the ELG (12.4.3), sampled once per cycle.
struct PanelSignals {
  PanelMode mode = PanelMode::automatic;
  int override_position = 1;    ///< feed override switch 1..16 (1 = 0 %)
  std::int64_t inc_factor = 1;  ///< INC selector: increments per key press (1, 10, 100, 1000, 10000)
  bool key_plus = false;        ///< direction key + (item 23)
  bool key_minus = false;       ///< direction key - (item 22)
  bool rapid = false;           ///< rapid traverse key (item 24)
  bool rapid_override = false;  ///< "rapid traverse override active" (item 25): override acts on rapid/REF
  bool ref_cam = false;         ///< deceleration cam of C actuated (the manual's low-active *Deceleration A69.5)
};

/// Machine data of the drive axis C for the setting-up modes (12.1). Speeds in 1000 units/min,
/// 1 unit = 2 MS = 2 counts; positions in MS units (counts).
struct SetupMachineData {
  std::int64_t jog_speed = 2000;        ///< MD 288*
  std::int64_t rapid_speed = 10000;     ///< MD 292*
  std::int64_t ref_speed = 10000;       ///< MD 296*
  std::int64_t ref_cutoff_speed = 300;  ///< MD 284* (behind the cam)
  std::int64_t inc_speed = 500;         ///< MD 300*
  std::int64_t max_speed = 10000;       ///< MD 280* (alarm 2035)
  std::int64_t ref_coordinate = 0;      ///< MD 240*, MS units
  bool ref_minus = false;               ///< MD 564* bit 0: reference point in minus direction
  /// MD 100-114: override % of positions 2..16; position 1 is 0 % (hard stop).
  std::array<std::int64_t, 15> override_percent{1, 2, 4, 6, 8, 10, 20, 40, 60, 70, 80, 90, 100, 110, 120};
  /// [I] Counts between two zero marks of C's encoder (default: one per revolution, 4 * MD 396*).
  std::int64_t zero_mark_counts = 720000;
  int axis_index = 1;  ///< C's axis number - 1 (the "*" of alarm 184*)
};

enum class SetupState : std::uint8_t { idle, jogging, incrementing, ref_to_cam, ref_to_zero_mark };

/// What the setting-up modes demand of C this cycle.
struct SetupCommand {
  enum class Kind : std::uint8_t { none, velocity, position };
  Kind kind = Kind::none;
  std::int64_t target = 0;           ///< position: C's target, counts
  double velocity_counts_per_s = 0;  ///< velocity: signed speed; position: speed limit (0 = stand)
};

/// Speed in counts/s of an MD speed in 1000 units/min at `percent` override (1 unit = 2 counts).
constexpr double md_speed_counts_per_s(std::int64_t md, std::int64_t percent) noexcept {
  return static_cast<double>(md) * 1000.0 * 2.0 / 60.0 * static_cast<double>(percent) / 100.0;
}

class SetupModes {
 public:
  explicit SetupModes(SetupMachineData md = {}) : md_(md) {}

  /// One cycle. `c_set` is C's set value (actual + following error), `c_actual` its actual value,
  /// `c_in_position` whether C's last move has ended; `blocked` holds every motion (coupled, an
  /// index running, the STOP reaction); `coupled` alone makes a key press a refusal. Raises at
  /// most one alarm per cycle (returned). Never throws.
  std::optional<Alarm> step(const PanelSignals& panel, std::int64_t c_set, std::int64_t c_actual, bool c_in_position,
                            bool coupled, bool blocked);
  /// ELG-RESET / EMERGENCY OFF: any motion ends without an alarm.
  void abort() noexcept;

  [[nodiscard]] SetupState state() const noexcept { return state_; }
  [[nodiscard]] const SetupCommand& command() const noexcept { return command_; }
  /// A setting-up motion is under way (Gearing ON then fails its approach condition: 2207).
  [[nodiscard]] bool moving() const noexcept { return state_ != SetupState::idle; }
  /// E69..E72 bit 1 "Reference point reached" of C.
  [[nodiscard]] bool referenced() const noexcept { return referenced_; }
  /// ELG actual value of C = counts + offset (MD 240* at the zero mark once referenced, else 0).
  [[nodiscard]] std::int64_t offset() const noexcept { return offset_; }
  /// Key presses refused (coupled, wrong REF direction): the manual's "not available".
  [[nodiscard]] int refusals() const noexcept { return refusals_; }
  /// The override in % of a switch position 1..16 (out of range: 0 %).
  [[nodiscard]] std::int64_t override_percent(int position) const noexcept;
  [[nodiscard]] const SetupMachineData& machine_data() const noexcept { return md_; }

 private:
  std::optional<Alarm> start(const PanelSignals& p, std::int64_t c_set, int direction);
  std::optional<Alarm> run_ref(const PanelSignals& p, std::int64_t c_actual);

  SetupMachineData md_;
  SetupState state_ = SetupState::idle;
  SetupCommand command_;
  PanelSignals last_{};
  int direction_ = 0;
  std::int64_t last_actual_ = 0;
  bool referenced_ = false;
  std::int64_t offset_ = 0;
  int refusals_ = 0;
};

}  // namespace hil::controllers::elg
