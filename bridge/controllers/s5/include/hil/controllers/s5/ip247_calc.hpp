// SPDX-License-Identifier: MIT
#pragma once
// IP247 machine-data calculators (manual §2.5.2-2.5.4, §5.6.1.2, §7.1.3-7.1.4; digest ip247.md
// §2.4): what a user computes when setting up an axis. Pure.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace hil::controllers::s5 {

struct Ip247CalcInput {
  std::optional<double> step_angle_deg{};  ///< motor step angle: pulses/rev = 360 / angle (x2 half step)
  bool half_step = false;
  std::optional<int> pulses_per_rev{};      ///< or given directly
  std::optional<double> gear_um_per_rev{};  ///< travel per motor revolution in BU (µm, 0.0001 in, m°)
  std::optional<double> speed_per_min{};    ///< a speed in unit/min (jog, incremental, ...) -> its frequency
  std::optional<double> fmax_hz{};          ///< absent: the frequency of `speed_per_min`
  std::optional<double> fss_hz{};
  std::optional<double> accel_hz_per_ms{};  ///< frequency increase a
  std::optional<double> range_bu{};         ///< rotary range (end - start) for the reproducibility check
};

struct Ip247CalcLine {
  std::string quantity{};
  double value = 0.0;
  std::string unit{};
  std::string md{};  ///< which MD to enter it in, or "" (derived only)
};

struct Ip247CalcResult {
  std::vector<Ip247CalcLine> lines{};
  std::vector<std::string> problems{};  ///< violated MD rules, with the MD error number
  [[nodiscard]] std::optional<double> get(const std::string& quantity) const;
};

[[nodiscard]] Ip247CalcResult ip247_calculate(const Ip247CalcInput& in);

}  // namespace hil::controllers::s5
