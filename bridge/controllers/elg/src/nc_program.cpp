// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/nc_program.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

namespace hil::controllers::elg {
namespace {

/// Reads one line's words; errors carry the column-free message (the caller adds line/block).
class LineScanner {
 public:
  explicit LineScanner(std::string_view s) : s_(s) {}

  void skip_space() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\r')) ++i_;
  }
  bool done() {
    skip_space();
    return i_ >= s_.size();
  }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  char get() { return i_ < s_.size() ? s_[i_++] : '\0'; }

  /// A signed decimal number such as "90", "-0.5", ".25", "+3".
  std::optional<double> number() {
    skip_space();
    const std::size_t start = i_;
    if (peek() == '+' || peek() == '-') ++i_;
    bool digits = false;
    while (i_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[i_])) || s_[i_] == '.')) {
      digits = digits || s_[i_] != '.';
      ++i_;
    }
    if (!digits || i_ - start > 16) {
      i_ = start;
      return std::nullopt;
    }
    std::string text(s_.substr(start, i_ - start));
    if (text.front() == '+') text.erase(0, 1);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(v)) {
      i_ = start;
      return std::nullopt;
    }
    return v;
  }
  /// An unsigned integer directly after an address letter.
  std::optional<int> integer(int max) {
    const std::size_t start = i_;
    long v = 0;
    while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) {
      v = v * 10 + (s_[i_] - '0');
      if (v > max) {
        i_ = start;
        return std::nullopt;
      }
      ++i_;
    }
    if (i_ == start) return std::nullopt;
    return static_cast<int>(v);
  }

 private:
  std::string_view s_;
  std::size_t i_ = 0;
};

std::string printable(char ch) {
  if (std::isprint(static_cast<unsigned char>(ch))) return std::string(1, ch);
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02X", static_cast<unsigned char>(ch));
  return buf;
}

}  // namespace

std::string NcError::what() const {
  std::string s = "line " + std::to_string(line);
  if (block >= 0) s += " (N" + std::to_string(block) + ")";
  return s + ": " + message;
}

int NcProgram::find(int n) const noexcept {
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (blocks[i].number == n) return static_cast<int>(i);
  }
  return -1;
}

