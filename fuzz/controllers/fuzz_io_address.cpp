// SPDX-License-Identifier: MIT
// The controllers' I/O address parsers (CLM1.4 `Ix.yy.z`, S5 `E 4.1` / `DB10 D 2.0`) under
// arbitrary text: never crash, and what parses formats back to text that parses to the same
// address (the round trip the scenario loader and the reports rely on), and maps onto the image
// inside the bounds the mapping promises.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hil/controllers/io_address_clm.hpp"
#include "hil/controllers/io_address_s5.hpp"

namespace {
using namespace hil::controllers;

void check(bool ok) {
  if (!ok) __builtin_trap();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  (void)is_clm_unused(text);
  if (auto clm = parse_clm_address(text)) {
    const auto again = parse_clm_address(format_clm_address(*clm));
    check(again && *again == *clm);
    const BitAddress b = to_bit_address(*clm);
    check(b.bit < 8 && b.byte < (clm_max_group + 1u) * clm_group_stride);
  } else {
    check(!clm.error().empty());
  }
  const S5DataBlock blocks[] = {{10, 0, 64}, {11, 128, 256}};
  for (const auto default_db : {std::optional<std::uint16_t>{}, std::optional<std::uint16_t>{10}}) {
    auto s5 = parse_s5_address(text, default_db);
    if (!s5) {
      check(!s5.error().empty());
      continue;
    }
    const auto again = parse_s5_address(format_s5_address(*s5), default_db);
    check(again && *again == *s5);
    if (s5->is_bit()) {
      if (auto b = to_bit_address(*s5, blocks)) check(b->bit < 8);
    } else {
      (void)to_byte_address(*s5, blocks);
    }
  }
  return 0;
}
