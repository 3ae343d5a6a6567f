// SPDX-License-Identifier: MIT
// The PC-ELG data channel (12.5) under arbitrary input: frames of 9 bytes are parsed and performed
// on the ELG's data image around a gearbox (reads, writes, refusals with 3016/3018); the bytes are
// also read as the console's value text. Nothing may crash, and a refused request is acknowledged.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <span>
#include <string>
#include <string_view>

#include "hil/controllers/elg/pc_data_image.hpp"

namespace elg = hil::controllers::elg;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)elg::parse_pc_value(std::string_view(reinterpret_cast<const char*>(data), size));
  elg::Gearbox box{elg::GearboxConfig{}};
  std::map<int, std::string> md{{3961, "180000"}, {5020, "00010010"}, {2801, "10000"}};
  std::map<int, std::string> sd{{5016, "00000000"}};
  elg::PcDataImage image(box, md, sd, {});
  elg::Signals signals;
  elg::AxisFeedback axes;
  const std::span<const std::uint8_t> bytes(data, size);
  for (std::size_t at = 0; at + elg::pc_frame_size <= bytes.size(); at += elg::pc_frame_size) {
    const auto request = elg::parse_pc_request(bytes.subspan(at, elg::pc_frame_size));
    if (!request) continue;
    const auto reply = image.request(*request);
    if (!reply.acknowledged || (!reply.performed && !reply.alarm)) std::abort();
    (void)elg::make_pc_reply(*request, reply);
    (void)elg::to_string(reply.value);
    // Couple and uncouple between requests so the "$" rule and the waiting inputs are exercised.
    signals.compute = (at / elg::pc_frame_size) % 3 == 0;
    signals.gearing_on = (at / elg::pc_frame_size) % 4 == 1;
    signals.gearing_off = (at / elg::pc_frame_size) % 4 == 3;
    box.step(signals, axes);
    image.update(axes);
  }
  return 0;
}
