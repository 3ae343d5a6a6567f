// SPDX-License-Identifier: MIT
// 3964R receiver fed arbitrary bytes with arbitrary gaps: never crash, every delivered block
// re-framed is a valid block; output is only DLE/NAK/STX-framed data.
#include <cstdint>
#include <cstdlib>

#include "hil/serial/s5/procedure_3964r.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hil::serial::s5;
  ProcedureOptions o;
  o.high_priority = size > 0 && (data[0] & 1);
  o.with_bcc = size > 1 && (data[1] & 1);
  o.max_block = 64;
  Procedure3964 p(o);
  if (size > 2 && (data[2] & 1)) p.send({data, data + std::min<std::size_t>(size, 16)});
  hil::TimePoint now{};
  for (std::size_t i = 0; i < size; i += 5) {
    p.on_bytes(std::span(data + i, std::min<std::size_t>(5, size - i)), now);
    now += std::chrono::milliseconds(data[i] % 256);
    p.poll(now);
    (void)p.take_output();
    while (auto b = p.take_received())
      if (b->size() > o.max_block) std::abort();
    (void)p.take_send_result();
  }
  return 0;
}
