// SPDX-License-Identifier: MIT
#include "hil/cli/duration_option.hpp"

#include <fmt/format.h>

#include <cstdio>

#include "hil/core/duration_text.hpp"

namespace hil::cli {

namespace {

std::string_view unit_word(std::string_view unit) {
  if (unit == "ns") return "nanoseconds";
  if (unit == "us") return "microseconds";
  if (unit == "ms") return "milliseconds";
  if (unit == "min") return "minutes";
  return "seconds";
}

std::string trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return std::string(s);
}

/// The option's first long name for messages ("--timeout" of "--timeout,-t").
std::string long_name(const std::string& names) {
  std::string first;
  std::size_t start = 0;
  while (start <= names.size()) {
    const auto comma = names.find(',', start);
    std::string part = names.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (part.starts_with("--")) return part;
    if (first.empty()) first = part;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return first;
}

}  // namespace

std::string format_duration(Duration d) {
  using namespace std::chrono;
  const auto ns = d.count();
  if (ns != 0 && ns % 60'000'000'000 == 0) return fmt::format("{}min", ns / 60'000'000'000);
  if (ns % 1'000'000'000 == 0) return fmt::format("{}s", ns / 1'000'000'000);
  if (ns % 1'000'000 == 0) return fmt::format("{}ms", ns / 1'000'000);
  if (ns % 1'000 == 0) return fmt::format("{}us", ns / 1'000);
  return fmt::format("{}ns", ns);
}

Duration read_duration_option(std::string_view name, std::string_view text, std::string_view bare_unit,
                              DurationRange range) {
  const std::string t = trimmed(text);
  const auto d = parse_duration_text(t, bare_unit);
  if (!d)
    throw CLI::ValidationError(
        std::string(name),
        fmt::format("'{}' is not a duration: expected a number with a unit {} (e.g. 250ms, 2s)", t, k_duration_units));
  if (*d < range.min || *d > range.max)
    throw CLI::ValidationError(std::string(name),
                               fmt::format("{} is out of range: expected {} .. {}", format_duration(*d),
                                           format_duration(range.min), format_duration(range.max)));
  if (is_bare_number(t))
    fmt::print(stderr, "hilbridge: warning: {} {}: a number without unit is read as {} (deprecated); write {} {}{}\n",
               name, t, unit_word(bare_unit), name, t, bare_unit);
  return *d;
}

CLI::Option* add_duration_option(CLI::App& cmd, const std::string& names, Duration& target, const std::string& help,
                                 std::string_view bare_unit, DurationRange range) {
  const std::string name = long_name(names);
  const std::string unit(bare_unit);
  auto* opt = cmd.add_option_function<std::string>(
      names,
      [&target, name, unit, range](const std::string& text) { target = read_duration_option(name, text, unit, range); },
      help);
  opt->type_name("DURATION");
  return opt;
}

CLI::Option* add_duration_alias(CLI::App& cmd, const std::string& old_name, const std::string& new_name,
                                Duration& target, std::string_view bare_unit, DurationRange range) {
  const std::string unit(bare_unit);
  auto* opt = cmd.add_option_function<std::string>(
      old_name,
      [&target, old_name, new_name, unit, range](const std::string& text) {
        const std::string t = trimmed(text);
        // A bare number is the old option's unit; that is what the alias means, so one warning only.
        if (is_bare_number(t)) {
          fmt::print(stderr, "hilbridge: warning: {} is deprecated; write {} {}{}\n", old_name, new_name, t, unit);
          target = read_duration_option(old_name, t + unit, unit, range);
        } else {
          fmt::print(stderr, "hilbridge: warning: {} is deprecated; write {} {}\n", old_name, new_name, t);
          target = read_duration_option(old_name, t, unit, range);
        }
      },
      "");
  opt->group("");  // hidden: old scripts keep working, --help shows only the new spelling
  return opt;
}

}  // namespace hil::cli
