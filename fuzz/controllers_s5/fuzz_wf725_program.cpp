// SPDX-License-Identifier: MIT
// WF 725/726 traversing programs: the parser never crashes, a rejected text names a number of the
// memory administration (220, 230..240) or an interpolation error of program input (174, 181), a
// parsed set survives the canonical text, every G17/G18/G19 block of it has its partner (the next
// block, the other axis of the pair), and the program memory takes or refuses it whole (10/64
// programs, 50/350 + 50 blocks).
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/controllers/s5/wf725_program.hpp"
#include "hil/controllers/s5/wf725_program_store.hpp"

using namespace hil::controllers::s5;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto p = parse_wf725_programs(text);
  if (!p) {
    const int c = p.error().code;
    if (c != 220 && c != 174 && c != 181 && (c < 230 || c > 240)) std::abort();
    return 0;
  }
  for (const auto& prog : *p) {
    for (std::size_t i = 0; i < prog.blocks.size(); ++i) {
      const auto pair = wf725_pair_axes(prog.blocks[i].group(4));
      if (pair.empty() || wf725_pair_partner(prog, i)) continue;
      if (i + 1 >= prog.blocks.size() || !wf725_pair_partner(prog, i + 1)) std::abort();
      const char a = prog.blocks[i].axis, b = prog.blocks[i + 1].axis;
      if (a == b || pair.find(a) == std::string_view::npos || pair.find(b) == std::string_view::npos) std::abort();
      if (!prog.blocks[i].x || !prog.blocks[i + 1].x) std::abort();
    }
  }
  for (const auto& prog : *p) {
    auto back = parse_wf725_programs(make_wf725_program_text(prog));
    if (!back || back->size() != 1 || back->front() != prog) std::abort();
  }
  for (const int series : {725, 726}) {
    Wf725ProgramStore store(wf725_memory_limits(series));
    for (const auto& prog : *p) {
      const auto before = store.size();
      const int e = store.store(prog);
      if (e != 0 && e != 123 && e != 124) std::abort();
      if (e != 0 && store.size() != before) std::abort();
      if (store.blocks_used(false) > store.limits().eeprom_blocks ||
          store.blocks_used(true) > store.limits().ram_blocks)
        std::abort();
    }
  }
  return 0;
}
