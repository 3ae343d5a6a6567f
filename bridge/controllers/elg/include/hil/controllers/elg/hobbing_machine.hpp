// SPDX-License-Identifier: MIT
#pragma once
// A gear-hobbing machine on the motion core: the System 3 NC program (NcInterpreter) moves the
// feed axes X, Z (and Y) and the hob spindle B, its M functions reach the ELG through the PC
// interface, and the ELG (Gearbox) commands the workpiece table C: cyclically while coupled
// (motion::Axis::follow), as a positioning move for a single-pitch index.
//
// Axis increments are the ELG's measuring-system counts: C and B count 4*MD 396* per revolution,
// Z/Y count one MS unit (MD 5002, e.g. 0.5 um) per increment. The caller builds the axes with
// those scalings (see hobbing_axis_config()), steps the axes, then calls step() once per ELG cycle.
// Thread: the cycle thread; step() never throws.

#include <cstdint>
#include <optional>
#include <string>

#include "hil/controllers/elg/gearbox.hpp"
#include "hil/controllers/elg/nc_interpreter.hpp"
#include "hil/controllers/elg/pc_interface.hpp"
#include "hil/controllers/elg/ssfk.hpp"
#include "hil/core/clock.hpp"
#include "hil/motion/axis.hpp"

namespace hil::controllers::elg {

struct HobbingAxes {
  motion::Axis* b = nullptr;  ///< hob spindle (guide axis), degrees
  motion::Axis* c = nullptr;  ///< workpiece table (drive axis), degrees
  motion::Axis* z = nullptr;  ///< axial feed, mm
  motion::Axis* x = nullptr;  ///< radial infeed, mm (optional)
  motion::Axis* y = nullptr;  ///< tangential shift, mm (optional)
};

struct HobbingConfig {
  GearboxConfig gearbox;
  MFunctionMap m_functions = default_m_functions();
  /// NC R parameters transferred to the ELG input parameters on every change while uncoupled
  /// (5.1; the manual's example keeps ud_z/ud_y in R12/R13 and maps them onto R61/R60).
  int r_z0 = 20, r_z2 = 21, r_ud_z = 12, r_ud_y = 13, r_toler = 40;
  double rapid_mm_per_s = 50.0;       ///< G0 speed of X/Y/Z
  double index_speed_deg_per_s = 30;  ///< C speed of a single-pitch index
  SsfkData ssfk;                      ///< C's SSFK (ssfk.hpp): added to C's position commands once referenced
};

/// Axis configuration helpers: increments per unit for the ELG's counts.
motion::Ratio rotary_counts_per_degree(std::int64_t pulses_per_rev) noexcept;  ///< 4 N / 360
motion::Ratio linear_counts_per_mm(std::int64_t ms_nm) noexcept;               ///< 1e6 / ms

class HobbingMachine final : public NcMachine {
 public:
  HobbingMachine(NcProgram program, HobbingConfig config, HobbingAxes axes);

  /// NC start (cycle start): the program runs from the next step(). The axes must be enabled.
  void start() noexcept { started_ = true; }
  /// One ELG cycle after the axes' update(): NC (once started), PC interface, ELG, C command.
  void step(const hil::CycleTime& cycle) noexcept;

  [[nodiscard]] const Gearbox& gearbox() const noexcept { return gearbox_; }
  /// The gearbox itself, for the ELG's other interfaces (PC data channel, V.24: 2214).
  [[nodiscard]] Gearbox& gearbox() noexcept { return gearbox_; }
  [[nodiscard]] const NcInterpreter& nc() const noexcept { return nc_; }
  [[nodiscard]] const PcInterface& pc() const noexcept { return pc_; }
  /// The PC's signals the NC does not drive (FE monitoring, RESET): set before step().
  Signals& pc_signals() noexcept { return pc_.signals(); }
  /// Gaps cut so far (Gearing ON events).
  [[nodiscard]] int couplings() const noexcept { return couplings_; }
  /// The ELG's C set value and its deviation from the linkage equation evaluated in degrees on
  /// the actual B/Z/Y values (counts; the plot's "C error against the ideal linkage").
  [[nodiscard]] std::int64_t c_set() const noexcept { return gearbox_.status().c_set; }
  [[nodiscard]] double linkage_error_counts() const noexcept { return linkage_error_; }
  [[nodiscard]] double worst_linkage_error_counts() const noexcept { return worst_linkage_error_; }
  /// C's actual position against the linkage equation on the actual B/Z/Y values, in degrees
  /// (the ELG's set-value error plus C's following error); 0 while uncoupled.
  [[nodiscard]] double c_linkage_error_deg() const noexcept { return c_linkage_error_deg_; }
  [[nodiscard]] const std::string& error() const noexcept { return error_; }
  /// The SSFK compensation (counts) in C's last command; 0 when SSFK is off or C not referenced.
  [[nodiscard]] std::int64_t ssfk_compensation() const noexcept { return ssfk_comp_; }

  // NcMachine
  void move(const NcTargets& targets, bool rapid, double feed_mm_per_s) override;
  [[nodiscard]] bool in_position() const override;
  [[nodiscard]] NcTargets position() const override;
  void spindle(double rpm, int direction) override;
  void m_function(int m) override;

 private:
  void transfer_parameters();
  void command_c();

  HobbingConfig config_;
  HobbingAxes axes_;
  NcInterpreter nc_;
  PcInterface pc_;
  Gearbox gearbox_;
  bool started_ = false;
  bool was_coupled_ = false;
  int couplings_ = 0;
  bool indexing_ = false;
  Ssfk ssfk_;
  std::int64_t ssfk_comp_ = 0;
  int ssfk_direction_ = 1;
  bool setup_motion_ = false;  ///< a JOG/INC/REF command was issued to C
  double issued_velocity_ = 0.0;
  std::int64_t issued_target_ = 0;
  std::int64_t latched_b_ = 0, latched_z_ = 0, latched_y_ = 0, latched_c_ = 0;
  double linkage_error_ = 0.0, worst_linkage_error_ = 0.0, c_linkage_error_deg_ = 0.0;
  double now_s_ = 0.0;
  std::string error_;
  double last_r_[5] = {};
};

}  // namespace hil::controllers::elg
