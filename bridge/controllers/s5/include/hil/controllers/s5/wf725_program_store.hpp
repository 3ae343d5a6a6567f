// SPDX-License-Identifier: MIT
#pragma once
// The WF 725/726 program memory (digest §6.2, errors §5.3): at most 10 (WF 725) / 64 (WF 726)
// programs; EEPROM 50 / 350 blocks and RAM 50 blocks, counted over every program stored there.
// Errors are the module's program-I/O numbers (catalogue `program_io`): 123 blocks full, 124
// programs full, 125 program 0, 127 program not available; teach-in 135, 136, 137, 138. A
// refused store changes nothing. Pure.

#include <vector>

#include "hil/controllers/s5/wf725_machine_data.hpp"
#include "hil/controllers/s5/wf725_program.hpp"

namespace hil::controllers::s5 {

class Wf725ProgramStore {
 public:
  explicit Wf725ProgramStore(Wf725MemoryLimits limits = {}) : limits_(limits) {}

  [[nodiscard]] const Wf725MemoryLimits& limits() const noexcept { return limits_; }
  /// Stores `p`, replacing a program of the same number. 0 or 125 / 124 / 123.
  [[nodiscard]] int store(Wf725Program p);
  /// Deletes program `number`: 0 or 125 / 127.
  [[nodiscard]] int remove(int number);
  /// Deletes block `block` of program `program`: 0 or 125 / 126 (block 0) / 127 / 128 (no such block).
  [[nodiscard]] int remove_block(int program, int block);
  /// The numbers of the stored programs, ascending.
  [[nodiscard]] std::vector<int> numbers() const;
  [[nodiscard]] const Wf725Program* find(int number) const noexcept;
  [[nodiscard]] std::size_t size() const noexcept { return programs_.size(); }
  /// Blocks stored in RAM (true) or EEPROM (false).
  [[nodiscard]] int blocks_used(bool ram) const noexcept;
  /// Teach-in: stores `block` (its number is `block_number`) in program `program`, creating the
  /// program in the selected memory when it does not exist and replacing a block of that number.
  /// 0 or 135 (program 0), 136 (block 0), 137 (no free program), 138 (memory full).
  [[nodiscard]] int teach(int program, int block_number, Wf725Block block, bool ram);

 private:
  Wf725MemoryLimits limits_;
  std::vector<Wf725Program> programs_;
};

}  // namespace hil::controllers::s5
