// SPDX-License-Identifier: MIT
// Fuzz the bus URL parser: anything it accepts must print and parse back to the same URL.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/can/bus_url.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  auto url = hil::can::parse_bus_url(input);
  if (url) {
    auto back = hil::can::parse_bus_url(url->to_string());
    if (!back || *back != *url) std::abort();
  } else if (url.error().empty()) {
    std::abort();
  }
  return 0;
}
