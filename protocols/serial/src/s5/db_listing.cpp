// SPDX-License-Identifier: MIT
#include "hil/serial/s5/db_listing.hpp"

#include <fmt/format.h>

#include <charconv>

namespace hil::serial::s5 {

namespace {
std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}
template <class T>
bool to_num(std::string_view s, T& v, int base = 10) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, base);
  return r.ec == std::errc{} && r.ptr == s.data() + s.size();
}
}  // namespace

std::expected<std::vector<DbImage>, std::vector<std::string>> parse_db_listing(std::string_view text,
                                                                               std::string_view name) {
  std::vector<DbImage> out;
  std::vector<std::string> problems;
  int lineno = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const auto nl = text.find('\n', pos);
    std::string_view line = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    ++lineno;
    if (const auto c = line.find(';'); c != std::string_view::npos) line = line.substr(0, c);
    line = trim(line);
    if (line.empty()) continue;
    const auto bad = [&](std::string msg) { problems.push_back(fmt::format("{}:{}: {}", name, lineno, msg)); };
    if (line.starts_with("DB")) {
      int n = -1;
      if (!to_num(trim(line.substr(2)), n) || n < 0 || n > 255) {
        bad(fmt::format("'{}' is not a DB header DB0..DB255", line));
        continue;
      }
      out.push_back(DbImage{static_cast<std::uint8_t>(n), {}});
      continue;
    }
    if (out.empty()) {
      bad("data word before the first 'DBn' line");
      continue;
    }
    const auto colon = line.find(':');
    const auto eq = line.find('=');
    if (colon == std::string_view::npos || eq == std::string_view::npos || eq < colon) {
      bad(fmt::format("'{}' is not '<dw>: <format> = <value>'", line));
      continue;
    }
    int dw = -1;
    if (!to_num(trim(line.substr(0, colon)), dw) || dw != static_cast<int>(out.back().words.size())) {
      bad(fmt::format("data word number '{}' out of sequence: expected {}", trim(line.substr(0, colon)),
                      out.back().words.size()));
      continue;
    }
    if (dw > 2047) {
      bad("more than 2048 data words in one DB");
      continue;
    }
    const std::string_view f = trim(line.substr(colon + 1, eq - colon - 1));
    const std::string_view v = trim(line.substr(eq + 1));
    std::uint16_t word = 0;
    if (f == "KH") {
      unsigned x = 0;
      if (v.size() > 4 || !to_num(v, x, 16)) {
        bad(fmt::format("KH value '{}' is not 1..4 hex digits", v));
        continue;
      }
      word = static_cast<std::uint16_t>(x);
    } else if (f == "KF") {
      int x = 0;
      std::string_view d = v;
      if (!d.empty() && d.front() == '+') d.remove_prefix(1);
      if (!to_num(d, x) || x < -32768 || x > 32767) {
        bad(fmt::format("KF value '{}' is not a 16-bit signed decimal", v));
        continue;
      }
      word = static_cast<std::uint16_t>(static_cast<std::int16_t>(x));
    } else if (f == "KY") {
      const auto comma = v.find(',');
      unsigned hi = 0, lo = 0;
      if (comma == std::string_view::npos || !to_num(trim(v.substr(0, comma)), hi) ||
          !to_num(trim(v.substr(comma + 1)), lo) || hi > 255 || lo > 255) {
        bad(fmt::format("KY value '{}' is not two bytes 'hi,lo' (0..255 each)", v));
        continue;
      }
      word = static_cast<std::uint16_t>((hi << 8) | lo);
    } else {
      bad(fmt::format("format '{}' unknown: use KH, KF or KY", f));
      continue;
    }
    out.back().words.push_back(word);
  }
  if (!problems.empty()) return std::unexpected(problems);
  return out;
}

std::string make_db_listing(const std::vector<DbImage>& dbs, std::string_view header_comment) {
  std::string out;
  std::size_t start = 0;
  while (start < header_comment.size()) {
    const auto nl = header_comment.find('\n', start);
    out += "; ";
    out += header_comment.substr(start, nl == std::string_view::npos ? std::string_view::npos : nl - start);
    out += '\n';
    if (nl == std::string_view::npos) break;
    start = nl + 1;
  }
  for (const auto& db : dbs) {
    out += fmt::format("DB{}\n", db.db);
    for (std::size_t i = 0; i < db.words.size(); ++i) out += fmt::format("  {}: KH = {:04X}\n", i, db.words[i]);
  }
  return out;
}

}  // namespace hil::serial::s5
