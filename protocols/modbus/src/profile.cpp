// SPDX-License-Identifier: MIT
#include "hil/modbus/profile.hpp"

namespace hil::modbus {

std::string_view to_string(FieldRole r) noexcept {
  switch (r) {
    case FieldRole::control_word:
      return "control_word";
    case FieldRole::mode:
      return "mode";
    case FieldRole::target_position:
      return "target_position";
    case FieldRole::target_velocity:
      return "target_velocity";
    case FieldRole::status_word:
      return "status_word";
    case FieldRole::actual_position:
      return "actual_position";
    case FieldRole::actual_velocity:
      return "actual_velocity";
    case FieldRole::fault_code:
      return "fault_code";
  }
  return "?";
}

std::string Profile::fault_text(std::uint32_t code) const {
  auto it = fault_texts.find(code);
  return it == fault_texts.end() ? std::string{} : it->second;
}

void define_registers(const Profile& profile, RegisterTable& table) {
  for (std::size_t i = 0; i < kFieldRoleCount; ++i) {
    const auto role = static_cast<FieldRole>(i);
    const RegisterField& f = profile.fields[i];
    if (!f.present) continue;
    table.define(profile.space_of(role), f.address, f.words(),
                 is_command(role) ? Access::read_write : Access::read_only);
  }
}

}  // namespace hil::modbus
