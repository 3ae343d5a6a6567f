// SPDX-License-Identifier: MIT
#include "hil/serial/tape/elg_tape.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>

namespace hil::serial::tape {

std::string_view elg_header(ElgSectionKind k) noexcept {
  return k == ElgSectionKind::machine_data ? "%TEA1" : "%SEA";
}

namespace {
std::string strip_comments(std::string_view b) {
  std::string out;
  int depth = 0;
  for (char c : b) {
    if (c == '(')
      ++depth;
    else if (c == ')' && depth > 0)
      --depth;
    else if (depth == 0 && c != ' ' && c != '\t' && c != '\r')
      out.push_back(c);
  }
  return out;
}
bool digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}
ElgTapeError format_error(std::string_view block, std::string msg) {
  return ElgTapeError{TapeError::data_format, std::string(block), std::move(msg)};
}
}  // namespace

std::expected<std::vector<ElgSection>, ElgTapeError> parse_elg_blocks(const std::vector<std::string>& blocks) {
  std::vector<ElgSection> out;
  bool open = false;
  for (const auto& raw : blocks) {
    const std::string b = strip_comments(raw);
    if (b.empty()) continue;
    if (b.front() == '%') {
      if (open) return std::unexpected(format_error(raw, "new '%' header before M02/M30 ended the previous section"));
      ElgSection s;
      if (b == "%TEA1")
        s.kind = ElgSectionKind::machine_data;
      else if (b == "%SEA")
        s.kind = ElgSectionKind::setting_data;
      else
        return std::unexpected(format_error(raw, fmt::format("unknown tape header '{}': expected %TEA1 or %SEA", b)));
      out.push_back(std::move(s));
      open = true;
      continue;
    }
    if (!open) return std::unexpected(format_error(raw, "data before a %TEA1 / %SEA header"));
    if (b == "M02" || b == "M30" || b == "M2") {
      open = false;
      continue;
    }
    const auto eq = b.find('=');
    if (b.front() != 'N' || eq == std::string::npos)
      return std::unexpected(format_error(raw, fmt::format("block '{}' is not N<number>=<value>", b)));
    const std::string_view num = std::string_view(b).substr(1, eq - 1);
    std::string_view val = std::string_view(b).substr(eq + 1);
    if (!digits(num) || num.size() > 5)
      return std::unexpected(format_error(raw, fmt::format("'{}' is not a data number (1 to 5 digits)", num)));
    std::string_view mag = val;
    if (!mag.empty() && (mag.front() == '+' || mag.front() == '-')) mag.remove_prefix(1);
    if (!digits(mag) || mag.size() > 9)
      return std::unexpected(
          format_error(raw, fmt::format("value '{}' of N{} must be a signed decimal of at most 9 digits", val, num)));
    ElgEntry e;
    std::from_chars(num.data(), num.data() + num.size(), e.number);
    if (!val.empty() && val.front() == '+') val.remove_prefix(1);
    e.value = std::string(val);
    out.back().entries.push_back(std::move(e));
  }
  if (open) return std::unexpected(format_error("", "tape ended without M02/M30"));
  return out;
}

std::vector<std::string> make_elg_blocks(const ElgSection& s) {
  std::vector<std::string> b;
  b.emplace_back(elg_header(s.kind));
  for (const auto& e : s.entries) b.push_back(fmt::format("N{}={}", e.number, e.value));
  b.emplace_back("M02");
  return b;
}

std::string make_elg_text(const std::vector<ElgSection>& sections) {
  std::string out;
  for (const auto& s : sections)
    for (const auto& b : make_elg_blocks(s)) {
      out += b;
      out += '\n';
    }
  return out;
}

std::expected<std::vector<ElgSection>, ElgTapeError> parse_elg_text(std::string_view text) {
  std::vector<std::string> blocks;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const auto nl = text.find('\n', pos);
    std::string_view line = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    if (line.size() > 254)
      return std::unexpected(
          ElgTapeError{TapeError::block_too_long, std::string(line.substr(0, 40)), "block longer than 254 characters"});
    if (!line.empty() && line.front() == ';') continue;  // file comment (not on tape)
    blocks.emplace_back(line);
  }
  return parse_elg_blocks(blocks);
}

}  // namespace hil::serial::tape
