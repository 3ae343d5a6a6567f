// SPDX-License-Identifier: MIT
// Fuzz target: an SDO server fed arbitrary frame sequences (input = 9-byte records: dlc, 8 data
// bytes; a record whose dlc byte has bit 7 set advances time by 2 s instead) must answer every
// request with a well-formed response or abort and never crash.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "hil/canopen/eds.hpp"
#include "hil/canopen/sdo_server.hpp"

namespace {
const hil::canopen::ObjectDictionary& od_template() {
  static const auto od = [] {
    auto d = hil::canopen::load_eds(HIL_CANOPEN_PROFILE_DIR "/hil_cia402_drive.eds", 2);
    if (!d) std::abort();
    return std::move(d->od);
  }();
  return od;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto od = od_template();
  od.set_max_value_size(256);
  hil::TimePoint t{};
  hil::canopen::SdoServer server(od, 2, [](const hil::can::Frame& f) {
    if (f.id != 0x582 || f.dlc != 8) std::abort();  // every answer is a full SDO frame
  });
  for (std::size_t i = 0; i + 9 <= size; i += 9) {
    if (data[i] & 0x80) {
      t += std::chrono::seconds(2);
      server.step(t);
      continue;
    }
    hil::can::Frame f;
    f.id = 0x602;
    f.dlc = static_cast<std::uint8_t>(data[i] % 9);
    for (int k = 0; k < 8; ++k) f.data[k] = data[i + 1 + k];
    server.on_frame(f, t += std::chrono::milliseconds(1));
  }
  return 0;
}
