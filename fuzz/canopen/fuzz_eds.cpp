// SPDX-License-Identifier: MIT
// Fuzz target: the CiA 306 EDS/DCF parser must return a description or a ConfigError for any input.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hil/canopen/eds.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto d = hil::canopen::parse_eds(text, "fuzz.eds", 7);
  if (!d) (void)d.error().describe();
  return 0;
}
