// SPDX-License-Identifier: MIT
// Fuzz target for the AMKASYN SF runtime (an interpreter of init/commanding DBs and tables): any
// init DB, commanding DB, table DB and input stream must give a status or run cycles, never a
// crash, hang or exception; a START that failed leaves the slot in RESET with an error text.
//   bytes: [type][fct][ba][init words 2..9: 16 bytes][command words 2..33: 64 bytes]
//          [table DB 1: up to 128 bytes][APSF only: FB listing, length byte + text]
//          [per cycle: E byte, M byte, position step (2 bytes)][IMES/EPOS only: pulse byte]...
// The FB listing goes through the AWL parser (SfRuntime::load_fb as FB DW4); pulse bits feed the
// zero-pulse latch of AZ message 1..4 (IMES) and the drives' reference latch (EPOS); at the end a
// READ VALUE (XFIPW) is commanded. (The type-dependent parts keep the older seeds' layout.)
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>

#include "hil/controllers/amkasyn/sf_runtime.hpp"

namespace amk = hil::controllers::amkasyn;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::span<const std::uint8_t> in(data, size);
  auto take = [&]() -> std::uint8_t {
    if (in.empty()) return 0;
    const std::uint8_t b = in.front();
    in = in.subspan(1);
    return b;
  };
  auto word = [&]() { return static_cast<std::int32_t>(take() | (take() << 8)); };
  const std::uint8_t type = take() % 13, fct = take(), ba = take();
  amk::DataBlock init(10), cmd(34), tab(64);
  init.set_dr(0, type).set_dl(0, 0);
  for (std::size_t w = 1; w < 10; ++w) init.set_dw(w, word());
  init.set_dl(0, 0);
  for (std::size_t k = 0; k < 4; ++k) init.set_dw(6 + k, 0x0101);  // Tab0..Tab7 = DB 1
  cmd.set_dr(0, 0).set_dl(0, fct).set_dr(1, 1).set_dl(1, ba);
  for (std::size_t w = 2; w < 34; ++w) cmd.set_dw(w, word());
  for (std::size_t w = 0; w < 64; ++w) tab.set_dw(w, word());
  std::string listing;
  if (type == 10)
    for (std::size_t n = take(); n > 0 && !in.empty(); --n) listing += static_cast<char>(take());
  amk::DbStore dbs;
  dbs[1] = tab;
  amk::ProcessImage image;
  amk::SfRuntime rt(2, dbs);
  if (const auto fb = rt.load_fb(cmd.dw(4) & 63, listing); !fb && fb.error().empty()) std::abort();
  const auto s0 = rt.init(init, image);
  if (s0.error && s0.text.empty()) std::abort();
  if (s0.error) return 0;
  const auto s1 = rt.command(cmd, image);
  if (s1.error && (s1.text.empty() || rt.state(0) == amk::SfState::active)) std::abort();
  std::int32_t pos = 0;
  for (int c = 0; c < 2000 && !in.empty(); ++c) {
    image.e[static_cast<std::size_t>(c % 256)] = take();
    image.m[static_cast<std::size_t>(c % 128)] = take();
    const auto step = static_cast<std::int16_t>(word());
    pos += step;
    // The drive's 32-bit counters wrap as the hardware's do (the arithmetic on them is unsigned;
    // a signed overflow here was the target's own undefined behaviour, found by fuzzing).
    const auto wrap = [](std::uint32_t v) { return static_cast<std::int32_t>(v); };
    for (auto& d : image.aw) {
      d.position_feedback = pos;
      d.message32 = wrap(static_cast<std::uint32_t>(pos) * 100u);
      d.message16 = static_cast<std::int16_t>(pos);
    }
    image.az[0] = wrap(static_cast<std::uint32_t>(image.az[0]) + static_cast<std::uint32_t>(step) * 65537u);
    const std::uint8_t pulses = (type == 7 || type == 11) ? take() : 0;
    for (std::size_t k = 0; k < 4; ++k)
      if ((pulses >> k) & 1) image.az_zero[k].pulse(image.az[k]);
    if (pulses & 0x10) {
      ++image.aw[0].reference_count;
      image.aw[0].reference_position = pos;
    }
    rt.cycle(image);
    if (c == 1000) {
      cmd.set_dr(1, 5);  // VALUE NEW in the middle
      (void)rt.command(cmd, image);
    }
  }
  (void)rt.command(amk::DataBlock(34), image);  // RESET SF0
  cmd.set_dr(1, 6);                             // READ VALUE (XFIPW; an error for the others)
  const auto s2 = rt.command(cmd, image);
  if (s2.error && s2.text.empty()) std::abort();
  return 0;
}
