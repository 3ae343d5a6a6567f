// SPDX-License-Identifier: MIT
// IP247 traversing programs: the syntax check never crashes, a valid program survives the
// canonical text and the VP DB image, and the interpreter runs it to an end or a module error
// without hanging (bounded number of next() calls).
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/controllers/s5/ip247_interpreter.hpp"
#include "hil/controllers/s5/ip247_program.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"

using namespace hil::controllers::s5;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto p = parse_ip247_program(text);
  auto db = make_ip247_vp_db({.db = 1, .text = std::string(text)});
  if (db) {
    auto back = parse_ip247_vp_db(*db);
    if (!back) std::abort();
  }
  if (!p) {
    if (p.error().code == Ip247SyntaxError::none) std::abort();
    return 0;
  }
  const std::string canon = make_ip247_program_text(*p);
  auto again = parse_ip247_program(canon);
  if (!again || again->blocks.size() != p->blocks.size()) std::abort();
  for (std::size_t i = 0; i < p->blocks.size(); ++i) {
    const auto& a = p->blocks[i];
    const auto& b = again->blocks[i];
    if (a.number != b.number || a.g != b.g || a.x_milli != b.x_milli || a.f != b.f || a.m != b.m || a.call != b.call) {
      std::abort();
    }
  }
  Ip247MachineData md;
  md.sw_start = -100'000'000 + 1;
  md.sw_end = 100'000'000 - 1;
  md.reference_coordinate = 0;
  Ip247Interpreter in([&](int n) { return n == p->number ? &*p : nullptr; });
  Ip247Offsets off;
  if (in.start(p->number, md, 0, false) != hil::stepdir::Ip247Error::none) std::abort();
  for (int k = 0; k < 2000 && in.running(); ++k) (void)in.next(off);
  return 0;
}
