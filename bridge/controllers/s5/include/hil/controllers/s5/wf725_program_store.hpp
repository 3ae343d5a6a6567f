// SPDX-License-Identifier: MIT
#pragma once
// The WF 725/726 program memory (digest §6.2, errors §5.3): at most 10 (WF 725) / 64 (WF 726)
// programs; EEPROM 50 / 350 blocks and RAM 50 blocks, counted over every program stored there.
// Errors are the module's program-I/O numbers (catalogue `program_io`): 123 blocks full, 124
// programs full, 125 program 0, 127 program not available, 105 the program is being processed;
// teach-in 135, 136, 137, 138. A refused store changes nothing.
// The memory is the module's: the axes of one module share it (docs/wf725.md, "Several axes").
// A program an axis runs (registered users say which) is never replaced, changed or deleted
// (105), and a stored program never moves (the axes keep pointers to the programs they run).
// Pure; thread: the module's cycle thread.

#include <cstdint>
#include <functional>
#include <list>
#include <utility>
#include <vector>

#include "hil/controllers/s5/wf725_machine_data.hpp"
#include "hil/controllers/s5/wf725_program.hpp"

namespace hil::controllers::s5 {

class Wf725ProgramStore {
 public:
  /// Whether a user (an axis) runs the stored program `number` (main or subprogram).
  using InUse = std::function<bool(int number)>;

  explicit Wf725ProgramStore(Wf725MemoryLimits limits = {}) : limits_(limits) {}

  [[nodiscard]] const Wf725MemoryLimits& limits() const noexcept { return limits_; }
  /// Stores `p`, replacing a program of the same number. 0 or 125 / 124 / 123 / 105.
  [[nodiscard]] int store(Wf725Program p);
  /// Deletes program `number`: 0 or 125 / 127 / 105.
  [[nodiscard]] int remove(int number);
  /// Deletes block `block` of program `program`: 0 or 125 / 126 (block 0) / 127 / 128 (no such block).
  [[nodiscard]] int remove_block(int program, int block);
  /// The numbers of the stored programs, ascending.
  [[nodiscard]] std::vector<int> numbers() const;
  [[nodiscard]] const Wf725Program* find(int number) const noexcept;
  [[nodiscard]] std::size_t size() const noexcept { return programs_.size(); }
  /// The stored programs in storage order.
  [[nodiscard]] const std::list<Wf725Program>& all() const noexcept { return programs_; }
  /// Blocks stored in RAM (true) or EEPROM (false).
  [[nodiscard]] int blocks_used(bool ram) const noexcept;
  /// Teach-in: stores `block` (its number is `block_number`) in program `program`, creating the
  /// program in the selected memory when it does not exist and replacing a block of that number.
  /// 0 or 135 (program 0), 136 (block 0), 137 (no free program), 138 (memory full), 105 (runs).
  [[nodiscard]] int teach(int program, int block_number, Wf725Block block, bool ram);

  /// Registers an axis that runs programs of this memory; returns its id for remove_user.
  int add_user(InUse in_use);
  void remove_user(int id) noexcept;
  /// Whether some registered axis runs program `number`.
  [[nodiscard]] bool in_use(int number) const;
  /// Counts every change of the stored programs (a state file saves when it moved).
  [[nodiscard]] std::uint64_t revision() const noexcept { return revision_; }

 private:
  Wf725MemoryLimits limits_;
  std::list<Wf725Program> programs_;  // a list: a stored program never moves
  std::vector<std::pair<int, InUse>> users_;
  int next_user_ = 0;
  std::uint64_t revision_ = 0;
};

}  // namespace hil::controllers::s5
