// SPDX-License-Identifier: MIT
#pragma once
// Split drive (gantry) of the WF 726, MD 27 / MD 29 (digest wf725-726.md §4.3, errors 25, 69, 6A,
// 6B, 6D; docs/wf725.md "Split drive"): axis A is the master, the axis MD 27 names (3 = A+B,
// 5 = A+C) follows A's set-point every run period ("one command, two drives"), shifted by the
// programmed shift of data code 31; the actual values are compared every module cycle against
// MD 29 (error 25). This header holds the pure rules and the coupling's state; the controller's
// side is in wf725_split_drive.cpp (Wf725Controller::couple_split_drive, split_drive_period).

#include <cstdint>
#include <expected>
#include <span>
#include <string>

#include "hil/controllers/s5/wf725_interface.hpp"
#include "hil/controllers/s5/wf725_machine_data.hpp"
#include "hil/motion/superimposed.hpp"

namespace hil::controllers::s5 {

class Wf725Controller;

namespace wf_db {
/// D 2.3 (decision: the manual names a "split-drive monitoring enable bit" without its place):
/// in axis A's DB axis, switches the MD 29 comparison on (controller key split_monitoring: bit).
inline constexpr std::uint8_t bit_split_monitoring = 3;
namespace code {
inline constexpr std::uint16_t split_difference = 0x30;  ///< read the split-drive difference, µm (manual)
inline constexpr std::uint16_t split_shift = 0x31;       ///< programmed shift: param1 µm, param2 feed (manual)
}  // namespace code
}  // namespace wf_db

/// The partner of axis A that MD 27 names: 'B' (3), 'C' (5), 0 (0: no split drive, or a value the
/// profile refuses).
[[nodiscard]] constexpr char wf725_split_partner(std::int64_t md27) noexcept {
  return md27 == 3 ? 'B' : md27 == 5 ? 'C' : '\0';
}

/// The first of MD 1, 2, 38, 39 that differs between master and slave (error 6D at a coupled
/// start), 0 when they agree.
[[nodiscard]] inline int wf725_split_md_mismatch(const Wf725MachineData& a, const Wf725MachineData& b) noexcept {
  for (const int n : {1, 2, 38, 39})
    if (a.get(n) != b.get(n)) return n;
  return 0;
}

/// Submodes in which the split drive runs (MD 27 text: set up, MDI, single block, automatic cycle,
/// single step, buffer); in the others each axis moves on its own DB axis.
[[nodiscard]] constexpr bool wf725_split_submode(wf_db::Submode s) noexcept {
  using enum wf_db::Submode;
  return s == set_up || s == mdi || s == single_step || s == automatic || s == automatic_step || s == automatic_buffer;
}

/// The state of one coupling, held by the master (axis A).
struct Wf725SplitDrive {
  Wf725Controller* slave = nullptr;
  bool engaged = false;             ///< master in a split submode, slave in submode "0", both enabled (master's cycle)
  bool following = false;           ///< the slave takes the master's set-point (Axis::follow) this period
  int rest_periods = 0;             ///< periods the master and the shift have rested while following
  double trim_mm = 0.0;             ///< the slave's residual at the start of following (ramped out by `shift`)
  motion::SuperimposedMove shift;   ///< programmed shift (data code 31) + the trim ramp, mm
  double shift_target_mm = 0.0;     ///< the programmed shift (slave - master), mm
  double commanded_mm = 0.0;        ///< the relation in force (the last one followed; 0 at power-up), mm
  double shift_feed = 0.0;          ///< mm/s of the last data code 31
  bool shift_requested = false;     ///< data code 31 while the slave rested: the next period follows
  double last_difference_um = 0.0;  ///< the last comparison's difference (data code 30)
  double max_difference_um = 0.0;   ///< largest |difference| compared since coupling (observation)
  double master_offset = 0.0, slave_offset = 0.0;  ///< the axes' machine offsets the shift belongs to
  /// Commanded slave - master relation now (mm): trim + shift in progress.
  [[nodiscard]] double relation_mm() const noexcept { return trim_mm + shift.offset(); }
};

/// Couples the axes of one module by MD 27 of its axis A (read at power-up): with 3 / 5, the axis
/// B / C follows A. Nothing to do (MD 27 = 0, no axis A): success. An error text when MD 27 names an
/// axis the module does not have or the pair cannot be coupled (couple_split_drive). Call once,
/// after the axes are bound and before the first cycle; each axis' split_drive_period() must then
/// run every run period before that axis' update (after the master's).
[[nodiscard]] std::expected<void, std::string> wf725_couple_split_drive(std::span<Wf725Controller* const> axes);

}  // namespace hil::controllers::s5