std::expected<NcProgram, NcError> parse_nc_program(std::string_view text) {
  NcProgram program;
  bool header = false;
  int line_no = 0;
  std::size_t pos = 0;
  constexpr std::size_t max_blocks = 100000;
  while (pos <= text.size()) {
    const std::size_t eol = text.find('\n', pos);
    std::string_view raw = text.substr(pos, eol == std::string_view::npos ? text.size() - pos : eol - pos);
    pos = eol == std::string_view::npos ? text.size() + 1 : eol + 1;
    ++line_no;
    // Strip comments "( ... )".
    std::string line;
    std::string comment;
    int depth = 0;
    for (char ch : raw) {
      if (ch == '(') {
        ++depth;
      } else if (ch == ')' && depth > 0) {
        --depth;
      } else if (depth > 0) {
        comment += ch;
      } else {
        line += ch;
      }
    }
    if (depth > 0) return std::unexpected(NcError{line_no, -1, "comment '(' is not closed on its line"});
    LineScanner sc(line);
    if (sc.done()) continue;
    if (sc.peek() == '%') {
      sc.get();
      auto n = sc.integer(99999);
      if (!n || !sc.done()) return std::unexpected(NcError{line_no, -1, "the header must be %nnn"});
      if (header) return std::unexpected(NcError{line_no, -1, "a second program header"});
      header = true;
      program.number = *n;
      program.comment = comment;
      continue;
    }
    if (!header) return std::unexpected(NcError{line_no, -1, "the program must start with a %nnn header"});
    if (program.blocks.size() >= max_blocks) return std::unexpected(NcError{line_no, -1, "too many blocks"});
    NcBlock block;
    block.line = line_no;
    auto fail = [&](std::string message) {
      return std::unexpected(NcError{line_no, block.number, std::move(message)});
    };
    while (!sc.done()) {
      const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(sc.get())));
      switch (letter) {
        case 'N': {
          auto n = sc.integer(9999);
          if (!n) return fail("N must be followed by a block number 0..9999");
          if (block.number >= 0 || !block.g.empty() || !block.m.empty() || !block.r.empty())
            return fail("the N word must come first in its block");
          block.number = *n;
          break;
        }
        case 'G':
        case 'M': {
          auto n = sc.integer(99);
          if (!n) return fail(std::string(1, letter) + " must be followed by a number 0..99");
          (letter == 'G' ? block.g : block.m).push_back(*n);
          break;
        }
        case 'D': {
          auto n = sc.integer(99);
          if (!n) return fail("D must be followed by a tool offset number 0..99");
          block.d = *n;
          break;
        }
        case 'X':
        case 'Y':
        case 'Z':
        case 'B':
        case 'C':
        case 'F':
        case 'S': {
          auto v = sc.number();
          if (!v) return fail(std::string(1, letter) + " must be followed by a number");
          std::optional<double>* slot = letter == 'X'   ? &block.x
                                        : letter == 'Y' ? &block.y
                                        : letter == 'Z' ? &block.z
                                        : letter == 'B' ? &block.b
                                        : letter == 'C' ? &block.c
                                        : letter == 'F' ? &block.f
                                                        : &block.s;
          if (slot->has_value()) return fail(std::string(1, letter) + " appears twice in the block");
          *slot = *v;
          break;
        }
        case 'R': {
          auto r = sc.integer(999);
          if (!r) return fail("R must be followed by a parameter number 0..999");
          RAssign a;
          a.r = *r;
          sc.skip_space();
          char sign = '\0';
          if ((sc.peek() == '-' || sc.peek() == '+')) {
            LineScanner probe = sc;
            probe.get();
            if (std::toupper(static_cast<unsigned char>(probe.peek())) == 'R') {
              sign = sc.get();
            }
          }
          if (std::toupper(static_cast<unsigned char>(sc.peek())) == 'R') {
            sc.get();
            auto from = sc.integer(999);
            if (!from) return fail("R" + std::to_string(*r) + ": the operand R needs a parameter number");
            a.from_r = *from;
            a.op = sign == '-' ? RAssign::Op::sub : RAssign::Op::add;
          } else {
            auto v = sc.number();
            if (!v) return fail("R" + std::to_string(*r) + " must be followed by a value or an R parameter");
            a.value = *v;
          }
          block.r.push_back(a);
          break;
        }
        case '@': {
          auto code = sc.integer(99);
          if (!code || *code > 6) return fail("@ must be followed by a jump code 00..06");
          NcJump j;
          j.condition = *code;
          sc.skip_space();
          const char dir = sc.get();
          if (dir != '-' && dir != '+') return fail("@: the direction must be '-' or '+'");
          j.backwards = dir == '-';
          sc.skip_space();
          auto target = sc.integer(9999);
          if (!target) return fail("@: the target block number is missing");
          j.target = *target;
          if (j.condition != 0) {
            for (int* operand : {&j.ra, &j.rb}) {
              sc.skip_space();
              if (std::toupper(static_cast<unsigned char>(sc.get())) != 'R')
                return fail("@: the condition needs two R parameters");
              auto n = sc.integer(999);
              if (!n) return fail("@: an R operand needs a parameter number");
              *operand = *n;
            }
          }
          if (block.jump) return fail("two jumps in one block");
          block.jump = j;
          break;
        }
        default:
          return fail("unknown address '" + printable(letter) + "'");
      }
    }
    if (block.number >= 0 && program.find(block.number) >= 0) return fail("block number used twice");
    program.blocks.push_back(std::move(block));
  }
  if (!header) return std::unexpected(NcError{line_no, -1, "no %nnn program header"});
  // Jump targets must exist in the direction written.
  for (std::size_t i = 0; i < program.blocks.size(); ++i) {
    const auto& b = program.blocks[i];
    if (!b.jump) continue;
    const int t = program.find(b.jump->target);
    if (t < 0 || (b.jump->backwards && t > static_cast<int>(i)) || (!b.jump->backwards && t < static_cast<int>(i)))
      return std::unexpected(NcError{
          b.line, b.number, "jump target N" + std::to_string(b.jump->target) + " does not exist in that direction"});
  }
  return program;
}

}  // namespace hil::controllers::elg
