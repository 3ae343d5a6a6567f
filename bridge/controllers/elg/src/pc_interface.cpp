// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/pc_interface.hpp"

#include <array>
#include <utility>

namespace hil::controllers::elg {
namespace {
constexpr std::array<std::pair<std::string_view, ElgCommand>, 11> names{{
    {"gearing_on", ElgCommand::gearing_on},
    {"gearing_off", ElgCommand::gearing_off},
    {"compute", ElgCommand::compute},
    {"single_pitch_on", ElgCommand::single_pitch_on},
    {"single_pitch_off", ElgCommand::single_pitch_off},
    {"index_plus", ElgCommand::index_plus},
    {"index_minus", ElgCommand::index_minus},
    {"fe_monitor_on", ElgCommand::fe_monitor_on},
    {"fe_monitor_off", ElgCommand::fe_monitor_off},
    {"hae_on", ElgCommand::hae_on},
    {"hae_off", ElgCommand::hae_off},
}};
}  // namespace

std::optional<ElgCommand> parse_elg_command(std::string_view name) noexcept {
  for (const auto& [text, command] : names) {
    if (text == name) return command;
  }
  return std::nullopt;
}

MFunctionMap default_m_functions() {
  return {{50, ElgCommand::gearing_on},  {51, ElgCommand::gearing_off},     {52, ElgCommand::compute},
          {53, ElgCommand::index_minus}, {54, ElgCommand::single_pitch_on}, {55, ElgCommand::single_pitch_off},
          {56, ElgCommand::index_plus}};
}

bool PcInterface::on_m_function(int m) {
  const auto it = map_.find(m);
  if (it == map_.end()) return false;
  switch (it->second) {
    case ElgCommand::gearing_on:
      signals_.gearing_off = false;
      signals_.gearing_on = true;
      pending_ = Pending::couple;
      break;
    case ElgCommand::gearing_off:
      signals_.gearing_on = false;
      signals_.gearing_off = true;
      pending_ = Pending::uncouple;
      break;
    case ElgCommand::compute:
      signals_.compute = true;
      pending_ = Pending::compute;
      break;
    case ElgCommand::single_pitch_on:
      signals_.single_pitch = true;
      break;
    case ElgCommand::single_pitch_off:
      signals_.single_pitch = false;
      break;
    case ElgCommand::index_plus:
    case ElgCommand::index_minus:
      (it->second == ElgCommand::index_plus ? signals_.index_plus : signals_.index_minus) = true;
      pending_ = Pending::index;
      pulse_cycles_ = 0;
      break;
    case ElgCommand::fe_monitor_on:
      signals_.fe_monitor = true;
      break;
    case ElgCommand::fe_monitor_off:
      signals_.fe_monitor = false;
      break;
    case ElgCommand::hae_on:
      signals_.hae = true;
      break;
    case ElgCommand::hae_off:
      signals_.hae = false;
      break;
  }
  return true;
}

void PcInterface::after_step(const GearboxStatus& status, bool new_alarm) {
  switch (pending_) {
    case Pending::none:
      break;
    case Pending::compute:
      // Acknowledged by "gearing constant computed" (E66.6), or refused with an alarm.
      if (status.computed || new_alarm) {
        signals_.compute = false;
        pending_ = Pending::none;
      }
      break;
    case Pending::couple:
      if (status.coupled || new_alarm) pending_ = Pending::none;
      break;
    case Pending::uncouple:
      if (!status.coupled) pending_ = Pending::none;
      break;
    case Pending::index:
      // The key is a pulse; the read-in disable holds until C stands at the new pitch.
      signals_.index_plus = signals_.index_minus = false;
      if (++pulse_cycles_ >= 2 && status.c_mode != CMode::position) pending_ = Pending::none;
      if (new_alarm) pending_ = Pending::none;
      break;
  }
}

}  // namespace hil::controllers::elg
