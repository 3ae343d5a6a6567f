// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/wf725_program.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>

namespace hil::controllers::s5 {
namespace {

constexpr std::int64_t max_position = 79'999'999;  // the BCD range of positions (§3.3)
constexpr std::int64_t max_feed = 30'000'000;      // MD 3's upper limit, 10^-2 mm/min

bool is_digit(char c) noexcept {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

class LineParser {
 public:
  LineParser(std::string_view text, int line, int program) : t_(text), line_(line), program_(program) {}

  std::unexpected<Wf725SyntaxError> fail(int code, int block, std::string message) const {
    return std::unexpected(Wf725SyntaxError{code, program_, block, line_, std::move(message)});
  }
  void skip_blanks() noexcept {
    while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\t')) ++i_;
  }
  [[nodiscard]] bool done() noexcept {
    skip_blanks();
    return i_ >= t_.size();
  }
  [[nodiscard]] char peek() const noexcept { return i_ < t_.size() ? t_[i_] : '\0'; }
  char take() noexcept { return t_[i_++]; }
  /// A signed number with the manual's digit-group blanks ("1000 000", "-24 537"): after the
  /// first digits, a single blank followed by exactly three digits continues the number.
  [[nodiscard]] std::optional<std::int64_t> number(bool allow_sign) noexcept {
    skip_blanks();
    bool negative = false;
    if (allow_sign && (peek() == '-' || peek() == '+')) negative = take() == '-';
    if (!is_digit(peek())) return std::nullopt;
    std::int64_t v = 0;
    int digits = 0;
    const auto digit_run = [&] {
      while (is_digit(peek())) {
        if (++digits > 12) return false;
        v = v * 10 + (take() - '0');
      }
      return true;
    };
    if (!digit_run()) return std::nullopt;
    while (i_ + 3 < t_.size() + 1 && peek() == ' ') {
      const std::size_t j = i_ + 1;
      if (j + 3 <= t_.size() && is_digit(t_[j]) && is_digit(t_[j + 1]) && is_digit(t_[j + 2]) &&
          (j + 3 == t_.size() || !is_digit(t_[j + 3]))) {
        i_ = j;
        if (!digit_run()) return std::nullopt;
      } else {
        break;
      }
    }
    return negative ? -v : v;
  }
  [[nodiscard]] std::string_view rest() const noexcept { return t_.substr(i_); }

 private:
  std::string_view t_;
  std::size_t i_ = 0;
  int line_;
  int program_;
};

std::string_view strip(std::string_view s) noexcept {
  if (const auto c = s.find(';'); c != std::string_view::npos) s = s.substr(0, c);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  return s;
}

std::expected<Wf725Program, Wf725SyntaxError> parse_header(std::string_view s, int line) {
  LineParser p(s.substr(1), line, 0);
  const auto n = p.number(false);
  if (!n || *n == 0) return p.fail(230, 0, "program header '%<number>': the program number must be 1..255, not 0");
  if (*n > 255) return p.fail(220, 0, fmt::format("program number {} out of range: 1..255", *n));
  Wf725Program prog;
  prog.number = static_cast<int>(*n);
  while (!p.done()) {
    std::string word;
    while (std::isalpha(static_cast<unsigned char>(p.peek())) != 0)
      word.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(p.take()))));
    if (word == "RAM") {
      prog.ram = true;
    } else if (word == "EEPROM") {
      prog.ram = false;
    } else if (!word.empty() && word.find_first_not_of("ABC") == std::string::npos) {
      for (char c : word)
        if (prog.valid_axes.find(c) == std::string::npos) prog.valid_axes.push_back(c);
    } else {
      return std::unexpected(Wf725SyntaxError{
          220, prog.number, 0, line,
          fmt::format("program header: '{}' is neither the axes it is valid for (A, B, C) nor RAM/EEPROM",
                      word.empty() ? std::string(p.rest()) : word)});
    }
  }
  return prog;
}

