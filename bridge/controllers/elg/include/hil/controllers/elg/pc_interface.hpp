// SPDX-License-Identifier: MIT
#pragma once
// The PC user program between NC and ELG (manual 3.1, 12.4; "package 6"): it turns the NC's
// M functions into ELG interface signals and holds the NC's read-in while a handshake runs
// (3.2: "the PC should hold an input disable on the NC while the computation runs").
//
// The M numbers are the user's choice (digest §11.1). Default assignment, as in the manual's
// example: M50 Gearing ON, M51 Gearing OFF, M52 compute gearing constants, M54 single pitch on,
// M55 single pitch off, M56 index one pitch forward; [I] M53 indexes one pitch backward.

#include <cstdint>
#include <map>
#include <optional>
#include <string_view>

#include "hil/controllers/elg/gearbox.hpp"

namespace hil::controllers::elg {

enum class ElgCommand : std::uint8_t {
  gearing_on,
  gearing_off,
  compute,
  single_pitch_on,
  single_pitch_off,
  index_plus,
  index_minus,
  fe_monitor_on,
  fe_monitor_off,
  hae_on,
  hae_off,
};

/// Parses "gearing_on", "compute", ...; nullopt when unknown.
std::optional<ElgCommand> parse_elg_command(std::string_view name) noexcept;

/// M number -> ELG command.
using MFunctionMap = std::map<int, ElgCommand>;
MFunctionMap default_m_functions();

class PcInterface {
 public:
  explicit PcInterface(MFunctionMap map = default_m_functions()) : map_(std::move(map)) {}

  /// An M function output by the NC; returns false when it is not an ELG function.
  bool on_m_function(int m);
  /// The signals for this ELG cycle (levels the PC holds, plus one-cycle pulses).
  [[nodiscard]] const Signals& signals() const noexcept { return signals_; }
  Signals& signals() noexcept { return signals_; }
  /// After the ELG step: acknowledged commands are withdrawn, pulses end.
  void after_step(const GearboxStatus& status, bool new_alarm);
  /// The NC must wait (read-in disable) while a handshake is pending.
  [[nodiscard]] bool read_in_disable() const noexcept { return pending_ != Pending::none; }

 private:
  enum class Pending : std::uint8_t { none, compute, couple, uncouple, index };
  MFunctionMap map_;
  Signals signals_;
  Pending pending_ = Pending::none;
  int pulse_cycles_ = 0;
};

}  // namespace hil::controllers::elg
