// SPDX-License-Identifier: MIT
// The SINUMERIK System 3 NC program parser and interpreter under arbitrary input: parse, then run
// what parses for a bounded number of cycles against a machine that is always in position.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hil/controllers/elg/nc_interpreter.hpp"

namespace {
struct NullMachine final : hil::controllers::elg::NcMachine {
  void move(const hil::controllers::elg::NcTargets& t, bool, double) override { at = t; }
  bool in_position() const override { return true; }
  hil::controllers::elg::NcTargets position() const override { return at; }
  void spindle(double, int) override {}
  void m_function(int) override {}
  hil::controllers::elg::NcTargets at;
};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto program = hil::controllers::elg::parse_nc_program(text);
  if (!program) {
    (void)program.error().what();
    return 0;
  }
  hil::controllers::elg::NcInterpreter nc(std::move(*program));
  NullMachine machine;
  for (int cycle = 0; cycle < 2000 && nc.step(cycle * 0.001, machine) == hil::controllers::elg::NcState::running;
       ++cycle) {
  }
  return 0;
}
