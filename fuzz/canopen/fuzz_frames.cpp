// SPDX-License-Identifier: MIT
// Fuzz target: NMT, heartbeat, SYNC, EMCY decoders and a slave node (NMT state machine, PDO
// engine with the CiA 402 EDS) fed arbitrary frames (11-byte records: id lo, id hi, dlc, 8 bytes).
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "hil/canopen/eds.hpp"
#include "hil/canopen/emcy.hpp"
#include "hil/canopen/nmt.hpp"
#include "hil/canopen/slave.hpp"
#include "hil/canopen/sync.hpp"

namespace {
const hil::canopen::ObjectDictionary& od_template() {
  static const auto od = [] {
    auto d = hil::canopen::load_eds(HIL_CANOPEN_PROFILE_DIR "/hil_cia402_drive.eds", 4);
    if (!d) std::abort();
    return std::move(d->od);
  }();
  return od;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hil::TimePoint t{};
  hil::canopen::Slave slave(od_template(), 4, [](const hil::can::Frame& f) {
    if (f.dlc > 8) std::abort();
  });
  slave.start(t);
  for (std::size_t i = 0; i + 11 <= size; i += 11) {
    hil::can::Frame f;
    f.id = static_cast<std::uint32_t>(data[i] | ((data[i + 1] & 0x07) << 8));
    f.rtr = (data[i + 1] & 0x80) != 0;
    f.dlc = static_cast<std::uint8_t>(data[i + 2] % 9);
    for (int k = 0; k < 8; ++k) f.data[k] = data[i + 3 + k];
    (void)hil::canopen::parse_nmt(f);
    (void)hil::canopen::parse_error_control(f);
    (void)hil::canopen::parse_sync(f);
    (void)hil::canopen::parse_emcy(f);
    slave.on_frame(f, t += std::chrono::milliseconds(1));
    slave.step(t);
  }
  return 0;
}
