// SPDX-License-Identifier: MIT
// WF 725/726 data codes (DW 11, executed by the rising edge of D 12.0; docs/wf725.md "The DB axis"):
// the manual's (3, 4, 8/9/A, 1A, 32, 800C) and ours (tables in wf725_interface.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/controllers/s5/wf725_controller.hpp"

namespace hil::controllers::s5 {

using namespace wf_db;

void Wf725Controller::handle_data_code(TimePoint now) {
  const std::uint16_t c = db_.read_word(dw_data_code);
  const std::int32_t p1 = db_.read_dd(dd_data_param1), p2 = db_.read_dd(dd_data_param2);
  db_.set_bit(dw_data_status, 1, false);
  // A new input clears the self-acknowledging messages of the data modes (DW 40).
  {
    std::vector<std::pair<const profiles::ErrorCatalogue*, int>> drop;
    for (const auto& e : errors().active())
      if (e.ack == AckRule::self_clearing && e.catalogue != traversing_cat_) drop.emplace_back(e.catalogue, e.code);
    for (const auto& [cat, code] : drop) (void)clear_error(*cat, code, 0);
  }
  std::int32_t result = 0;
  if (split_data_code(c, p1, p2, now, result)) {  // 30/31: split drive (wf725_split_drive.cpp)
    db_.write_dd(dd_data_result, result);
    db_.set_bit(dw_data_status, 0, true);
    return;
  }
  switch (c) {
    case 0:
      raise_io(112, now);
      break;
    case code::acknowledge:
      (void)acknowledge(Acknowledgement::acknowledge);
      break;
    case code::ref_rapid:
    case code::ref_reduced:
    case code::ref_slow:
      ref_speeds_[c - code::ref_rapid] = p1;
      break;
    case code::mdi_position:
      mdi_position_ = p1;
      mdi_incremental_ = (p2 & 1) != 0;
      break;
    case code::mdi_feed:
      if (p1 <= 0) {
        raise_io(145, now, "MDI feed 0");
      } else {
        mdi_feed_ = p1;
      }
      break;
    case code::jog_feed:
      jog_feed_ = std::max<std::int32_t>(p1, 0);
      break;
    case code::encoder_speed:
    case code::pulse_difference:
      if (!md_.incremental() || md_.integer(34) <= 0) {
        raise_io(113, now, fmt::format("data code {:X}: incremental encoders only (MD 34 pulses)", c));
      } else if (c == code::pulse_difference) {
        result = static_cast<std::int32_t>(pulse_difference_);
      } else {
        const auto& ax = axis(0);
        const double inc_per_s = ax.status().velocity * static_cast<double>(ax.config().inc_per_unit.num) /
                                 static_cast<double>(ax.config().inc_per_unit.den);
        result =
            static_cast<std::int32_t>(std::llround(std::abs(inc_per_s) * 60.0 / static_cast<double>(md_.integer(34))));
      }
      break;
    case code::drift:
      result = compensate_drift(now);
      break;
    case code::control_voltage:
      control_mv_ = std::clamp<std::int32_t>(p1, 0, 10000);  // the 11-bit DAC: at most 10 V
      break;
    case code::delete_block:
      if (running_program_ == p1 && p1 != 0) {
        raise_io(105, now, "the program runs");
      } else if (const int e = store_->remove_block(p1, p2)) {
        raise_io(e, now, fmt::format("program {} block {}", p1, p2));
      }
      break;
    case code::list_programs: {
      const auto n = store_->numbers();
      if (p1 <= 0) {
        raise_io(145, now, "page number 0");
      } else {
        write_list(n, p1);
        result = static_cast<std::int32_t>(n.size());
      }
      break;
    }
    case code::list_blocks: {
      const Wf725Program* prog = p1 == 0 ? nullptr : store_->find(p1);
      if (p1 == 0) {
        raise_io(125, now);
      } else if (prog == nullptr) {
        raise_io(127, now, fmt::format("program {}", p1));
      } else if (p2 <= 0) {
        raise_io(145, now, "page number 0");
      } else if (prog->blocks.empty()) {
        raise_io(129, now, fmt::format("program {}", p1));
      } else {
        std::vector<int> n;
        for (const auto& b : prog->blocks) n.push_back(b.number);
        write_list(n, p2);
        result = static_cast<std::int32_t>(n.size());
      }
      break;
    }
    case code::measured:
      result = measured_um_ ? static_cast<std::int32_t>(std::llround(*measured_um_)) : 0;
      break;
    case code::teach_in: {
      // Teach-in (§6.4): the actual value becomes block p2 of program p1 (G90, the MDI feed or MD 3).
      Wf725Block b;
      b.g[0] = 90;
      b.x = std::llround(actual_um());
      b.f = mdi_feed_ > 0 ? mdi_feed_ : std::llround(md_.get(3) * 100);
      if (const int e = store_->teach(p1, p2, b, db_.bit(dw_control, bit_ram))) raise_io(e, now);
      break;
    }
    case code::tool_offset:
      if (p1 < 1 || p1 > 20) {
        raise_io(142, now, fmt::format("tool offset number {}", p1));
      } else {
        offsets_um_[static_cast<std::size_t>(p1)] = p2;
      }
      break;
    case code::delete_program:
      if (running_program_ == p1 && p1 != 0) {
        raise_io(105, now, "the program runs");
      } else if (const int e = store_->remove(p1)) {
        raise_io(e, now);
      }
      break;
    case code::write_md:
      if (const int e = write_machine_data(p1, p2))
        raise_io(e, now,
                 e == 121 ? fmt::format("MD {}", p1) : "machine data are written in mode machine data input/output",
                 e == 121 ? "program_io" : "memory_admin");
      break;
    case code::read_md:
      if (p1 < 1 || p1 > 50) {
        raise_io(121, now, fmt::format("MD {}", p1));
      } else {
        result = read_machine_data(p1);
      }
      break;
    case code::buffer_length:
      buffer_length(p1, p2, now);
      break;
    case code::buffer_reload:
      buffer_reload(p1, p2, now);
      break;
    case code::program_in:
    case code::program_out:
      if (mode_bits_ != (1U << (bit_mode_program_io - 8))) {
        raise_io(201, now, "programs are read in and out in mode program input/output (D 0.9)", "memory_admin");
      } else if (c == code::program_in) {
        program_input(p1, now);
      } else {
        program_output(p1, p2, now);
      }
      break;
    default:
      raise_io(113, now, fmt::format("data code {:X}", c));
      break;
  }
  db_.write_dd(dd_data_result, result);
  db_.set_bit(dw_data_status, 0, true);
}

}  // namespace hil::controllers::s5