std::expected<Wf725Block, Wf725SyntaxError> parse_block(std::string_view s, int line, int program,
                                                        const Wf725ProgramSyntax& syntax) {
  LineParser p(s, line, program);
  Wf725Block b;
  if (p.peek() == '/') {
    (void)p.take();
    b.skippable = true;
    p.skip_blanks();
  }
  if (std::toupper(static_cast<unsigned char>(p.peek())) != 'N')
    return p.fail(231, 0, "a block starts with its block number N1..N255 (after an optional '/')");
  (void)p.take();
  const auto n = p.number(false);
  if (!n || *n == 0) return p.fail(231, 0, "block number N0 or missing: N1..N255");
  if (*n > 255) return p.fail(220, 0, fmt::format("block number N{} out of range: N1..N255", *n));
  b.number = static_cast<int>(*n);
  const int bn = b.number;
  std::string seen;
  while (!p.done()) {
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(p.take())));
    if (letter == 'A' || letter == 'B' || letter == 'C') {
      if (b.axis != 0 || !seen.empty())
        return p.fail(220, bn, "the axis letter A/B/C follows N once, before the functions");
      b.axis = letter;
      continue;
    }
    if (letter != 'G' && seen.find(letter) != std::string::npos)
      return p.fail(220, bn, fmt::format("address {} given twice in one block", letter));
    seen.push_back(letter);
    const bool signed_value = letter == 'X';
    const auto v = p.number(signed_value);
    if (!v) return p.fail(220, bn, fmt::format("address {} without a number", letter));
    switch (letter) {
      case 'G': {
        const int group = syntax.group(*v);
        if (group == 0)
          return p.fail(220, bn,
                        fmt::format("G{:02} is no WF function (G04, G17-19, G23-29, G53, G54, G68, G69, G73-79, "
                                    "G90, G91, G92, G93, G99)",
                                    *v));
        auto& slot = b.g[static_cast<std::size_t>(group - 1)];
        if (slot >= 0)
          return p.fail(
              231 + group, bn,
              fmt::format("G{:02} and G{:02} are both of G group {}: one G function per group", slot, *v, group));
        slot = static_cast<int>(*v);
        break;
      }
      case 'X':
        if (*v > max_position || *v < -max_position) return p.fail(220, bn, fmt::format("X {} beyond ±79 999 999", *v));
        b.x = *v;
        break;
      case 'F':
        if (*v > max_feed) return p.fail(220, bn, fmt::format("F {} beyond 30 000 000 (10^-2 mm/min)", *v));
        b.f = *v;
        break;
      case 'M':
        if (*v > 99) return p.fail(220, bn, fmt::format("M{} out of range: M0..M99", *v));
        b.m = static_cast<int>(*v);
        break;
      case 'T':
        if (*v > 20) return p.fail(239, bn, fmt::format("tool offset T{} beyond the 20 offset memories", *v));
        b.tool = static_cast<int>(*v);
        break;
      case 'L':
        if (*v == 0 || *v > 255) return p.fail(220, bn, fmt::format("subprogram L{} out of range: L1..L255", *v));
        b.call = static_cast<int>(*v);
        break;
      case 'P':
        if (*v == 0 || *v > 99) return p.fail(240, bn, fmt::format("number of passes P{} out of range: P1..P99", *v));
        b.passes = static_cast<int>(*v);
        break;
      default:
        return p.fail(220, bn,
                      fmt::format("'{}' starts no function (N, A/B/C, G, X, F, M, T, L, P; ';' comment)", letter));
    }
  }
  if (b.has_g(4)) {
    if (!b.f || *b.f == 0) return p.fail(236, bn, "G04 (dwell) needs its time: G04 F<ms>");
    if (b.x) return p.fail(220, bn, "G04 (dwell) takes no position X");
  }
  if (b.call) {
    if (!b.passes) return p.fail(237, bn, fmt::format("subprogram call L{} without its number of passes P", *b.call));
    for (int g : b.g)
      if (g >= 0) return p.fail(238, bn, "a subprogram call L takes no G function");
    if (b.x || b.f) return p.fail(220, bn, "a subprogram call L takes no X or F");
  } else if (b.passes) {
    return p.fail(220, bn, "P (passes) belongs to a subprogram call L");
  }
  return b;
}

}  // namespace

