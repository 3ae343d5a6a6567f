// SPDX-License-Identifier: MIT
#pragma once
// The SINUMERIK System 3 part-program subset the ELG's hobbing cycles need (manual 13.2, digest
// §11.1): `%nnn` header, N blocks (the N word is optional: a block without one continues the
// numbering), G0/G1 rapid and feed, G90/G91 absolute/incremental, G94/G95 feed per minute/per
// revolution, G04 dwell (F seconds), F feed, S spindle speed, M functions, R-parameter assignment
// and addition, axis words X Y Z B C, and the `@` conditional jump. Plane selection and cutter
// radius compensation (G17-G19, G40-G42, D) are accepted and recorded but do not change the path
// (docs/elg.md: the simulated tool point is the programmed point).
//
// Decisions where the manual's example is the only source (digest §11.1 [I], docs/elg.md):
// - `R14 R15` (R parameter followed by R parameter) adds: R14 := R14 + R15; `R14 -R15` subtracts.
// - `@0c d nn Ra Rb` jumps in direction d ('-' backwards, '+' forwards) to block N nn when the
//   condition c holds between Ra and Rb: 0 always, 1 Ra = Rb, 2 Ra != Rb, 3 Ra > Rb, 4 Ra >= Rb,
//   5 Ra < Rb, 6 Ra <= Rb. The example's `@03 - 20 R21 R14` so repeats N20 while Z2 > tooth count.

#include <cstdint>
#include <expected>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hil::controllers::elg {

/// A parse error with the line (1-based) and the block number, and what is wrong.
struct NcError {
  int line = 0;
  int block = -1;  ///< N number of the block, -1 when it has none
  std::string message;
  std::string what() const;
};

/// One R-parameter operation of a block.
struct RAssign {
  int r = 0;
  enum class Op : std::uint8_t { set, add, sub } op = Op::set;
  double value = 0.0;         ///< for set with a constant
  std::optional<int> from_r;  ///< the R operand of add/sub/set
};

/// The `@` jump of a block.
struct NcJump {
  int condition = 0;  ///< 0..6 (see the file comment)
  bool backwards = true;
  int target = 0;      ///< N number
  int ra = 0, rb = 0;  ///< R operands (conditions 1..6)
};

struct NcBlock {
  int number = -1;  ///< N word, -1 if absent
  int line = 0;
  std::vector<int> g;                   ///< G functions in block order
  std::vector<int> m;                   ///< M functions in block order
  std::optional<double> x, y, z, b, c;  ///< axis words
  std::optional<double> f;              ///< F: feed, or dwell seconds with G04
  std::optional<double> s;              ///< S: spindle speed, rpm
  std::optional<int> d;                 ///< D: tool offset number (recorded only)
  std::vector<RAssign> r;
  std::optional<NcJump> jump;
};

struct NcProgram {
  int number = 0;       ///< %nnn
  std::string comment;  ///< text in parentheses after the header
  std::vector<NcBlock> blocks;
  /// Index of the block with N `number`, or -1.
  int find(int number) const noexcept;
};

/// Parses a program text. Bad input: the line and block, what is wrong; nothing is half-built.
std::expected<NcProgram, NcError> parse_nc_program(std::string_view text);

}  // namespace hil::controllers::elg
