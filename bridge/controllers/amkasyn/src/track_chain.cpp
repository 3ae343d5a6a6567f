// SPDX-License-Identifier: MIT
// The BINEA/CAM track chain (see track_chain.hpp).
#include "hil/controllers/amkasyn/track_chain.hpp"

namespace hil::controllers::amkasyn {

std::optional<bool> TrackChain::step(const TrackMode& m, bool table_bit, bool input, int monoflop_half_ms,
                                     int cycle_half_ms) noexcept {
  bool t = table_bit;
  if (m.monoflop) {
    if (table_bit && !prev_table_) remaining_half_ms_ = monoflop_half_ms;  // retriggerable
    t = remaining_half_ms_ > 0;
    if (remaining_half_ms_ > 0) remaining_half_ms_ -= cycle_half_ms;
  }
  prev_table_ = table_bit;
  const bool e = input != m.invert_in;
  if (m.logic == 1) t = t && e;
  if (m.logic == 2) t = t || e;
  if (m.output_off) return std::nullopt;
  return t != m.invert_out;
}

}  // namespace hil::controllers::amkasyn
