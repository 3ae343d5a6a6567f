// SPDX-License-Identifier: MIT
#pragma once
// The ELG's operating modes as one step function (manual ch. 3-7; digest §3-§5): compute gearing
// constants, Gearing ON/OFF, single pitch (EZT) with its tooth counter, semi-automatic centring
// (HAE), following-error monitoring with alarm 2215, and the alarm/reset rules. Pure and
// clock-free: the caller steps it once per ELG cycle with the interface signals and the axes'
// actual values in encoder counts (x4), and applies the C command it returns.
//
// Decisions where the manual is silent (digest §12, docs/elg.md), each an option below:
// - Compute, Gearing ON, Transfer actual value and the index keys act on rising edges; Gearing OFF
//   acts on its level and wins over ON (safe side).
// - "Gearing constant computed" (E66.6) stays set until an input parameter changes.
// - The approach condition of Gearing ON is |C following error| <= MD 166.
// - A following error exactly equal to the limit keeps the contact closed.
// - Single-pitch indexes land on a grid counted from EZT selection (index_on_grid).
// - Gearing ON while a JOG/INC/REF motion of C runs fails the approach condition: 2207.

#include <cstdint>
#include <optional>
#include <vector>

#include "hil/controllers/elg/alarm.hpp"
#include "hil/controllers/elg/gear.hpp"
#include "hil/controllers/elg/setup_modes.hpp"

namespace hil::controllers::elg {

/// Interface signals from the PC to the ELG (12.4.2), sampled once per cycle as levels.
struct Signals {
  bool compute = false;          ///< A67.7 "Compute gearing constants"
  bool gearing_on = false;       ///< A67.5
  bool gearing_off = false;      ///< A67.6
  bool single_pitch = false;     ///< A67.4 EZT
  bool hae = false;              ///< A67.3 semi-automatic centring
  bool transfer_actual = false;  ///< A67.2 "Transfer actual value"
  bool fe_monitor = false;       ///< A67.1 "Following error monitoring active"
  bool reset = false;            ///< ELG-RESET
  bool emergency_off = false;    ///< EMERGENCY OFF from the PC
  bool index_plus = false;       ///< direction key + (or the M function mapped to it, e.g. M56)
  bool index_minus = false;      ///< direction key -
  bool inc_plus = false;         ///< INC key + (HAE offset motion while coupled)
  bool inc_minus = false;        ///< INC key -
  bool data_start = false;       ///< V.24 Data Start
  PanelSignals panel;            ///< machine control panel: JOG/INC/REF of C (setup_modes.hpp)
};

/// Actual values of the axes in encoder counts (quadrupled) and C's following error.
struct AxisFeedback {
  std::int64_t b = 0;
  std::int64_t z = 0;
  std::int64_t y = 0;
  std::int64_t c = 0;
  std::int64_t c_following_error = 0;  ///< set value - actual value of C, counts (= MS units)
  bool c_in_position = true;           ///< C's move has ended (standing within MD 204* of its target)
};

/// Options and machine data of the gearbox (MD 166, 169, 170, 300*, the INC selector, cycle).
struct GearboxConfig {
  GearMachineData md;
  std::int64_t gearing_on_tolerance = 100;  ///< MD 166, MS units (approach condition)
  std::int64_t fe_tolerance_min = 20;       ///< MD 169, MS units
  std::int64_t inc_increments = 1000;       ///< INC selector position: dS = n * 2 MS
  double cycle_s = 0.002;                   ///< ELG cycle (position controller cycle)
  std::int64_t max_partial_counts = 0;      ///< C set value change per cycle that is the limit
                                            ///< (2205); 0 = no limit. 2206 warns at 90 %.
  bool clear_computed_on_parameter_change = true;
  /// [I] Single-pitch indexes land on the grid start + k * pitch counted from EZT selection (true),
  /// or move one pitch from wherever C stands (false: the manual's literal "moves C by one pitch").
  bool index_on_grid = true;
  SetupMachineData setup;  ///< MD 100-114, 240*, 280*-300*, 564* of C (JOG/INC/REF)
};

enum class CMode : std::uint8_t {
  hold,      ///< no motion demanded by the ELG (C holds or is moved by its own modes)
  follow,    ///< coupled: C follows `c_set` every cycle
  position,  ///< single-pitch index: move C to `c_set` (positioning at the jog speed)
  stop,      ///< STOP reaction: set value 0, C stops
  velocity,  ///< JOG / REF: C traverses at `c_velocity` counts/s (0: stands)
};

enum class HaeState : std::uint8_t { idle, approach, one_point, centring, gap_reached };

/// Outputs to the PC (12.4.1) and the C command.
struct GearboxStatus {
  bool computed = false;                  ///< E66.6 "Gearing constant computed"
  bool coupled = false;                   ///< E66.7 "Coupling ON"
  bool tooth_gap_reached = false;         ///< E66.3
  bool actual_value_transferred = false;  ///< E68.4
  bool alarm = false;                     ///< E65.5 "ELG alarm"
  bool contact_closed = true;             ///< FE relay contact (MD 5022): opens with 2215
  std::int32_t tooth = 0;                 ///< TOOTH NO. while EZT is selected (1..Z2), else 0
  HaeState hae = HaeState::idle;
  CMode c_mode = CMode::hold;
  std::int64_t c_set = 0;     ///< C set value / target, counts
  std::int64_t fe_limit = 0;  ///< max(MD 169, R40)
  /// velocity: C's speed (counts/s, signed); position: the speed limit (counts/s, 0 = the machine's
  /// index speed for a single-pitch index; a setting-up INC step at 0 % override also gives 0 and
  /// C stands until the override rises: `setup_step` tells the two apart).
  double c_velocity = 0.0;
  bool setup_step = false;    ///< position: the move is an INC step (else a single-pitch index)
  bool referenced = false;    ///< C's "Reference point reached" (E69..E72 bit 1)
  std::int64_t c_offset = 0;  ///< ELG actual value of C = counts + c_offset (MD 240* after REF)
};

class Gearbox {
 public:
  explicit Gearbox(GearboxConfig config);

