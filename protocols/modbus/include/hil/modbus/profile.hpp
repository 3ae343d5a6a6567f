// SPDX-License-Identifier: MIT
#pragma once
// A drive's register profile, loaded from profiles/modbus/*.yaml: where the control word,
// status word, mode, targets, actual values and fault code live, their width, signedness and
// word order, the scaling to drive increments, the state machine behind the words (CiA 402-2
// §6.3 control/status words, or vendor bits) and the function codes the drive accepts.
// The same profile drives both ends: ModbusDrive (client) and the simulated drive server.

#include <array>
#include <cstdint>
#include <expected>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "hil/core/config_error.hpp"
#include "hil/modbus/packing.hpp"
#include "hil/modbus/register_table.hpp"

namespace hil::modbus {

enum class FieldRole : std::uint8_t {
  control_word,
  mode,
  target_position,
  target_velocity,
  status_word,
  actual_position,
  actual_velocity,
  fault_code,
};
inline constexpr std::size_t kFieldRoleCount = 8;
[[nodiscard]] std::string_view to_string(FieldRole r) noexcept;
/// Command fields are written by the client (read-write holding registers); the others are
/// feedback (read-only, in the space the read function code addresses).
[[nodiscard]] constexpr bool is_command(FieldRole r) noexcept {
  return r <= FieldRole::target_velocity;
}

struct RegisterField {
  bool present = false;
  std::uint16_t address = 0;  ///< PDU address (0-based, as on the wire)
  ValueFormat format{};
  /// Drive increments (or increments/s) per register unit: increments = raw * scale.
  double scale = 1.0;
  [[nodiscard]] std::uint16_t words() const noexcept { return format.words; }
};

enum class StateMachineKind : std::uint8_t {
  cia402,  ///< control word 6040h / status word 6041h semantics (CiA 402-2 §6.3)
  vendor,  ///< enable / fault-reset / quick-stop bits and ready / enabled / fault status bits
};

/// Bit numbers (0..15) of the vendor words; -1 = not used.
struct VendorBits {
  int enable = -1;       ///< control: level, 1 = power stage on and following
  int fault_reset = -1;  ///< control: rising edge acknowledges a fault
  int quick_stop = -1;   ///< control: level, 1 = stop with the quick-stop ramp and disable
  int ready = -1;        ///< status: power stage ready (no fault)
  int enabled = -1;      ///< status: following the targets
  int fault = -1;        ///< status: fault latched
  int referenced = -1;   ///< status: position referenced (both state machines; -1 = always referenced)
};

struct FunctionCodes {
  std::uint8_t read = 3;    ///< 3 (feedback in holding registers) or 4 (input registers)
  std::uint8_t write = 16;  ///< 6 (one register per request; 16-bit fields only) or 16
  bool read_write = false;  ///< use FC 23 (write command block, read feedback block) per cycle
};

struct Profile {
  std::string name;
  std::string description;
  std::string source;  ///< file it was loaded from ("" for in-memory)
  StateMachineKind state_machine = StateMachineKind::cia402;
  std::uint8_t unit_id = 1;
  FunctionCodes function_codes{};
  std::array<RegisterField, kFieldRoleCount> fields{};
  std::int64_t mode_position = 8;  ///< value written to `mode` for CommandMode::position (CiA 402: 8 = CSP)
  std::int64_t mode_velocity = 9;  ///< ... for CommandMode::velocity (CiA 402: 9 = CSV)
  /// ... for homing (CiA 402: 6 = HM, started by a rising edge of control word bit 4, done on
  /// status bits 12 + 10, failed on bit 13). Absent: the drive offers no homing. cia402 only.
  std::optional<std::int64_t> mode_homing;
  VendorBits bits{};
  std::map<std::uint32_t, std::string> fault_texts;  ///< fault-code register value -> text

  [[nodiscard]] const RegisterField& field(FieldRole r) const noexcept { return fields[static_cast<std::size_t>(r)]; }
  [[nodiscard]] RegisterField& field(FieldRole r) noexcept { return fields[static_cast<std::size_t>(r)]; }
  /// Space holding the feedback fields (input when function_codes.read == 4).
  [[nodiscard]] RegisterSpace feedback_space() const noexcept {
    return function_codes.read == 4 ? RegisterSpace::input : RegisterSpace::holding;
  }
  [[nodiscard]] RegisterSpace space_of(FieldRole r) const noexcept {
    return is_command(r) ? RegisterSpace::holding : feedback_space();
  }
  /// Text for a fault code ("" when the profile does not name it).
  [[nodiscard]] std::string fault_text(std::uint32_t code) const;
};

/// Parse a profile from YAML text. `source` names the file in errors. Checks: required fields
/// (control_word, status_word, target_position, actual_position), types (u16 i16 u32 i32; s16 s32 too),
/// overlapping registers, FC choices (read 3|4, write 6|16, FC 23 only with holding feedback
/// and contiguous blocks), vendor bits in 0..15 and present for a vendor state machine.
[[nodiscard]] std::expected<Profile, ConfigError> parse_profile(const std::string& yaml_text,
                                                                const std::string& source = "");
/// Load and parse a profile file.
[[nodiscard]] std::expected<Profile, ConfigError> load_profile(const std::string& path);

/// Define the profile's registers in `table`: command fields read-write holding registers,
/// feedback fields read-only in the feedback space.
void define_registers(const Profile& profile, RegisterTable& table);

}  // namespace hil::modbus
