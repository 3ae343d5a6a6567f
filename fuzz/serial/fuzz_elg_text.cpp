// SPDX-License-Identifier: MIT
// ELG tape text files (what users edit): never crash; parse(make(parse(x))) == parse(x).
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/serial/tape/elg_tape.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hil::serial::tape;
  auto s = parse_elg_text(std::string_view(reinterpret_cast<const char*>(data), size));
  if (s) {
    auto again = parse_elg_text(make_elg_text(*s));
    if (!again || *again != *s) std::abort();
  }
  return 0;
}
