// SPDX-License-Identifier: MIT
#pragma once
// IP247 machine data (one set per axis): the 70-word MD DB (manual §6.3.8.1, digest ip247.md
// §2.2) as typed values, the firmware's consistency check with the MD error numbers (§7.2.1) and
// the derived quantities the axis runs on (resolution, vmax, speed -> pulse frequency). Pure.
// Positions are in base units (BU = 0.001 of the axis unit: µm, 0.0001 in, 0.001°).

#include <array>
#include <cstdint>
#include <expected>
#include <vector>

#include "hil/stepdir/ip247_error.hpp"
#include "hil/stepdir/ip247_ramp.hpp"

namespace hil::controllers::s5 {

enum class Ip247Unit : std::uint8_t { mm = 1, inch = 2, degree = 3 };

struct Ip247MachineData {
  std::uint8_t db = 1;
  int module = 0;  ///< DL n+3, must match the SYS-ID module number
  int axis = 1;    ///< DR n+3, 1..3
  Ip247Unit unit = Ip247Unit::mm;
  int md_error = 0;  ///< DR n+4 (written by the check)
  std::int32_t fmax_hz = 5000;
  std::int32_t fss_hz = 200;
  std::int32_t accel_mhz_per_ms = 50'000;  ///< "frequency increase" a (mHz/ms == Hz/s)
  int pulse_us = 30;
  bool positive_edge = true;  ///< n+12: 40h positive, 00h negative
  int patterns = 4;
  int pulses_per_rev = 200;
  std::int32_t gear_bu_per_rev = 2000;  ///< travel per motor revolution
  std::int32_t jog1 = 3000, jog2 = 3000, incremental_speed = 3000, reference_speed = 3000;  ///< unit/min
  bool reference_sync = false;   ///< n+25: 0 = yes, 1 = no (stored inverted there)
  int reference_direction = -1;  ///< n+26: 00h forward (+1), 20h backward (-1)
  std::int32_t reference_coordinate = 0;
  std::int32_t sw_start = -400'000, sw_end = 500'000;  ///< linear: SW limits; rotary: range
  bool limits_normally_closed = true;                  ///< n+33: 0 = NO ("pos"), 1 = NC ("neg")
  std::int32_t tool_offset = 2300;
  std::int32_t backlash = 0;
  std::array<std::int32_t, 4> zero_offsets{10'000, 25'000, 3'250, -75'000};  ///< G54..G57
  bool rotary = false;                                                       ///< n+46: 80h
  bool ag_bcd = false;                                                       ///< n+47: AG values BCD-coded
  friend bool operator==(const Ip247MachineData&, const Ip247MachineData&) = default;
};

inline constexpr std::size_t ip247_md_words = 70;
inline constexpr std::int64_t ip247_coordinate_limit = 100'000'000;  ///< |coordinate| < 100 m = 10^8 BU

/// The DB image (70 words, error byte from md_error).
[[nodiscard]] std::vector<std::uint16_t> make_ip247_md_db(const Ip247MachineData& md);
/// Reads an image; structural faults (length, identifier) give MD error 1 ("not yet checked").
[[nodiscard]] std::expected<Ip247MachineData, stepdir::Ip247MdError> parse_ip247_md_db(
    const std::vector<std::uint16_t>& words);
/// The firmware check at MD input (MD error numbers 2..22; 12 needs the SYS-ID module number).
[[nodiscard]] stepdir::Ip247MdError check_ip247_md(const Ip247MachineData& md, int sysid_module);

/// Derived quantities of a checked set.
struct Ip247Kinematics {
  std::int64_t gear_bu = 2000;  ///< BU per revolution
  std::int64_t ppr = 200;       ///< pulses per revolution
  double f_max_hz = 5000.0;

  /// Resolution in BU per pulse (may be fractional).
  [[nodiscard]] double resolution_bu() const noexcept {
    return static_cast<double>(gear_bu) / static_cast<double>(ppr);
  }
  /// Pulses for a position in BU (rounded to the nearest pulse).
  [[nodiscard]] std::int64_t pulses(std::int64_t bu) const noexcept;
  /// Position in BU of a pulse count (rounded).
  [[nodiscard]] std::int64_t bu(std::int64_t pulses) const noexcept;
  /// Pulse frequency for a speed in unit/min: f = v * 1000 / 60 / resolution.
  [[nodiscard]] double frequency_hz(double unit_per_min) const noexcept;
  /// vmax in unit/min from fmax.
  [[nodiscard]] double vmax() const noexcept { return f_max_hz * resolution_bu() * 60.0 / 1000.0; }
};
[[nodiscard]] Ip247Kinematics ip247_kinematics(const Ip247MachineData& md) noexcept;
[[nodiscard]] stepdir::Ip247RampParams ip247_ramp_params(const Ip247MachineData& md) noexcept;

}  // namespace hil::controllers::s5