int wf725_g_group(int g) noexcept {
  if (g == 90 || g == 91) return 1;
  if (g == 4 || g == 68 || g == 69 || g == 99) return 2;
  if (g == 53 || g == 54 || g == 92 || g == 93) return 3;
  if ((g >= 17 && g <= 19) || (g >= 23 && g <= 29) || (g >= 73 && g <= 79)) return 4;
  return 0;
}

Wf725ProgramSyntax wf725_default_syntax() noexcept {
  Wf725ProgramSyntax s;
  for (int g = 0; g < 100; ++g) s.g_group[static_cast<std::size_t>(g)] = static_cast<std::uint8_t>(wf725_g_group(g));
  return s;
}

std::expected<Wf725ProgramSyntax, std::string> wf725_program_syntax(const profiles::Profile& profile) {
  const auto it = profile.tables.find("program_g_functions");
  if (it == profile.tables.end()) return wf725_default_syntax();
  Wf725ProgramSyntax s;
  for (std::size_t i = 0; i < it->second.size(); ++i) {
    const auto& row = it->second[i];
    const auto g = row.find("g"), group = row.find("group");
    int gv = -1, grv = -1;
    if (g != row.end()) (void)std::from_chars(g->second.data(), g->second.data() + g->second.size(), gv);
    if (group != row.end())
      (void)std::from_chars(group->second.data(), group->second.data() + group->second.size(), grv);
    if (gv < 0 || gv > 99 || grv < 1 || grv > 4)
      return std::unexpected(
          fmt::format("{} profile, tables.program_g_functions[{}]: a row needs g: 00..99 and "
                      "group: 1..4",
                      profile.device, i));
    s.g_group[static_cast<std::size_t>(gv)] = static_cast<std::uint8_t>(grv);
  }
  return s;
}

std::string_view wf725_pair_axes(int g) noexcept {
  return g == 17 ? "AB" : g == 18 ? "AC" : g == 19 ? "BC" : "";
}

namespace {

/// The interpolation rules of a block entered after `prev` (digest §5.3, 174/181; docs/wf725.md,
/// "Combined programs"): a block with G17/G18/G19 opens a pair, the next block of the program
/// is its partner. `open` is the opener waiting for its partner (nullptr: none).
std::optional<Wf725SyntaxError> check_interpolation(const Wf725Block& b, const Wf725Block* open, int program,
                                                    int line) {
  const auto fail = [&](int code, std::string message) {
    return Wf725SyntaxError{code, program, b.number, line, std::move(message)};
  };
  const int g = open != nullptr ? open->group(4) : b.group(4);
  const std::string_view pair = wf725_pair_axes(g);
  if (open == nullptr && pair.empty()) return std::nullopt;
  if (b.call)
    return fail(181, fmt::format("the partner block of the G{} pair (N{}) must follow it: a call L cannot be part of "
                                 "an interpolation pair",
                                 g, open != nullptr ? open->number : b.number));
  if (open != nullptr && b.group(4) >= 0 && b.group(4) != g)
    return fail(174, fmt::format("N{} completes the G{} pair of N{}: G{:02} is not allowed there (the same G{} or "
                                 "none)",
                                 b.number, g, open->number, b.group(4), g));
  if (b.axis == 0 || pair.find(b.axis) == std::string_view::npos)
    return fail(174,
                fmt::format("G{} interpolates the axes {} and {}: each block of the pair carries one of their "
                            "letters (N{} has {})",
                            g, pair[0], pair[1], b.number, b.axis == 0 ? std::string("none") : std::string(1, b.axis)));
  if (open != nullptr && b.axis == open->axis)
    return fail(174, fmt::format("G{} pair N{}/N{}: both blocks name axis {}; one block per axis of {}{}", g,
                                 open->number, b.number, b.axis, pair[0], pair[1]));
  if (!b.x) return fail(174, fmt::format("N{}: a block of a G{} pair needs its position X", b.number, g));
  if (b.group(2) >= 0 || b.group(3) >= 0)
    return fail(174, fmt::format("N{}: a block of a G{} pair takes no G function of group 2 or 3 (G04, G68, G69, "
                                 "G99, G53, G54, G92, G93)",
                                 b.number, g));
  if (open != nullptr && open->skippable != b.skippable)
    return fail(174,
                fmt::format("G{} pair N{}/N{}: both blocks or neither are skippable ('/')", g, open->number, b.number));
  return std::nullopt;
}

}  // namespace

