// SPDX-License-Identifier: MIT
#pragma once
// The AWL (S5-style statement list) subset an APSF function block runs (manual §3.11): a parser
// from the PS listing text and a step-bounded interpreter. Pure: memory goes through AwlMemory.
//
// Listing: one statement per line, an optional label "NAME:" (up to 4 characters, S5 style) in
// front, ";" or "//" starts a comment; a first line "FB n" and "NAME:..." header lines are allowed.
//   load / transfer    L, T  EB/EW/ED n, AB/AW/AD n, MB/MW/MD n, DW/DD n (the opened DB),
//                      constants (L only) KF -32768..32767, KB 0..255, KH 0..FFFF, KM 16 bits,
//                      KD 32-bit (AMK)
//   arithmetic         +F -F xF :F (16 bit), +D -D xD :D (32 bit), WWD (ACCU1 low word -> 32 bit
//                      signed, AMK from V02.09), TAK (swap ACCU1/ACCU2), ADD KF n
//   word logic, shifts UW OW XOW (ACCU2 with ACCU1, 16 bit), KEW / KZW (one's / two's complement of
//                      the low word), SLW / SRW n (0..15, logical, 16 bit), SLD / SRD n (0..32, 32 bit)
//   compare -> RLO     !=F ><F >F >=F <F <=F and the D forms (ACCU2 against ACCU1)
//   bit logic          U UN O ON E/A/M byte.bit; = S R A/M byte.bit
//   jumps              SPA SPB SPBN SPZ SPN SPP SPM =label (within the block)
//   block end          BE, BEA, BEB (if RLO = 1)
//   open DB            A DB n
// Forbidden in an APSF (a running time error, SF error 6): the timers SI SV SE SS SA and R T, block
// calls SPA/SPB FB|PB|OB|SB, E DB, STP, STS. Anything else is a parse error naming the line.
// Arithmetic wraps (two's complement); ":F" / ":D" by 0 give 0 (decision: the S5 sets an
// overflow flag the subset has no use for).

#include <cstdint>
#include <expected>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace hil::controllers::amkasyn {

enum class AwlArea : std::uint8_t { none, e, a, m, db, constant };

struct AwlInstruction {
  enum class Op : std::uint8_t {
    load,
    transfer,
    add_f,
    sub_f,
    mul_f,
    div_f,
    add_d,
    sub_d,
    mul_d,
    div_d,
    wwd,
    tak,
    and_w,
    or_w,
    xor_w,
    not_w,
    neg_w,
    shl_w,
    shr_w,
    shl_d,
    shr_d,
    add_k,
    cmp_f,
    cmp_d,
    and_bit,
    and_not,
    or_bit,
    or_not,
    assign,
    set,
    reset,
    jump,
    jump_rlo,
    jump_not_rlo,
    jump_zero,
    jump_not_zero,
    jump_pos,
    jump_neg,
    block_end,
    block_end_rlo,
    open_db,
    forbidden,
  };
  Op op = Op::block_end;
  AwlArea area = AwlArea::none;
  int width = 0;              ///< 1 bit, 8, 16 or 32
  int address = 0;            ///< byte / word number, DB number, jump target (instruction index)
  int bit = 0;                ///< bit number of a bit operand
  std::int32_t constant = 0;  ///< L K.., ADD KF; the compare kind (0 ==, 1 <>, 2 >, 3 >=, 4 <, 5 <=)
  int line = 0;               ///< 1-based listing line
  std::string text;           ///< the statement as written (for errors)
};

/// A parsed FB. `forbidden` lists the forbidden statements (line and text); the SF refuses START
/// when it is not empty.
struct AwlProgram {
  std::vector<AwlInstruction> code;
  std::vector<std::string> forbidden;
};

/// Parse a listing; the error names the line, the statement and the rule.
[[nodiscard]] std::expected<AwlProgram, std::string> parse_awl(std::string_view text);

/// The memory an FB sees (bytes of E/A/M; words and double words of the opened DB, which may be
/// absent). Called only from run_awl, on the caller's thread.
class AwlMemory {
 public:
  virtual ~AwlMemory() = default;
  [[nodiscard]] virtual std::uint8_t byte(AwlArea area, int n) const noexcept = 0;
  virtual void set_byte(AwlArea area, int n, std::uint8_t v) noexcept = 0;
  /// Data word n of the open DB (false: no DB open or n beyond its end).
  virtual bool db_word(int db, int n, std::uint16_t& v) const noexcept = 0;
  virtual bool set_db_word(int db, int n, std::uint16_t v) noexcept = 0;
};

struct AwlRun {
  bool ok = true;
  std::string error;  ///< what went wrong at which line (budget exceeded, no DB open, ...)
  int steps = 0;
};

/// Runs the FB once from its first statement until a block end (or the end of the code), at most
/// `budget` statements. `open_db` is the DB opened at the start (0 = none).
[[nodiscard]] AwlRun run_awl(const AwlProgram& program, AwlMemory& memory, int open_db, int budget) noexcept;

using FbStore = std::map<int, AwlProgram>;

}  // namespace hil::controllers::amkasyn
