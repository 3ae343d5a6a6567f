// SPDX-License-Identifier: MIT
// Fuzz target for the awN_message16 schedule text (analog_schedule.hpp): any text gives steps with
// strictly increasing times or an error, never a crash or an exception.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/controllers/amkasyn/analog_schedule.hpp"

namespace amk = hil::controllers::amkasyn;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto s = amk::parse_analog_schedule(text);
  if (!s) {
    if (s.error().empty()) std::abort();  // every refusal says why
    return 0;
  }
  if (s->empty()) std::abort();
  for (std::size_t k = 1; k < s->size(); ++k)
    if ((*s)[k].from <= (*s)[k - 1].from) std::abort();
  if (amk::analog_word_at(*s, s->back().from) != s->back().word) std::abort();
  return 0;
}
