// SPDX-License-Identifier: MIT
#pragma once
// Durations as people write them, in scenario files and on the command line: "250ms", "2 s",
// "30us", "200ns", "1min", "1.5s". One grammar for both (docs/cli.md, docs/scenarios.md): a decimal
// number, optional blanks, then a unit ns | us | ms | s | min (ns for timings below a microsecond,
// such as a step/dir direction setup time). Pure: no I/O, no allocation.

#include <optional>
#include <string_view>

#include "hil/core/clock.hpp"

namespace hil {

/// The units a duration may be written in, for messages: "ns, us, ms, s or min".
inline constexpr std::string_view k_duration_units = "ns, us, ms, s or min";

/// `text` -> Duration. A number without unit is read in `bare_unit` ("s" in scenario files; an
/// option's old unit on the command line). nullopt when malformed, an unknown unit, negative, not finite or
/// longer than ten days. Rounds to the nanosecond (100us is 100000ns, not 99999ns).
[[nodiscard]] std::optional<Duration> parse_duration_text(std::string_view text, std::string_view bare_unit = "s");

/// True when `text` is a bare number (no unit after it): what a command-line option warns about as
/// deprecated.
[[nodiscard]] bool is_bare_number(std::string_view text);

}  // namespace hil
