// SPDX-License-Identifier: MIT
#pragma once
// Every time option of the CLI (docs/cli.md, "Durations"): a duration with its unit, in the grammar
// of scenario files (hil/core/duration_text.hpp): `--timeout 500ms`, `--duration 2s`, `--latency
// 30us`. A bare number keeps the option's old unit for old scripts and prints a one-line
// deprecation warning on stderr naming the spelling to use. A renamed option keeps its old name as
// a hidden alias that warns. A malformed or out-of-range value is a usage error (exit 2) that says
// which option, what was given and what is expected.

#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "hil/core/clock.hpp"

namespace hil::cli {

/// Accepted values of one time option, both ends included; `min` may be 0.
struct DurationRange {
  Duration min{};
  Duration max = std::chrono::hours(24 * 10);
};

/// "250ms", "2s", "30us", "200ns", "1min", "0s": `d` in the largest unit of the grammar that
/// writes it exactly as a whole number.
[[nodiscard]] std::string format_duration(Duration d);

/// Adds the time option `names` ("--timeout" or "--duration,-d") writing `target`. `bare_unit`
/// ("s", "ms", "us", "ns") is how a number without unit was read before units were required.
CLI::Option* add_duration_option(CLI::App& cmd, const std::string& names, Duration& target, const std::string& help,
                                 std::string_view bare_unit, DurationRange range = {});

/// A hidden deprecated alias `old_name` ("--timeout-ms") of the time option `new_name`: a bare
/// number is in `bare_unit`; every use warns on stderr naming the new spelling.
CLI::Option* add_duration_alias(CLI::App& cmd, const std::string& old_name, const std::string& new_name,
                                Duration& target, std::string_view bare_unit, DurationRange range = {});

/// Reads `text` given to option `name` as add_duration_option does (warning on stderr for a bare
/// number); throws CLI::ValidationError on a bad or out-of-range value. For options whose value
/// is parsed after CLI11 (a value taken from a file or another option).
[[nodiscard]] Duration read_duration_option(std::string_view name, std::string_view text, std::string_view bare_unit,
                                            DurationRange range = {});

}  // namespace hil::cli
