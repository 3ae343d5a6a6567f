// SPDX-License-Identifier: MIT
#pragma once
// The CLM1.4 logic task (manual §6, digest clm14.md §4.5): up to 1000 IL lines with a boolean
// accumulator, compiled on power-up and on leaving Parameter mode, then run continuously.
// Compile errors (unknown instruction or operand, missing END, unbalanced parentheses) are
// error 38 with the line; `END` at line 0000 disables the task. Operands: load from
// M0/M1/M4/M5/M6/Q0/Q1/Q2/I0/I1/I2, store to M5, M6, Q1, Q2.02-Q2.05. Pure.

#include <array>
#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <vector>

#include "hil/controllers/clm14/address.hpp"
#include "hil/controllers/clm14/instruction.hpp"

namespace hil::controllers::clm14 {

enum class LogicOp : std::uint8_t {
  ld,
  ldn,
  st,
  stn,
  set,
  res,
  setc,
  resc,
  setcn,
  rescn,
  and_,
  andn,
  or_,
  orn,
  xor_,
  xorn,
  and_open,
  andn_open,
  or_open,
  orn_open,
  xor_open,
  xorn_open,
  close,
  nop,
  end,
};

/// One compiled instruction: the operand resolved to its byte in Image::bytes() and its bit mask,
/// and the instruction as two truth tables over (accumulator, operand bit), bit index acc * 2 + v:
/// the new accumulator and the new operand bit. A pass then needs no dispatch per line: one select
/// for the accumulator and a write only for the store family (about 1 ns per line, bench_clm14).
struct LogicInstruction {
  LogicOp op = LogicOp::nop;
  std::uint8_t mask = 0;
  std::uint16_t offset = 0;
  std::uint8_t acc_table = 0;
  std::uint8_t bit_table = 0;
};

class LogicProgram {
 public:
  /// Compile lines 0000..0999 (index = line number; missing lines are NOP). Error 38 with the
  /// offending line on failure.
  [[nodiscard]] static std::expected<LogicProgram, ProgramError> compile(const std::vector<std::string>& lines);

  /// One pass over the program on `image` (reads and writes it in place).
  void run(Image& image) const noexcept;
  [[nodiscard]] bool empty() const noexcept { return code_.empty(); }
  /// The output bits of byte `a` the logic task stores to, as a mask: the NC tasks may no longer
  /// drive them (§9.1). 0 for inputs and markers.
  [[nodiscard]] std::uint8_t owned_mask(const ByteAddress& a) const noexcept { return owned_mask_[Image::offset(a)]; }
  [[nodiscard]] std::size_t size() const noexcept { return code_.size(); }

 private:
  std::vector<LogicInstruction> code_;
  std::array<std::uint8_t, Image::size> owned_mask_{};  ///< by Image::offset; outputs only
};

}  // namespace hil::controllers::clm14
