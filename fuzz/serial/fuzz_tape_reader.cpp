// SPDX-License-Identifier: MIT
// Tape reader (ISO/EIA detection, parity, block limits) and the ELG block parser: never crash;
// blocks never exceed the limit; a parsed ELG tape written again reads back the same.
#include <cstdint>
#include <cstdlib>

#include "hil/serial/tape/elg_tape.hpp"
#include "hil/serial/tape/tape_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hil::serial::tape;
  TapeReaderOptions o;
  o.even_block_check = size > 0 && (data[0] & 1);
  o.max_block_length = 254;
  const auto r = read_tape(std::span(data, size), o);
  for (const auto& b : r.blocks)
    if (b.size() > 254) std::abort();
  auto s = parse_elg_blocks(r.blocks);
  if (s) {
    std::vector<std::string> blocks;
    for (const auto& sec : *s) {
      auto b = make_elg_blocks(sec);
      blocks.insert(blocks.end(), b.begin(), b.end());
    }
    auto tape = make_tape(blocks, TapeWriterOptions{});
    if (!tape) std::abort();
    auto again = parse_elg_blocks(read_tape(*tape, TapeReaderOptions{}).blocks);
    if (!again || *again != *s) std::abort();
  }
  return 0;
}
