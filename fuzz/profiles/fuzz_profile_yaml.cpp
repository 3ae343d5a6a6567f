// SPDX-License-Identifier: MIT
// The YAML profile loader on arbitrary text: must return a profile or a ConfigError, never crash.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hil/profiles/loader.hpp"
#include "hil/profiles/validation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto p = hil::profiles::load_profile_text(text, "fuzz.yaml");
  if (p) {
    // a loaded profile must be usable: defaults, validation and every id resolve
    const auto set = hil::profiles::default_set(**p);
    (void)hil::profiles::validate(**p, set);
    for (const auto& r : (*p)->all_refs()) (void)(*p)->resolve(r.id());
  } else {
    (void)p.error().describe();
  }
  return 0;
}
