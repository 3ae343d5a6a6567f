// SPDX-License-Identifier: MIT
#pragma once
// One CLM1.4 program line, parsed (manual §5.7, digest clm14.md §4.2: 55 commands). The text
// form is the one the device stores and sends ("POI 1 +000200.000 999", "CPJ V600>=+V601 0000.00 0400");
// parsing is whitespace-insensitive and the checks are the device's: an axis outside 1..4 is
// error 16, an I/O address outside the address space 1D, a line target above 2999 0E, anything
// else malformed 0A "Invalid Prg Cmd". Pure: text in, Instruction or ProgramError out.

#include <array>
#include <cstdint>
#include <expected>
#include <string>
#include <string_view>

#include "hil/controllers/clm14/address.hpp"
#include "hil/controllers/clm14/error.hpp"
#include "hil/controllers/clm14/number.hpp"

namespace hil::controllers::clm14 {

/// The 55 commands, in the manual's alphabetical order.
enum class Op : std::uint8_t {
  acc,
  aea,
  aeo,
  akn,
  akp,
  ape,
  bac,
  bce,
  bic,
  bio,
  bpa,
  cid,
  cio,
  clc,
  con,
  cou,
  cpj,
  cpl,
  cps,
  cst,
  cvt,
  eos,
  fak,
  fol,
  fun,
  hom,
  jmp,
  jsr,
  jst,
  jtk,
  lmk,
  lml,
  lmr,
  mat,
  mlo,
  mlt,
  nop,
  pbk,
  poa,
  poi,
  psa,
  psi,
  rep,
  rmi,
  rsv,
  rtm,
  rts,
  sac,
  set,
  srm,
  srp,
  txt,
  vcc,
  veo,
  wai,
};
inline constexpr int op_count = 55;
[[nodiscard]] std::string_view mnemonic(Op op) noexcept;

/// A numeric operand: a constant or a variable ("V600", "+V601", "-V604": a sign before a
/// variable negates it, manual §5.6).
struct Num {
  Micro value = 0;
  std::int16_t var = -1;  ///< variable number when >= 0
  bool negate = false;
  [[nodiscard]] bool is_var() const noexcept { return var >= 0; }
};

enum class Cmp : std::uint8_t { eq, ne, lt, gt, le, ge };

/// Operand layout per command (n[] in the order written, see instruction.cpp's table):
///  ACC a acc dec | AEA bit s | AEO a x y sss mmm | AKN bit s | AKP byte pat | APE byte pat
///  BAC tttt ±off n | BCE tttt bit s | BIC base step startbit n m | BIO tttt byte byte2 pat
///  BPA tttt byte pat | CID Vr m ±val | CIO src dst n | CLC tttt | CON a s ±vvv | COU ±off bit n
///  CPJ Vr op ±val tol tttt | CPL a | CPS Vr op ±val tol bit | CST t l | CVT Vr byte f d | EOS
///  FAK a f | FOL a m ±f | FUN ccccccc (pattern[0..6]) | HOM a | JMP/JSR/JST tttt | JTK tttt k
///  LMK a len off | LML a len | LMR a mark off ±barrier | MAT Vr = Va op ±Vb | MLO/MLT a len bit
///  PBK a | POA/POI/PSA/PSI a ±L vvv | REP tttt a dist | RMI a m input | RSV t iiii fffff
///  RTM a m | RTS | SAC a m ±L | SET Vr = ±val | SRM a ±off ±vvv input | SRP a m x Vbase byte
///  TXT m text | VCC a ±L vvv m r | VEO a s e vvv l | WAI sec
/// (FOL, FUN, LMK, LMR, MLO, MLT: layouts decided where the manual lost the figure, docs/clm14.md.)
struct Instruction {
  Op op = Op::nop;
  std::array<Num, 5> n{};
  BitAddress bit{};
  BitAddress bit2{};
  ByteAddress byte{};
  ByteAddress byte2{};
  std::array<std::uint8_t, 8> pattern{};  ///< as written: [0] = bit 7 .. [7] = bit 0; values 0/1/2
  Cmp cmp = Cmp::eq;
  char mat_op = '+';           ///< MAT: + - * /
  std::int16_t var = -1;       ///< the variable a command writes or compares (SET/MAT/CPJ/CPS/CVT/CID/SRP)
  bool counter_reset = false;  ///< COU/BAC offset written "000000": set the count to 0 when stored
  std::string text;            ///< TXT text (16 characters); RSV flags
};

struct ProgramError {
  ClmError error = ClmError::invalid_program_command;
  int line = -1;        ///< program or logic line, -1 when not known
  std::string message;  ///< what is wrong and where, e.g. "line 0012 'POI 7 ...': axis 7 is not 1..4"
};

/// Parse "MNE operands" (the stored line without the line number).
[[nodiscard]] std::expected<Instruction, ProgramError> parse_instruction(std::string_view text);

/// Canonical stored text of a COU/BAC line after its offset was applied: the offset field
/// becomes "+00000" / "+0000" (manual §5.7 COU, digest §4.3). Other lines unchanged.
[[nodiscard]] std::string clear_counter_offset(std::string_view text);

}  // namespace hil::controllers::clm14
