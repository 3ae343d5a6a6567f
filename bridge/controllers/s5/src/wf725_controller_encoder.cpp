// SPDX-License-Identifier: MIT
// WF 725/726 measuring-circuit checks (docs/wf725.md, "Encoder faults"; manual §6.2.1 errors 07-09,
// 0B, 30-34, MD 41 masks, MD 40 simulation): every condition the manual ties to an error, on the
// axis' counter and the encoder fault inputs (input byte 2, our model of the encoder signals).
#include <fmt/format.h>

#include <cmath>

#include "hil/controllers/s5/wf725_controller.hpp"

namespace hil::controllers::s5 {
namespace {

constexpr std::int64_t mask_cable = 1;       // MD 41 K: cable-break (and level) check
constexpr std::int64_t mask_double = 4;      // MD 41 U: double reading of the absolute value
constexpr std::int64_t mask_pulse = 65'536;  // MD 41 J: pulse check (WF 726)
constexpr int in_cable_break = 0, in_level_low = 1, in_pulse_loss = 3, in_parity = 4, in_telegram = 5, in_jump = 6;

}  // namespace

bool Wf725Controller::encoder_input(int bit) const noexcept {
  return io().get(BitAddress{IoArea::input, 2, static_cast<std::uint8_t>(bit)});
}

void Wf725Controller::raise_encoder(int code, TimePoint now, std::string_view context) {
  if (has_error(code)) return;
  const bool data_mode = !traversing_ && drive_enabled_;
  raise_wf(code, now, context);
  synced_ = false;  // the position is lost
  // §6.2.1 error 17: an error < 60 of the measuring circuit in a data mode drops the drive enable.
  if (data_mode) raise_wf(0x17, now, fmt::format("error {:02X} in a data mode", code));
}

void Wf725Controller::encoder_cycle(TimePoint now) {
  const std::int64_t md41 = md_.integer(41);
  const bool simulation = md_.integer(40) == 1;
  const bool absolute = !md_.incremental();
  if (!powered_up_) {
    powered_up_ = true;
    // 30: an absolute encoder in MD 4 on a module without the absolute-encoder board (variant A).
    if (absolute && opt_.variant == 'A')
      raise_encoder(0x30, now, fmt::format("MD 4 = {} on a variant A module", md_.integer(4)));
  }
  if (simulation) return;  // MD 40: actual = command, the encoder checks are off
  if ((md41 & mask_cable) == 0) {
    if (encoder_input(in_cable_break)) raise_encoder(0x07, now, "cable break in the encoder cable");
    if (encoder_input(in_level_low)) raise_encoder(0x0B, now, "the encoder level sensor sees no voltage");
  }
  const auto& st = axis(0).status();
  if (!absolute) {
    // 08: pulse monitor (WF 726, MD 41 J = 0): the pulses between two zero marks (every MD 34
    // increments of the counter) differ from MD 34 while pulses are lost.
    const std::int64_t md34 = md_.integer(34);
    // The pulses the counter misses while the encoder loses pulses (decision: one per cycle of
    // motion): the pulse-check difference of data code 4.
    if (encoder_input(in_pulse_loss) && st.position_inc != last_inc_) --pulse_difference_;
    last_inc_ = st.position_inc;
    if (md34 <= 0) return;
    const std::int64_t marks = st.position_inc >= 0 ? st.position_inc / md34 : -((-st.position_inc + md34 - 1) / md34);
    if (zero_mark_known_ && marks != zero_mark_count_ && md_.series == 726 && (md41 & mask_pulse) == 0 &&
        encoder_input(in_pulse_loss))
      raise_encoder(0x08, now, "pulses between two zero marks differ from MD 34");
    zero_mark_count_ = marks;
    zero_mark_known_ = true;
    return;
  }
  const bool parallel = opt_.variant == 'B', ssi = opt_.variant == 'C';
  // 31: invalid data: the SSI telegram, or interference the double reading (MD 41 U = 0) sees.
  if (encoder_input(in_telegram) && (ssi || (parallel && (md41 & mask_double) == 0)))
    raise_encoder(0x31, now, ssi ? "SSI telegram not operative" : "the double reading differs (interference)");
  // 32: even parity of the parallel encoder, with a parity bit (MD 21 = 1 or 3).
  const std::int64_t md21 = md_.integer(21);
  if (encoder_input(in_parity) && parallel && (md21 == 1 || md21 == 3))
    raise_encoder(0x32, now, "odd bit combination (even parity)");
  // 33: a jump > MD 34 since the previous reading is replaced by an extrapolated value; only
  // difference_cycles jumps in a row stop the axis.
  jumps_ = encoder_input(in_jump) ? jumps_ + 1 : 0;
  if (jumps_ >= opt_.difference_cycles) raise_encoder(0x33, now, fmt::format("{} jumps > MD 34 in a row", jumps_));
  // 34: the reading minus the masked range MD 7 must lie within 0 .. MD 5 (parallel encoder).
  const std::int64_t md7 = md_.integer(7), md5 = md_.integer(5);
  if (parallel && md7 > 0 && md5 > 0) {
    const std::int64_t reading = st.position_inc;
    if (reading - md7 < 0 || reading + md7 > md5)
      raise_encoder(0x34, now, fmt::format("reading {} steps, masked range MD 7 = {}, MD 5 = {}", reading, md7, md5));
  }
}

}  // namespace hil::controllers::s5
