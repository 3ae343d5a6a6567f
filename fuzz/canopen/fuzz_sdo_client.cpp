// SPDX-License-Identifier: MIT
// Fuzz target: an SDO client in the middle of each kind of transfer fed arbitrary server answers
// (9-byte records: dlc, 8 data bytes) must complete exactly once or stay pending, never crash.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "hil/canopen/sdo_client.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  hil::canopen::SdoClientOptions o;
  o.block = (data[0] & 1) != 0;
  o.block_threshold = 0;
  o.timeout = std::chrono::milliseconds(5);
  o.retries = data[0] >> 6;
  hil::canopen::SdoClient client(
      3,
      [](const hil::can::Frame& f) {
        if (f.id != 0x603 || f.dlc != 8) std::abort();
      },
      o);
  int completions = 0;
  hil::TimePoint t{};
  auto done = [&](std::error_code, std::vector<std::uint8_t>) { ++completions; };
  if (data[0] & 2)
    client.async_upload(0x1008, 0, t, done);
  else
    client.async_download(0x2000, 0, std::vector<std::uint8_t>(static_cast<std::size_t>(data[0]) * 3, 0xAA), t, done);
  for (std::size_t i = 1; i + 9 <= size; i += 9) {
    hil::can::Frame f;
    f.id = 0x583;
    f.dlc = static_cast<std::uint8_t>(data[i] % 9);
    for (int k = 0; k < 8; ++k) f.data[k] = data[i + 1 + k];
    client.on_frame(f, t += std::chrono::milliseconds(1));
    if (data[i] & 0x80) client.step(t += std::chrono::milliseconds(10));
  }
  for (int k = 0; k < 10; ++k) client.step(t += std::chrono::milliseconds(10));
  if (completions != 1) std::abort();  // the timeout always ends a transfer
  return 0;
}
