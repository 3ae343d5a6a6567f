// SPDX-License-Identifier: MIT
#pragma once
// Reads a scenario file (YAML, yaml-cpp). Every error is a hil::ConfigError naming the file,
// the line and column (yaml-cpp Mark), the key path ("machine.axes[1].limits.jerk") and what
// was expected. Unknown keys are errors (a typo must never be ignored silently). The `drive:`
// maps are checked only for `transport:`; their other keys belong to the transport factory.

#include <expected>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>

#include "hil/core/config_error.hpp"
#include "hil/runtime/scenario.hpp"

namespace hil::runtime {

/// Load and validate a scenario file. Blocking (reads the file). Never throws.
[[nodiscard]] std::expected<Scenario, ConfigError> load_scenario(const std::filesystem::path& file);

/// Parse scenario text; `file_name` only labels messages (and Scenario::file). Never throws.
[[nodiscard]] std::expected<Scenario, ConfigError> parse_scenario(std::string_view text,
                                                                  const std::string& file_name = "");

/// "250ms", "2 s", "1.5", "100us", "1min" (a bare number is seconds) -> Duration; nullopt when
/// malformed, negative or longer than ten days.
[[nodiscard]] std::optional<Duration> parse_duration(std::string_view text);

/// Increments per unit: "1000", "4096/5", "12.5" -> {num, den} (both 1..2^40); nullopt otherwise.
[[nodiscard]] std::optional<std::pair<std::int64_t, std::int64_t>> parse_ratio(std::string_view text);

/// A fault code as scenarios write it: "motion:1", "cia402:0x7305" -> {category, value}; a device
/// catalogue's code as its manual writes it: "wf725-726.traversing:96" -> {category, -1, "96"}.
struct FaultCode {
  std::string category;
  int value = 0;     ///< -1 for a device catalogue code (match `text`)
  std::string text;  ///< the code as written after the colon
};
[[nodiscard]] std::optional<FaultCode> parse_fault_code(std::string_view text);

}  // namespace hil::runtime
