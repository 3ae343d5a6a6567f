// SPDX-License-Identifier: MIT
#pragma once
// IP247 traversing programs (VP, DIN 66025 subset; manual §2.6, digest ip247.md §3): the parsed
// form and the firmware's syntax check. Pure: text in, program or the module's syntax error out.
//
// Text: a header line (`%` main / `L` sub, program number 0..255 in at most 3 columns, up to 58
// chars of free text), blocks of at most 50 chars including <LF>, functions in the fixed order
// N L G X F M separated by blanks, and a final block with M02. Rules of §2.6.10 (what may follow
// L, G00, G04, G20, G24, G74, X, F) give errors 5, 6 and 9; loops are matched (13, 14). Run-time
// checks (speeds against vmax, ranges, missing subprograms, nesting depth) belong to the
// interpreter (ip247_interpreter.hpp). Decisions where the manual is silent: docs/ip247.md.

#include <cstdint>
#include <expected>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hil/controllers/s5/ip247_syntax_error.hpp"

namespace hil::controllers::s5 {

inline constexpr std::size_t ip247_max_program_chars = 1023;  ///< per program incl. header (§2.6.1)
inline constexpr std::size_t ip247_max_block_chars = 50;      ///< per block incl. <LF> (§2.6.3)
inline constexpr int ip247_max_program_number = 255;

/// One block. Values as written: `x_milli` in thousandths of the program unit (X-5.5 = -5500).
struct Ip247Block {
  int number = 0;             ///< N (0..999)
  char kind = 'N';            ///< 'N' normal, '/' skippable, ':' main block (all executed alike)
  std::optional<int> call{};  ///< L: subprogram number
  std::optional<int> g{};     ///< G function number
  std::optional<std::int64_t> x_milli{};
  std::optional<std::int32_t> f{};
  std::optional<int> m{};
  int line = 0;      ///< 2 = first block (line 1 is the header)
  int partner = -1;  ///< G24: index of its G20; G20: index of its G24

  [[nodiscard]] bool has_motion() const noexcept { return x_milli.has_value() || g == 74; }
  [[nodiscard]] bool is_dwell() const noexcept { return g == 4; }
  [[nodiscard]] bool is_final() const noexcept { return m == 2; }
  friend bool operator==(const Ip247Block&, const Ip247Block&) = default;
};

struct Ip247Program {
  int number = 0;
  bool subprogram = false;  ///< header `L` (documentation only: any program can be called)
  std::string title{};      ///< free text of the header (without the separating blank)
  std::vector<Ip247Block> blocks{};
  friend bool operator==(const Ip247Program&, const Ip247Program&) = default;
};

/// The firmware syntax check. Nothing is returned unless the whole text is valid.
[[nodiscard]] std::expected<Ip247Program, Ip247SyntaxFault> parse_ip247_program(std::string_view text);

/// Canonical text (`%  7 title`, blocks `N1 X1258.250 F2500`), parseable by parse_ip247_program.
[[nodiscard]] std::string make_ip247_program_text(const Ip247Program& p);

/// The G functions the module implements (§2.6.6).
[[nodiscard]] bool ip247_g_known(int g) noexcept;

}  // namespace hil::controllers::s5
