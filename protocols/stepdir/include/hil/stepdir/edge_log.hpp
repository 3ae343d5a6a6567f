// SPDX-License-Identifier: MIT
#pragma once
// Text format of a recorded or planned edge stream, one edge per line:
//   # comment
//   <time_ns> <line> <level>
// <line> is `step`, `dir`, `enable` or an output-bank index 0..65535; <level> is 0 or 1.
// `hilbridge stepdir plan` writes it, `hilbridge stepdir verify` reads it. Pure.

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <vector>

#include "hil/gpio/edge.hpp"

namespace hil::stepdir {

struct EdgeLogError {
  std::size_t line = 0;    ///< 1-based line of the log
  std::size_t column = 0;  ///< 1-based
  std::string message;
  [[nodiscard]] std::string describe() const;  ///< "line 4, column 9: level must be 0 or 1, got '2'"
};

/// Line names used by the format (index 0 = step, 1 = dir, 2 = enable).
[[nodiscard]] std::string_view edge_line_name(std::uint16_t line) noexcept;

[[nodiscard]] std::expected<std::vector<gpio::Edge>, EdgeLogError> parse_edge_log(std::string_view text);
/// Append one edge as a log line to `out`.
void format_edge(const gpio::Edge& e, std::string& out);
[[nodiscard]] std::string format_edge_log(const std::vector<gpio::Edge>& edges);

}  // namespace hil::stepdir
