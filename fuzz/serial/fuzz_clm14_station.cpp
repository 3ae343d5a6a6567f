// SPDX-License-Identifier: MIT
// The emulated CLM1.4 line (32 RS-485 stations) fed arbitrary bytes and character errors:
// never crash, every reply is a well-formed telegram, "Y", or a poll answer.
#include <cstdint>
#include <cstdlib>
#include <memory>

#include "hil/mocks/legacy/clm14_line.hpp"
#include "hil/serial/line_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hil::mocks::legacy;
  static auto dd = hil::serial::clm14::load_device_data();
  if (!dd) std::abort();
  // Built once: the line keeps state across inputs like a device that is never reset.
  static Clm14Line single(*dd, 0);
  static Clm14Line multi(*dd, 32);
  Clm14Line& line = size > 0 && (data[0] & 1) ? multi : single;
  // Mode changes validate every parameter of every station: only on explicit request bytes.
  if (size > 1 && data[1] == 'P') line.set_mode(ClmMode::parameter);
  if (size > 1 && data[1] == 'M') line.set_mode(ClmMode::manual);
  std::size_t pos = 0;
  while (pos < size) {
    const std::size_t n = std::min<std::size_t>(1 + data[pos] % 40, size - pos);
    std::string out = line.on_bytes(std::span(data + pos, n), {});
    if (data[pos] == 0xFF) out += line.on_line_error(hil::serial::LineError::parity, {});
    if (!out.empty() && out.back() != '\n') std::abort();
    pos += n;
  }
  if (size > 2 && data[2] == 0x42) (void)line.save_state();
  return 0;
}