std::expected<std::vector<Wf725Program>, Wf725SyntaxError> parse_wf725_programs(std::string_view text,
                                                                                const Wf725ProgramSyntax& syntax) {
  std::vector<Wf725Program> out;
  int line = 0;
  // The opener of an interpolation pair waiting for its partner (index into out.back().blocks), its line.
  constexpr std::size_t none = static_cast<std::size_t>(-1);
  std::size_t open = none;
  int open_line = 0;
  const auto unpaired = [&]() {
    const auto& prog = out.back();
    const auto& b = prog.blocks[open];
    return Wf725SyntaxError{181, prog.number, b.number, open_line,
                            fmt::format("N{} opens a G{} interpolation pair: its partner block (the other axis of "
                                        "the pair) must follow it directly",
                                        b.number, b.group(4))};
  };
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    const std::string_view raw = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++line;
    const std::string_view s = strip(raw);
    if (s.empty()) continue;
    if (s.front() == '%') {
      if (open != none) return std::unexpected(unpaired());
      auto h = parse_header(s, line);
      if (!h) return std::unexpected(h.error());
      for (const auto& q : out)
        if (q.number == h->number)
          return std::unexpected(
              Wf725SyntaxError{220, h->number, 0, line, fmt::format("program %{} given twice", h->number)});
      out.push_back(std::move(*h));
      continue;
    }
    if (out.empty())
      return std::unexpected(
          Wf725SyntaxError{230, 0, 0, line, "a block before the program header: start the program with %<number>"});
    auto& prog = out.back();
    auto b = parse_block(s, line, prog.number, syntax);
    if (!b) return std::unexpected(b.error());
    if (!prog.blocks.empty() && b->number <= prog.blocks.back().number) {
      // Interpolation blocks are converted on entry, in ascending block numbers (181).
      const bool interpolation = open != none || !wf725_pair_axes(b->group(4)).empty();
      return std::unexpected(Wf725SyntaxError{interpolation ? 181 : 220, prog.number, b->number, line,
                                              fmt::format("block N{} after N{}: block numbers ascend within a program",
                                                          b->number, prog.blocks.back().number)});
    }
    if (auto e = check_interpolation(*b, open != none ? &prog.blocks[open] : nullptr, prog.number, line))
      return std::unexpected(std::move(*e));
    const bool opens = open == none && !wf725_pair_axes(b->group(4)).empty();
    prog.blocks.push_back(std::move(*b));
    if (opens) {
      open = prog.blocks.size() - 1;
      open_line = line;
    } else {
      open = none;
    }
  }
  if (open != none) return std::unexpected(unpaired());
  if (out.empty())
    return std::unexpected(Wf725SyntaxError{230, 0, 0, line, "no program: the text has no %<number> header"});
  return out;
}

std::string make_wf725_program_text(const Wf725Program& p) {
  std::string s = fmt::format("%{}", p.number);
  if (!p.valid_axes.empty()) s += " " + p.valid_axes;
  if (p.ram) s += " RAM";
  s += '\n';
  for (const auto& b : p.blocks) {
    if (b.skippable) s += '/';
    s += fmt::format("N{}", b.number);
    if (b.axis != 0) s += fmt::format(" {}", b.axis);
    for (int g : b.g)
      if (g >= 0) s += fmt::format(" G{:02}", g);
    if (b.x) s += fmt::format(" X{}", *b.x);
    if (b.f) s += fmt::format(" F{}", *b.f);
    if (b.m) s += fmt::format(" M{}", *b.m);
    if (b.tool) s += fmt::format(" T{}", *b.tool);
    if (b.call) s += fmt::format(" L{} P{}", *b.call, b.passes.value_or(1));
    s += '\n';
  }
  return s;
}

}  // namespace hil::controllers::s5
