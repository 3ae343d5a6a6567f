// SPDX-License-Identifier: MIT
#include "hil/core/duration_text.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

namespace hil {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

/// Seconds per `unit`; 0 for an unknown unit.
double unit_seconds(std::string_view unit) {
  if (unit == "s") return 1.0;
  if (unit == "ms") return 1e-3;
  if (unit == "us") return 1e-6;
  if (unit == "ns") return 1e-9;
  if (unit == "min") return 60.0;
  return 0.0;
}

/// The number at the start of `text` and what follows it (trimmed); nullopt when no number.
std::optional<std::pair<double, std::string_view>> split(std::string_view text) {
  text = trim(text);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end == text.data()) return std::nullopt;
  return std::pair{value, trim(std::string_view(end, static_cast<std::size_t>(text.data() + text.size() - end)))};
}

}  // namespace

std::optional<Duration> parse_duration_text(std::string_view text, std::string_view bare_unit) {
  const auto parts = split(text);
  if (!parts) return std::nullopt;
  const double scale = unit_seconds(parts->second.empty() ? bare_unit : parts->second);
  if (scale == 0.0) return std::nullopt;
  const double seconds = parts->first * scale;
  if (!std::isfinite(seconds) || seconds < 0.0 || seconds > 10.0 * 86400.0) return std::nullopt;
  return Duration{std::llround(seconds * 1e9)};  // round: 100us must not become 99999ns
}

bool is_bare_number(std::string_view text) {
  const auto parts = split(text);
  return parts && parts->second.empty();
}

}  // namespace hil
