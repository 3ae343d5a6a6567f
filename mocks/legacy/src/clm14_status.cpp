// SPDX-License-Identifier: MIT
// Status replies of the emulated CLM1.4 (manual §9.2 "Readout of Status Information", digest
// clm14.md §2.8), taken from the running controller model.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/mocks/legacy/clm14_station.hpp"
#include "hil/serial/clm14/serial_error.hpp"

namespace hil::mocks::legacy {

namespace cc = controllers::clm14;
using serial::clm14::SerialError;

namespace {

/// "evmmmmm.mmm": e = 'A' when homed else ' ', v = sign, `int_digits`.3 (clamped to the field).
std::string position_field(double iu, bool homed, int int_digits) {
  double lim = std::pow(10.0, int_digits) - 0.001;
  const double v = std::clamp(iu, -lim, lim);
  return fmt::format("{}{}", homed ? 'A' : ' ', cc::format_fixed(cc::to_micro(v), int_digits, 3));
}

std::string signed_field(double v, int int_digits, int frac_digits) {
  const double lim = std::pow(10.0, int_digits) - std::pow(10.0, -frac_digits);
  return cc::format_fixed(cc::to_micro(std::clamp(v, -lim, lim)), int_digits, frac_digits);
}

}  // namespace

std::string Clm14Station::status_content(int n, std::string_view arg, bool& ok, int& err) const {
  const auto& c = clm_;
  const auto& s = c.settings();
  const auto fail = [&](SerialError e) {
    ok = false;
    err = static_cast<int>(e);
    return std::string{};
  };
  const auto increments = [&](int axis) {
    const auto& as = s.axes[static_cast<std::size_t>(axis - 1)];
    const double counts = as.feed_constant > 0 ? c.position(axis) * as.encoder_pulses * 4.0 / as.feed_constant : 0.0;
    return fmt::format("{:08X}", static_cast<std::uint32_t>(static_cast<std::int64_t>(std::llround(counts))));
  };
  const auto rpm = [&](int axis) {
    const auto& as = s.axes[static_cast<std::size_t>(axis - 1)];
    const double r = as.feed_constant > 0 ? c.velocity(axis) / as.feed_constant * 60.0 : 0.0;
    return fmt::format("1 {}", signed_field(r, 4, 2));
  };
  const auto task_pair = [&](int t, bool with_main) {
    const auto v = c.task(t);
    if (!v.used && t != 1) return std::string(9, ' ');
    const std::string main =
        v.depth > 0 ? fmt::format("{:04d}", v.main_pc) : (with_main ? fmt::format("{:04d}", v.pc) : "    ");
    return fmt::format("{:04d} {}", v.pc, main);
  };
  switch (n) {
    case 0:
      return position_field(c.position(1), c.homed(1), 5) + " " + position_field(c.position(2), c.homed(2), 6);
    case 2:
      return task_pair(1, true);
    case 3:
      return increments(1) + " " + increments(2);
    case 4: {
      // "?X 04 nnnn": the counter of line nnnn; blanks when that line holds none
      if (arg.size() != 4 || arg.find_first_not_of("0123456789") != std::string_view::npos)
        return fail(SerialError::not_accepted);
      const int line = (arg[0] - '0') * 1000 + (arg[1] - '0') * 100 + (arg[2] - '0') * 10 + (arg[3] - '0');
      if (line >= program_lines) return fail(SerialError::block_number_too_large);
      const auto v = c.counter(line);
      if (!v) return fmt::format("{:04d} {} {}", line, std::string(4, ' '), std::string(6, ' '));
      return fmt::format("{:04d} {:04d} {:06d}", line, v->count % 10000, v->preset);
    }
    case 5: {
      std::string fw = data_->identification().substr(0, 20);
      fw.resize(20, ' ');
      return " " + fw;
    }
    case 8:
      return task_pair(1, false) + " " + task_pair(2, false) + " " + task_pair(3, false);
    case 9:
      // m: axis 1's position (the sum of its measuring-wheel moves), n: its motor encoder position
      return " " + position_field(c.position(1), c.homed(1), 5).substr(0, 1) + signed_field(c.position(1), 5, 3) + " " +
             signed_field(c.motor_position(1), 6, 3);
    case 10:
      return signed_field(c.following_error(1), 5, 3) + " " + signed_field(c.following_error(2), 6, 3);
    case 19:
      return data_->identification();
    case 39:
      return task_pair(4, false) + " " + task_pair(5, false);
    case 40:
      return increments(3) + " " + increments(4);
    case 41:
      return position_field(c.latched_position(1), c.homed(1), 5);
    case 42:
      return rpm(3) + " " + rpm(4);
    case 43:
      return signed_field(c.following_error(3), 5, 3) + " " + signed_field(c.following_error(4), 6, 3);
    case 44:
      return position_field(c.position(3), c.homed(3), 5) + " " + position_field(c.position(4), c.homed(4), 6);
    case 45:
    case 49: {
      // analog inputs 3/4 (45) and 1/2 (49) in mV, sign and 5 digits [decided]
      const int first = n == 49 ? 1 : 3;
      return fmt::format("{:+06d} {:+06d}", c.analog_input(first), c.analog_input(first + 1));
    }
    case 47: {
      // master encoder 1: "0 +rrrr.rr", its revolutions per minute (velocity / C002 × 60) over the
      // model's velocity window; serial error 10 while it has no resolution (C000/C002 unset)
      if (!s.me1.used()) return fail(SerialError::mwheel_param_error);
      return fmt::format("0 {}", signed_field(c.master_velocity() / s.me1.feed_constant * 60.0, 4, 2));
    }
    case 48:
      return rpm(1) + " " + rpm(2);
    case 54: {
      // flying cutoff length counters: material, product (whole IU, sign + 8 digits)
      const auto field = [](double iu) {
        const double v = std::clamp(std::trunc(iu), -99999999.0, 99999999.0);
        return fmt::format("{:+09d}", static_cast<long long>(v));
      };
      return field(c.length_counter(1)) + " " + field(c.length_counter(2));
    }
    case 53: {
      const int e = c.error();
      if (e == 0 && !c.status_text().empty()) return c.status_text();
      const int shown = e != 0 ? e : (c.mode() == cc::Mode::parameter ? 0x01 : 0x00);
      return fmt::format("{:02X} {}", shown, data_->fault_text(shown));
    }
    case 60: {
      if (arg.size() != 1 || arg[0] < '0' || arg[0] > '3') return fail(SerialError::not_accepted);
      const std::string item = c.error_item(arg[0] - '0');
      return item.empty() ? std::string(6, ' ') : fmt::format("{} {}", arg[0], item);
    }
    case 61: {
      // "mt.nn": I/Q/M, source, byte -> bits 7..0
      const auto b = cc::parse_byte(arg);
      if (!b) return fail(SerialError::not_accepted);
      const std::uint8_t v = c.image().byte(*b);
      std::string bits;
      for (int i = 7; i >= 0; --i) bits += ((v >> i) & 1U) ? '1' : '0';
      return fmt::format("{} {}", arg, bits);
    }
    case 63: {
      // "vb": TXT 0 lines v..b (1..4)
      if (arg.size() != 2 || arg[0] < '1' || arg[0] > '4' || arg[1] < arg[0] || arg[1] > '4')
        return fail(SerialError::not_accepted);
      std::string out;
      for (int i = arg[0] - '1'; i <= arg[1] - '1'; ++i) {
        std::string l = c.text_lines()[static_cast<std::size_t>(i)];
        l.resize(16, ' ');
        out += l;
      }
      return out;
    }
    default:
      return fail(SerialError::status_illegal);
  }
}

}  // namespace hil::mocks::legacy
