// SPDX-License-Identifier: MIT
// Fuzz the edge-log parser: any input either parses or gives an error with a line number; a
// parsed log must round-trip through format_edge_log, and the verifier must digest it.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/stepdir/edge_log.hpp"
#include "hil/stepdir/verifier.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto edges = hil::stepdir::parse_edge_log(text);
  if (!edges) {
    if (edges.error().line == 0 || edges.error().message.empty()) std::abort();
    return 0;
  }
  auto again = hil::stepdir::parse_edge_log(hil::stepdir::format_edge_log(*edges));
  if (!again || *again != *edges) std::abort();
  hil::stepdir::StepVerifier v(hil::stepdir::StepTiming{});
  v.feed(*edges);
  v.expect_net_steps(static_cast<std::int64_t>(size));
  if (v.first_violation()) (void)v.first_violation()->describe();
  return 0;
}
