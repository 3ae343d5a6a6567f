// SPDX-License-Identifier: MIT
// CLM1.4 telegram parser + line splitter: never crash; a parsed telegram re-made with its
// checksum must parse back to the same telegram.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/serial/clm14/serial_error.hpp"
#include "hil/serial/clm14/telegram.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hil::serial::clm14;
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  LineSplitter sp;
  for (char c : in) {
    if (sp.feed(c) != LineSplitter::Event::line) continue;
    const std::string line = sp.take_line();
    for (bool strict : {true, false}) {
      auto t = parse_telegram(line, strict);
      if (!t || t->is_confirmation()) continue;
      const std::string wire = make_telegram(*t, true);
      auto back = parse_telegram(std::string_view(wire).substr(0, wire.size() - 2), true);
      if (!back || back->body != t->body || back->lead != t->lead || back->station != t->station) std::abort();
      (void)parse_error_body(t->body);
    }
  }
  return 0;
}