  /// Input parameters (R20, R21, R60, R61) as transferred from the NC (5.1). Rejected (false)
  /// while coupled, as the manual forbids changing them then.
  bool set_input(const GearInput& input);
  /// TOLER (R40): accepted even while coupled; a value below MD 169 is not accepted and the last
  /// valid limit stays (5.2). Returns whether it was accepted.
  bool set_tolerance(std::int64_t r40);

  /// One ELG cycle. Never throws.
  const GearboxStatus& step(const Signals& signals, const AxisFeedback& axes);

  /// An alarm of another ELG function that is a message only (the PC data channel's 3016/3018):
  /// latched like the others, cleared by RESET with the coupling OFF.
  void raise_message(Alarm alarm) { raise(alarm); }

  /// POWER ON RESET: clears every alarm including 2200, uncouples, forgets the constants.
  void power_on_reset();

  const GearboxStatus& status() const noexcept { return status_; }
  /// Latched alarms, in the order raised.
  const std::vector<Alarm>& alarms() const noexcept { return alarms_; }
  bool has_alarm(Alarm alarm) const noexcept;
  const GearInput& input() const noexcept { return input_; }
  const std::optional<GearConstants>& constants() const noexcept { return constants_; }
  const SetupModes& setup() const noexcept { return setup_; }
  const GearboxConfig& config() const noexcept { return config_; }

 private:
  void raise(Alarm alarm);
  void on_compute();
  void engage(const AxisFeedback& axes, bool single_pitch);
  void disengage();
  void run_coupled(const Signals& signals, const AxisFeedback& axes);
  void run_indexing(const Signals& signals, const AxisFeedback& axes);
  void run_hae(const Signals& signals, const AxisFeedback& axes);
  void run_setup(const Signals& signals, const AxisFeedback& axes);
  void monitor_following_error(const Signals& signals, const AxisFeedback& axes);

  GearboxConfig config_;
  GearInput input_;
  std::optional<GearConstants> constants_;
  std::int64_t r40_ = 0;
  Linkage linkage_;
  Signals last_{};
  GearboxStatus status_;
  std::vector<Alarm> alarms_;
  bool stopped_ = false;

  // Single pitch: indexes done since EZT was selected, and the C position they count from.
  std::int64_t index_count_ = 0;
  std::int64_t index_base_ = 0;
  bool indexing_ = false;
  bool ezt_base_valid_ = false;

  // HAE: superimposed offset on the coupled C set value (counts), its target and the flanks.
  double hae_offset_ = 0.0;
  std::int64_t hae_target_ = 0;
  std::int64_t p1_ = 0;
  std::int64_t last_partial_ = 0;
  std::int64_t last_c_set_ = 0;

  SetupModes setup_;
  bool setup_moved_c_ = false;  ///< C's set value is its own since a setting-up motion
};

}  // namespace hil::controllers::elg
