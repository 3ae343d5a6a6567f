// SPDX-License-Identifier: MIT
// Fuzz target for the AMKASYN DB text codec (db_text.hpp): any text gives DataBlocks or an error
// naming a line inside the text, never a crash, an exception or a block beyond its size.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/controllers/amkasyn/db_text.hpp"

namespace amk = hil::controllers::amkasyn;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  int lines = 1;
  for (char c : text) lines += c == '\n' ? 1 : 0;
  if (auto sf = amk::parse_sf_db_text(text)) {
    if (sf->init.size() != 10 || sf->command.size() != 34) std::abort();
  } else if (sf.error().line < 1 || sf.error().line > lines) {
    std::abort();
  }
  if (auto t = amk::parse_table_db_text(text)) {
    if (t->size() > amk::max_table_words) std::abort();
  } else if (t.error().line < 1 || t.error().line > lines) {
    std::abort();
  }
  return 0;
}
