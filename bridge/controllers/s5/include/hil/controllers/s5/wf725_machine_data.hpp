// SPDX-License-Identifier: MIT
#pragma once
// The machine data MD 1-50 of one WF 725/726 axis as the running module holds them (digest
// wf725-726.md §3): read from the profile-validated parameter set, changed by the PLC in mode
// "machine data input/output" (data code 50h, docs/wf725.md), checked when the PLC switches to
// "traversing" (§3.3: 19, 1A, 1B, 1C). Values are the profile's engineering units (positions
// µm or 10^-3 degree, MD 3 mm/min, MD 22 (m/min)/mm). Pure.

#include <array>
#include <cstdint>
#include <expected>
#include <string>

#include "hil/controllers/parameter_file.hpp"
#include "hil/profiles/settings.hpp"

namespace hil::controllers::s5 {

/// Program memory of a module (§6.2; errors 68, 123, 124, 137, 138).
struct Wf725MemoryLimits {
  int programs = 64;
  int blocks_per_program = 200;
  int eeprom_blocks = 350;
  int ram_blocks = 50;
};
[[nodiscard]] constexpr Wf725MemoryLimits wf725_memory_limits(int series) noexcept {
  return series == 725 ? Wf725MemoryLimits{10, 40, 50, 50} : Wf725MemoryLimits{64, 200, 350, 50};
}

struct Wf725MachineData {
  int series = 726;                  ///< 725 or 726 (profile setting `module`)
  std::array<long double, 51> md{};  ///< index = MD number; unset MDs are 0
  std::uint64_t present = 0;         ///< bit n: MD n was given

  [[nodiscard]] long double get(int n) const noexcept {
    return n >= 1 && n <= 50 ? md[static_cast<std::size_t>(n)] : 0;
  }
  /// The MD as a whole number (positions in µm, digit maps, counts).
  [[nodiscard]] std::int64_t integer(int n) const noexcept;
  void set(int n, long double v) noexcept;
  [[nodiscard]] bool closed_loop() const noexcept { return integer(4) == 1 || integer(4) == 2; }
  [[nodiscard]] bool incremental() const noexcept { return integer(4) == 1 || integer(4) == 3; }
  [[nodiscard]] bool rotary() const noexcept { return integer(18) >= 2; }
  /// MD 15 as the WF 726 closed-loop fast-input map (digit n = function of input En), else as
  /// the cam source (1 = DB bit 2.1, 2 = X7 E1..E3).
  [[nodiscard]] bool fast_input_map() const noexcept { return series == 726 && closed_loop(); }
  /// Function 0..9 of fast input En (1..6) by the MD 15 map; 0 when MD 15 is the cam source.
  [[nodiscard]] int fast_input_function(int input) const noexcept;
  /// The fast input (1..6) with function `f`, 0 when none.
  [[nodiscard]] int fast_input_with(int f) const noexcept;
};

/// Reads MD 1..50 of a loaded set (values or the profile's defaults) for module series
/// `settings["module"]` (WF725A/B -> 725, else 726).
[[nodiscard]] Wf725MachineData wf725_machine_data(const LoadedParameters& p, const profiles::Settings& settings);

/// The checks when switching from "machine data input/output" to "traversing" (§4.3, error list):
/// MD 19 = MD 20 = 0 -> 0x19; MD 34 = 0 -> 0x1A; MD 12 > MD 11 -> 0x1B; MD 14 < MD 13 -> 0x1C.
/// 0 when the set passes.
[[nodiscard]] int check_wf725_mode_change(const Wf725MachineData& md) noexcept;

/// MD whose value shapes the motion core's axis (scaling, dynamics, windows). A change written in
/// mode MD I/O takes effect at the next power-up of the module (docs/wf725.md).
[[nodiscard]] bool wf725_md_shapes_axis(int n) noexcept;

}  // namespace hil::controllers::s5
