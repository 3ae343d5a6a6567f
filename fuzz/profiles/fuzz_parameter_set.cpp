// SPDX-License-Identifier: MIT
// One device's parameter-set parser (chosen by HIL_FUZZ_DEVICE) on arbitrary text: parse, validate
// and write back; the written text must parse again without new problems.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/profiles/loader.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/validation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto profile = [] {
    auto p = hil::profiles::find_profile(HIL_FUZZ_DEVICE);
    if (!p) std::abort();  // the shipped profile must load
    return *p;
  }();
  static const auto parser = hil::profiles::make_parameter_set_parser(profile);
  if (!parser) std::abort();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto r = parser->parse(text);
  for (const auto& p : r.problems) (void)p.describe("fuzz");
  if (r.set.entries.size() <= 3) (void)hil::profiles::validate(*profile, r.set);
  const auto written = parser->write(r.set);
  const auto again = parser->parse(written);
  if (again.set.entries.size() != r.set.entries.size()) std::abort();  // write/parse must round-trip
  return 0;
}
