// SPDX-License-Identifier: MIT
// Fuzz the candump log-line and cansend frame-spec parsers with a format round trip.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "hil/can/candump.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace cd = hil::can::candump;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  std::size_t start = 0;
  while (start <= input.size()) {
    auto nl = input.find('\n', start);
    if (nl == std::string_view::npos) nl = input.size();
    const auto line = input.substr(start, nl - start);
    if (auto r = cd::parse_log_line(line)) {
      std::string out;
      cd::format_log_line(out, *r);
      auto back = cd::parse_log_line(out);
      if (!back || back->frame != r->frame || back->interface != r->interface) std::abort();
    }
    if (auto f = cd::parse_frame_spec(line)) {
      auto back = cd::parse_frame_spec(cd::format_frame_spec(*f));
      if (!back || *back != *f) std::abort();
    }
    start = nl + 1;
  }
  return 0;
}
