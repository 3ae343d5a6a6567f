// SPDX-License-Identifier: MIT
#include "hil/stepdir/edge_log.hpp"

#include <charconv>

#include <fmt/format.h>

namespace hil::stepdir {

std::string EdgeLogError::describe() const {
  return fmt::format("line {}, column {}: {}", line, column, message);
}

std::string_view edge_line_name(std::uint16_t line) noexcept {
  switch (line) {
    case 0:
      return "step";
    case 1:
      return "dir";
    case 2:
      return "enable";
    default:
      return {};
  }
}

namespace {

bool is_space(char c) noexcept {
  return c == ' ' || c == '\t' || c == '\r';
}

}  // namespace

std::expected<std::vector<gpio::Edge>, EdgeLogError> parse_edge_log(std::string_view text) {
  std::vector<gpio::Edge> out;
  std::size_t line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t eol = text.find('\n', pos);
    const std::string_view line = text.substr(pos, eol == std::string_view::npos ? text.size() - pos : eol - pos);
    ++line_no;
    // Split into fields.
    std::string_view fields[4];
    std::size_t cols[4] = {};
    std::size_t nf = 0;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_space(line[i])) ++i;
      if (i >= line.size() || line[i] == '#') break;
      const std::size_t start = i;
      while (i < line.size() && !is_space(line[i]) && line[i] != '#') ++i;
      if (nf == 3) {
        return std::unexpected(
            EdgeLogError{line_no, start + 1, "too many fields: expected '<time_ns> <line> <level>'"});
      }
      fields[nf] = line.substr(start, i - start);
      cols[nf] = start + 1;
      ++nf;
    }
    if (nf != 0) {
      if (nf != 3) {
        return std::unexpected(EdgeLogError{line_no, nf ? cols[nf - 1] : 1,
                                            fmt::format("expected '<time_ns> <line> <level>', got {} field(s)", nf)});
      }
      gpio::Edge e;
      auto [p, ec] = std::from_chars(fields[0].data(), fields[0].data() + fields[0].size(), e.t_ns);
      if (ec != std::errc{} || p != fields[0].data() + fields[0].size()) {
        return std::unexpected(
            EdgeLogError{line_no, cols[0], fmt::format("time must be an integer in ns, got '{}'", fields[0])});
      }
      // Bounded so that the verifier's differences of two times cannot overflow.
      if (e.t_ns < 0 || e.t_ns > (std::int64_t{1} << 62)) {
        return std::unexpected(
            EdgeLogError{line_no, cols[0], fmt::format("time must be 0 .. 2^62 ns, got '{}'", fields[0])});
      }
      if (fields[1] == "step") {
        e.line = 0;
      } else if (fields[1] == "dir") {
        e.line = 1;
      } else if (fields[1] == "enable") {
        e.line = 2;
      } else {
        unsigned v = 0;
        auto [p2, ec2] = std::from_chars(fields[1].data(), fields[1].data() + fields[1].size(), v);
        if (ec2 != std::errc{} || p2 != fields[1].data() + fields[1].size() || v > 65535) {
          return std::unexpected(EdgeLogError{
              line_no, cols[1], fmt::format("line must be step, dir, enable or 0..65535, got '{}'", fields[1])});
        }
        e.line = static_cast<std::uint16_t>(v);
      }
      if (fields[2] == "0") {
        e.level = false;
      } else if (fields[2] == "1") {
        e.level = true;
      } else {
        return std::unexpected(
            EdgeLogError{line_no, cols[2], fmt::format("level must be 0 or 1, got '{}'", fields[2])});
      }
      out.push_back(e);
    }
    if (eol == std::string_view::npos) break;
    pos = eol + 1;
  }
  return out;
}

void format_edge(const gpio::Edge& e, std::string& out) {
  const auto name = edge_line_name(e.line);
  if (name.empty()) {
    fmt::format_to(std::back_inserter(out), "{} {} {}\n", e.t_ns, e.line, e.level ? 1 : 0);
  } else {
    fmt::format_to(std::back_inserter(out), "{} {} {}\n", e.t_ns, name, e.level ? 1 : 0);
  }
}

std::string format_edge_log(const std::vector<gpio::Edge>& edges) {
  std::string out = "# hilbridge edge log: <time_ns> <line> <level>\n";
  for (const auto& e : edges) format_edge(e, out);
  return out;
}

}  // namespace hil::stepdir
