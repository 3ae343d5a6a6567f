// SPDX-License-Identifier: MIT
// RK512 telegram parser and assembler, and the IP247 / WF endpoints behind 3964R fed raw line
// bytes: never crash; a parsed command re-made gives the same telegram.
#include <cstdint>
#include <cstdlib>

#include "hil/mocks/legacy/s5_block_endpoint.hpp"
#include "hil/serial/s5/rk512.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hil::serial::s5;
  auto t = parse_rk512(std::span(data, size));
  if (t && t->kind == Rk512Telegram::Kind::command && t->data.size() <= rk512_default_max_data) {
    auto again = make_rk512_request(t->header, t->data);
    if (again.size() != 1 || again[0] != std::vector<std::uint8_t>(data, data + size)) std::abort();
  }
  Rk512Assembler as;
  if (t) (void)as.feed(*t);
  hil::mocks::legacy::S5BlockEndpoint ip(hil::mocks::legacy::make_ip247_policy({}));
  hil::mocks::legacy::S5BlockEndpoint wf(hil::mocks::legacy::make_wf725_policy({}));
  hil::TimePoint now{};
  for (std::size_t i = 0; i < size; i += 7) {
    const auto chunk = std::span(data + i, std::min<std::size_t>(7, size - i));
    (void)ip.on_bytes(chunk, now);
    (void)wf.on_bytes(chunk, now);
    now += std::chrono::milliseconds(data[i] % 300);
    (void)ip.on_idle(now);
    (void)wf.on_idle(now);
  }
  return 0;
}
