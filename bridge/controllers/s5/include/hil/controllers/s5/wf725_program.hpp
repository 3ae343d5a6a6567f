// SPDX-License-Identifier: MIT
#pragma once
// WF 725/726 traversing programs (digest wf725-726.md §6.2; the block structure the manual
// documents, the rest decided in docs/wf725.md). A program file holds one or more programs:
//
//   %5 A RAM                               header: program number 1..255, the axes it is valid
//   N1 G90 X 1000 000 F 12 000              for (A, B, C; none = every axis), memory (EEPROM
//   N2 G90 G92 G68 X 2000 000 F 10 000 M0   default, or RAM)
//   /N3 G91 X -500 F 4000 M21 T3            '/' = skippable block ("skip block" interface bit)
//   N4 G04 F 1500                           dwell 1500 ms
//   N5 L7 P2                                call program 7, 2 passes
//
// A block: N (1..255) [axis letter A/B/C], up to four G functions, one per group, X (position
// or distance in resolution units, µm or 10^-3 degree), F (feed, 10^-2 mm/min as MD 3; the
// dwell time in ms with G04), one M (0..99), T (tool offset 0..20, 0 = deselect), L/P
// (subprogram and passes). Numbers may carry the manual's digit-group blanks ("1000 000").
// ';' starts a comment. G groups (decision, profile wf725-726.yaml `program`):
//   group 1: G90 absolute, G91 incremental               (errors 83 / 232)
//   group 2: G04 dwell, G68/G69 continuous travel -/+ (flying measurement / setting of actual
//            value), G99 wait for the external read-in enable   (84 / 233)
//   group 3: G53 cancel zero offset, G54 zero offset (the T offset memory as a zero offset is
//            not modelled: G54 shifts by the tool offset memory entry given by T), G92 set actual
//            value, G93 cancel set actual value             (85 / 234)
//   group 4: G17/G18/G19 interpolation, G23..G29 (block change MD 46), G73..G79 (MD 47)  (86 / 235)
// Syntax errors carry the STEP 5 memory administration's numbers (§6.1.3, 230..240), which
// validate blocks on input; a syntax rule the manual gives no number for is 220 ("wrong
// parameters", the text is the FB's input). Interpolation pairs (G17 A+B, G18 A+C, G19 B+C: the
// block with the G and the next block, one per axis of the pair, each with X) are checked on
// input with the program-I/O numbers 174 (letters/G/X do not fit the pair) and 181 (the partner
// does not follow, or the numbers do not ascend). Nothing of a faulty file is stored. Pure.

#include <array>
#include <cstdint>
#include <expected>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hil/profiles/profile.hpp"

namespace hil::controllers::s5 {

struct Wf725Block {
  int number = 0;                 ///< N 1..255
  char axis = 0;                  ///< 'A', 'B', 'C' in combined programs, else 0
  bool skippable = false;         ///< '/'
  std::array<int, 4> g{};         ///< per group 1..4 the G number, -1 = none
  std::optional<std::int64_t> x;  ///< µm (10^-3 degree)
  std::optional<std::int64_t> f;  ///< 10^-2 mm/min; G04: dwell in ms
  std::optional<int> m;           ///< 0..99
  std::optional<int> tool;        ///< T 0..20
  std::optional<int> call;        ///< L: subprogram number
  std::optional<int> passes;      ///< P: passes of the call

  Wf725Block() { g.fill(-1); }
  [[nodiscard]] bool has_g(int n) const noexcept {
    for (int v : g)
      if (v == n) return true;
    return false;
  }
  [[nodiscard]] int group(int k) const noexcept { return g[static_cast<std::size_t>(k - 1)]; }
  friend bool operator==(const Wf725Block&, const Wf725Block&) = default;
};

struct Wf725Program {
  int number = 0;
  std::string valid_axes;  ///< "A", "AB", ...; empty = every axis
  bool ram = false;        ///< stored in RAM (else EEPROM)
  std::vector<Wf725Block> blocks;
  [[nodiscard]] bool valid_for(char axis) const noexcept {
    return valid_axes.empty() || valid_axes.find(axis) != std::string::npos;
  }
  [[nodiscard]] const Wf725Block* find(int block_number) const noexcept {
    for (const auto& b : blocks)
      if (b.number == block_number) return &b;
    return nullptr;
  }
  friend bool operator==(const Wf725Program&, const Wf725Program&) = default;
};

/// A rejected program text: the number of the STEP 5 memory administration (§6.1.3), where.
struct Wf725SyntaxError {
  int code = 0;         ///< 220, 230..240; 174 / 181 (program I/O: interpolation pairs)
  int program = 0;      ///< program number (0 before the header)
  int block = 0;        ///< N of the faulty block (0: header)
  int line = 0;         ///< 1-based line of the text
  std::string message;  ///< what is wrong and what to write instead
};

/// The axis pair G17 / G18 / G19 interpolates ("AB", "AC", "BC"); empty for any other G.
[[nodiscard]] std::string_view wf725_pair_axes(int g) noexcept;
/// Whether block `i` of `p` is the partner (second block) of an interpolation pair: the block
/// before it opens a pair (G17/G18/G19) and is not itself a partner.
[[nodiscard]] inline bool wf725_pair_partner(const Wf725Program& p, std::size_t i) noexcept {
  bool partner = false;  // of block k, walking from the start
  for (std::size_t k = 1; k <= i && k < p.blocks.size(); ++k)
    partner = !partner && !wf725_pair_axes(p.blocks[k - 1].group(4)).empty();
  return partner;
}

/// G group (1..4) of G number `g` in the built-in table (= profile table program_g_functions),
/// 0 when the WF has no such G function.
[[nodiscard]] int wf725_g_group(int g) noexcept;

/// The G functions a program may use and their groups (G00..G99; group 0 = no such G).
struct Wf725ProgramSyntax {
  std::array<std::uint8_t, 100> g_group{};
  [[nodiscard]] int group(std::int64_t g) const noexcept {
    return g >= 0 && g < 100 ? g_group[static_cast<std::size_t>(g)] : 0;
  }
};
/// The built-in table (wf725_g_group).
[[nodiscard]] Wf725ProgramSyntax wf725_default_syntax() noexcept;
/// The table of the profile (`tables: program_g_functions`, rows {g, group}); the built-in one
/// when the profile has none. Error text names the bad row.
[[nodiscard]] std::expected<Wf725ProgramSyntax, std::string> wf725_program_syntax(const profiles::Profile& profile);

/// Parses every program of `text` (at least one). All or nothing.
[[nodiscard]] std::expected<std::vector<Wf725Program>, Wf725SyntaxError> parse_wf725_programs(
    std::string_view text, const Wf725ProgramSyntax& syntax = wf725_default_syntax());
/// Canonical text of a program (parses back to the same program).
[[nodiscard]] std::string make_wf725_program_text(const Wf725Program& p);

}  // namespace hil::controllers::s5
