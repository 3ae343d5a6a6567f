// SPDX-License-Identifier: MIT
// Fuzz the register-profile loader: any text gives a profile or a ConfigError, never a crash;
// an accepted profile always yields a valid exchange plan.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "hil/modbus/exchange_plan.hpp"
#include "hil/modbus/profile.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto p = hil::modbus::parse_profile(text, "fuzz.yaml");
  if (p && !hil::modbus::make_exchange_plan(*p)) std::abort();
  if (!p && p.error().message.empty()) std::abort();
  return 0;
}
