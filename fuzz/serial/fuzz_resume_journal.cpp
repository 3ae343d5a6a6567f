// SPDX-License-Identifier: MIT
// The upload resume journal (FILE.hilbridge-resume, which a crash may truncate or a user edit):
// any bytes give a journal or none, never a crash; a journal read back from what it writes is
// the same journal.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/serial/item_transfer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using hil::serial::ResumeJournal;
  const auto j = ResumeJournal::parse(std::string_view(reinterpret_cast<const char*>(data), size));
  if (!j) return 0;
  const auto again = ResumeJournal::parse(j->text());
  if (!again || again->hash != j->hash || again->next != j->next || again->device != j->device) std::abort();
  return 0;
}
