// SPDX-License-Identifier: MIT
#include "hil/serial/clm14/files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace hil::serial::clm14 {

namespace {
std::string_view trim_line_end(std::string_view s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}
}  // namespace

std::expected<FileKind, std::string> parse_file_kind(std::string_view s) {
  if (s == "program") return FileKind::program;
  if (s == "parameters" || s == "params") return FileKind::parameters;
  return std::unexpected(fmt::format("unknown item kind '{}': use program or parameters", s));
}

std::expected<DeviceFile, FileProblems> parse_device_file(std::string_view text, FileKind kind, const DeviceData& data,
                                                          int axes, std::string_view name) {
  DeviceFile file{kind, {}};
  FileProblems problems;
  std::set<std::string, std::less<>> seen;
  std::vector<std::string> numbers;
  if (kind == FileKind::parameters) numbers = data.parameter_numbers(axes);
  int lineno = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    std::string_view line = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++lineno;
    line = trim_line_end(line);
    if (line.empty() || line.front() == ';') continue;
    const auto where = [&](std::string_view what) { problems.push_back(fmt::format("{}:{}: {}", name, lineno, what)); };
    const std::size_t sp = line.find(' ');
    const std::string key(line.substr(0, sp));
    const std::string_view rest = sp == std::string_view::npos ? std::string_view{} : line.substr(sp + 1);
    if (!seen.insert(key).second) {
      where(fmt::format("'{}' appears twice", key));
      continue;
    }
    if (kind == FileKind::program) {
      if (key.size() != 4 || !std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        where(fmt::format("'{}' is not a 4-digit line number 0000..2999", key));
        continue;
      }
      if (std::stoi(key) > 2999) {
        where(fmt::format("line number {} is larger than 2999 (the CLM has 3000 program lines)", key));
        continue;
      }
      auto checked = data.check_program_line(rest);
      if (!checked) {
        where(fmt::format("line {}: {}", key, checked.error().message));
        continue;
      }
    } else {
      if (std::find(numbers.begin(), numbers.end(), key) == numbers.end()) {
        where(fmt::format("'{}' is not a parameter of this CLM ({} axes): expected B000..B019, A100..A{}42, C000..C008",
                          key, axes, axes));
        continue;
      }
      auto checked = data.check_parameter(key, rest);
      if (!checked) {
        where(fmt::format("{}: {}", key, checked.error().message));
        continue;
      }
    }
    file.items.push_back(FileItem{key, std::string(rest), lineno});
  }
  if (!problems.empty()) return std::unexpected(std::move(problems));
  return file;
}

std::string make_device_file(const DeviceFile& file, std::string_view header_comment) {
  std::string out;
  std::size_t start = 0;
  while (start < header_comment.size()) {
    const std::size_t nl = header_comment.find('\n', start);
    out += "; ";
    out += header_comment.substr(start, nl == std::string_view::npos ? std::string_view::npos : nl - start);
    out += '\n';
    if (nl == std::string_view::npos) break;
    start = nl + 1;
  }
  for (const auto& it : file.items) {
    out += it.key;
    out += ' ';
    out += trim_line_end(it.text);
    if (out.back() == ' ') out.pop_back();
    out += '\n';
  }
  return out;
}

}  // namespace hil::serial::clm14
