// SPDX-License-Identifier: MIT
// Fuzz the CLM1.4 program-line parser and the logic-task compiler: any bytes give a parsed
// line or a ProgramError with a device error number, never a crash. The corpus has every
// command's syntax, including the master-encoder and flying-cutoff commands (FOL, FUN, LMK, LMR,
// LML, MLO, MLT, EOS, AEO, VEO 5, FAK 5, SRP).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hil/controllers/clm14/instruction.hpp"
#include "hil/controllers/clm14/logic_task.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hil::controllers::clm14;
  const std::string text(reinterpret_cast<const char*>(data), size);
  (void)parse_instruction(text);
  (void)clear_counter_offset(text);
  std::vector<std::string> lines;
  std::string cur;
  for (char c : text) {
    if (c == '\n') {
      lines.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  lines.push_back(cur);
  for (const auto& l : lines) (void)parse_instruction(l);  // a multi-line input: each line as a program line
  if (auto p = LogicProgram::compile(lines)) {
    Image image;
    p->run(image);
  }
  return 0;
}
