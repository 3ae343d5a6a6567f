// SPDX-License-Identifier: MIT
// Fuzz the socketcand stream splitter and element parser; every element that parses must
// format and parse back to the same value (for frame elements).
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "hil/can/socketcand.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace sc = hil::can::socketcand;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  sc::ElementSplitter splitter;
  // Feed in two uneven pieces to exercise elements split across reads.
  const auto cut = size / 3;
  splitter.feed(input.substr(0, cut));
  sc::ElementSplitter::Item item;
  std::size_t seen = 0;
  auto drain = [&] {
    while (splitter.next(item)) {
      ++seen;
      if (item.error) continue;
      auto e = sc::parse_element(item.element);
      if (!e) continue;
      std::string out;
      sc::format_element(out, *e);
      if (std::holds_alternative<sc::Send>(*e) || std::holds_alternative<sc::RxFrame>(*e) ||
          std::holds_alternative<sc::Open>(*e) || std::holds_alternative<sc::ErrorFrame>(*e)) {
        auto back = sc::parse_element(out);
        if (!back || *back != *e) std::abort();
      }
    }
  };
  drain();
  splitter.feed(input.substr(cut));
  drain();
  if (splitter.buffered() > sc::max_element_size + size) std::abort();
  (void)sc::parse_element(input);
  return 0;
}
