// SPDX-License-Identifier: MIT
// Fuzz target for the scenario loader: any bytes must give a Scenario or a ConfigError, never a
// crash, hang or exception; and a ConfigError must say what is wrong.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/core/duration_text.hpp"
#include "hil/runtime/scenario_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto r = hil::runtime::parse_scenario(text, "fuzz.yaml");
  if (!r) {
    if (r.error().message.empty() || r.error().file != "fuzz.yaml") std::abort();
    (void)r.error().describe();
  } else {
    // Loaded scenarios are internally consistent: every step and expectation names an axis.
    if (r->axes.empty()) std::abort();
    for (const auto& e : r->expectations)
      if (!r->find_axis(e.axis)) std::abort();
  }
  (void)hil::runtime::parse_duration(text.substr(0, 32));
  // The CLI's reading of the same grammar: a bare number in an option's old unit.
  if (const auto d = hil::parse_duration_text(text.substr(0, 32), "us"); d && *d < hil::Duration::zero()) std::abort();
  (void)hil::is_bare_number(text.substr(0, 32));
  (void)hil::runtime::parse_ratio(text.substr(0, 32));
  (void)hil::runtime::parse_fault_code(text.substr(0, 32));
  return 0;
}
