// SPDX-License-Identifier: MIT
// CLM1.4 commands without motion (manual §5.7, digest clm14.md §4.2): I/O, jumps, subroutines,
// counters, comparisons, conversions, arithmetic, texts, waits.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/controllers/clm14/controller.hpp"

namespace hil::controllers::clm14 {

namespace {

__extension__ typedef __int128 i128;

bool matches(std::uint8_t byte, const std::array<std::uint8_t, 8>& pat) {
  for (int i = 0; i < 8; ++i) {
    const std::uint8_t want = pat[static_cast<std::size_t>(7 - i)];  // pattern is written bit 7 .. bit 0
    if (want == 2) continue;
    if (((byte >> i) & 1U) != want) return false;
  }
  return true;
}

/// The n-th bit counted from `start` upward, crossing into the next byte after bit 7.
BitAddress bit_plus(BitAddress a, int n) {
  const int pos = a.bit + n;
  a.byte.byte = static_cast<std::uint8_t>(a.byte.byte + pos / 8);
  a.bit = static_cast<std::uint8_t>(pos % 8);
  return a;
}

bool fits(const BitAddress& start, int n) {
  const BitAddress last = bit_plus(start, n - 1);
  const int bytes = start.byte.area == Area::marker ? marker_bytes : io_bytes;
  return last.byte.byte < bytes;
}

}  // namespace

bool Controller::forbidden_in_cutoff(const Instruction& in) const {
  // §7.12: ACC AEO CON CPL FOL HOM JST PBK POA PSA REP RMI RSV RTM SAC SRM SRP VCC on axis 1.
  switch (in.op) {
    case Op::jst:
    case Op::rsv:
      return true;
    case Op::acc:
    case Op::aeo:
    case Op::con:
    case Op::cpl:
    case Op::fol:
    case Op::hom:
    case Op::pbk:
    case Op::poa:
    case Op::psa:
    case Op::rmi:
    case Op::rtm:
    case Op::sac:
    case Op::srm:
    case Op::srp:
    case Op::vcc:
    case Op::rep: {
      const Num& n = in.op == Op::rep ? in.n[1] : in.n[0];
      const Micro v = n.is_var() ? vars_[static_cast<std::size_t>(n.var)] : n.value;
      return v / micro_one == 1;
    }
    default:
      return false;
  }
}

void Controller::fail(int t, int code, std::string why) {
  const Task& k = tasks_[static_cast<std::size_t>(t - 1)];
  raise(code, fmt::format("task {} NC line {:04d} {}: {}", t, k.pc, text_[static_cast<std::size_t>(k.pc)], why), 1,
        k.pc);
}

std::optional<Micro> Controller::value(const Num& n, int t) {
  (void)t;
  if (!n.is_var()) return n.value;
  const Micro v = vars_[static_cast<std::size_t>(n.var)];
  return n.negate ? -v : v;
}

std::optional<int> Controller::integer(const Num& n, int t, int lo, int hi) {
  const Micro v = *value(n, t);
  const Micro whole = v / micro_one;  // truncates toward zero
  if (whole < lo || whole > hi || (!n.is_var() && v % micro_one != 0)) {
    fail(t,
         n.is_var() ? static_cast<int>(ClmError::variable_value) : static_cast<int>(ClmError::invalid_program_command),
         fmt::format("{} = {} is outside {}..{}", n.is_var() ? fmt::format("V{:03d}", n.var) : std::string("operand"),
                     format_variable(v), lo, hi));
    return std::nullopt;
  }
  return static_cast<int>(whole);
}

std::optional<Micro> Controller::length(const Num& n, int t) {
  Micro v = *value(n, t);
  v = v / 1000 * 1000;  // 3 decimals, truncated
  if (v > 999'999'999'000 || v < -999'999'999'000) {
    fail(t, static_cast<int>(ClmError::variable_value),
         fmt::format("length {} does not fit ±999999.999", format_variable(v)));
    return std::nullopt;
  }
  return v;
}

bool Controller::store_variable(int var, Micro v, int t) {
  if (v > variable_max || v < -variable_max) {
    fail(t, static_cast<int>(ClmError::variable_value), fmt::format("V{:03d} result out of ±99999999.999999", var));
    return false;
  }
  // SET may also write V047/V048 and Vx00 while the axis is not homed (§5.6).
  const int axis = var / 100;
  if (var >= 100 && var < 500 && var % 100 == 0 && !homed(axis) && axes_[static_cast<std::size_t>(axis - 1)].port) {
    auto& a = axes_[static_cast<std::size_t>(axis - 1)];
    a.base += to_double(v) - clm_position(axis);
    vars_[static_cast<std::size_t>(var)] = v;
    return true;
  }
  if ((var == 47 || var == 48) && settings_.axes[static_cast<std::size_t>(var - 47)].measuring_wheel()) {
    // measuring wheel: the motor position of axis 1 / 2, writable while not homed (§5.6)
    if (homed(var - 46) || !set_motor_position(var - 46, to_double(v))) {
      fail(t, static_cast<int>(ClmError::write_system_variable),
           fmt::format("V{:03d} (motor position of axis {}) is writable only while the axis is not homed", var,
                       var - 46));
      return false;
    }
    vars_[static_cast<std::size_t>(var)] = v;
    return true;
  }
  if (var < 600 && var != 47 && var != 48) {
    fail(t, static_cast<int>(ClmError::write_system_variable), fmt::format("V{:03d} is a system variable", var));
    return false;
  }
  vars_[static_cast<std::size_t>(var)] = v;
  return true;
}

Controller::Flow Controller::exec_counter(Task& task, const Instruction& in, int line) {
  int& count = counters_[line];
  const Num& preset = in.op == Op::cou ? in.n[1] : in.n[2];
  const int t = static_cast<int>(&task - tasks_.data()) + 1;
  auto n = integer(preset, t, 0, in.op == Op::cou ? 999999 : 99999);
  if (!n) return Flow::halt;
  ++count;
  const bool reached = count >= *n;
  if (reached) count = 0;
  if (preset.is_var() && preset.var < 999) vars_[static_cast<std::size_t>(preset.var + 1)] = count * micro_one;
  if (in.op == Op::cou) {
    if (reached) write_bit(in.bit, true);  // COU only ever sets the bit
    return Flow::next;
  }
  if (reached) return Flow::next;
  auto target = integer(in.n[0], t, 0, 2999);
  if (!target) return Flow::halt;
  task.jump_to = *target;
  return Flow::jump;
}

Controller::Flow Controller::exec(int t, Task& k, const Instruction& in, TimePoint now) {
  if (flying_cutoff() && forbidden_in_cutoff(in)) {
    fail(t, static_cast<int>(ClmError::invalid_program_command),
         fmt::format("{} is not allowed on axis 1 in flying cutoff mode (§7.12)", mnemonic(in.op)));
    return Flow::halt;
  }
  const auto jump = [&](const Num& target) {
    auto v = integer(target, t, 0, 2999);
    if (!v) return Flow::halt;
    k.jump_to = *v;
    return Flow::jump;
  };
  const auto bit_value = [&](const Num& n) -> std::optional<bool> {
    auto v = integer(n, t, 0, 1);
    if (!v) return std::nullopt;
    return *v == 1;
  };
  switch (in.op) {
    case Op::nop:
      return Flow::next;
    case Op::aea: {
      auto v = bit_value(in.n[0]);
      if (!v) return Flow::halt;
      write_bit(in.bit, *v);
      return Flow::next;
    }
    case Op::akn: {
      auto v = bit_value(in.n[0]);
      if (!v) return Flow::halt;
      return image_.bit(in.bit) == *v ? Flow::next : Flow::wait;
    }
    case Op::akp:
      return matches(image_.byte(in.byte), in.pattern) ? Flow::next : Flow::wait;
    case Op::ape:
      for (int i = 0; i < 8; ++i) {
        const std::uint8_t p = in.pattern[static_cast<std::size_t>(7 - i)];
        if (p != 2) write_bit({in.byte, static_cast<std::uint8_t>(i)}, p == 1);
      }
      return Flow::next;
    case Op::bac:
    case Op::cou:
      return exec_counter(k, in, k.pc);
    case Op::bce: {
      auto v = bit_value(in.n[1]);
      if (!v) return Flow::halt;
      return image_.bit(in.bit) == *v ? jump(in.n[0]) : Flow::next;
    }
    case Op::bic: {
      auto base = integer(in.n[0], t, 0, 2999);
      auto step = integer(in.n[1], t, 0, 2999);
      auto bits = integer(in.n[2], t, 1, 8);
      auto mode = integer(in.n[3], t, 0, 1);
      if (!base || !step || !bits || !mode) return Flow::halt;
      if (!fits(in.bit, *bits)) {
        fail(t, static_cast<int>(ClmError::command_io), "BIC bits run past the end of the I/O area");
        return Flow::halt;
      }
      int v = 0;
      for (int i = 0; i < *bits; ++i) {
        const bool b = image_.bit(bit_plus(in.bit, i));
        if (!b) continue;
        v += *mode == 0 ? (1 << i) : (i < 4 ? (1 << i) : 10 * (1 << (i - 4)));
      }
      if (*mode == 1) {
        int lo_nibble = 0, hi_nibble = 0;
        for (int i = 0; i < *bits; ++i)
          if (image_.bit(bit_plus(in.bit, i))) (i < 4 ? lo_nibble : hi_nibble) |= 1 << (i % 4);
        if (lo_nibble > 9 || hi_nibble > 9) {
          fail(t, static_cast<int>(ClmError::bcd_input),
               fmt::format("BIC bits are not BCD ({}{})", hi_nibble, lo_nibble));
          return Flow::halt;
        }
      }
      const int target = *base + v * *step;
      if (target > 2999) {
        fail(t, static_cast<int>(ClmError::invalid_block_number), fmt::format("BIC target {} beyond 2999", target));
        return Flow::halt;
      }
      k.jump_to = target;
      return Flow::jump;
    }
    case Op::bio:
      return matches(image_.byte(in.byte), in.pattern) && matches(image_.byte(in.byte2), in.pattern) ? jump(in.n[0])
                                                                                                     : Flow::next;
    case Op::bpa:
      return matches(image_.byte(in.byte), in.pattern) ? jump(in.n[0]) : Flow::next;
    case Op::cid: {
      auto mode = integer(in.n[0], t, 0, 1);
      if (!mode) return Flow::halt;
      const Micro v = *value(in.n[1], t);
      const Micro cur = vars_[static_cast<std::size_t>(in.var)];
      return store_variable(in.var, *mode == 1 && options_.cid_mode1_adds ? cur + v : v, t) ? Flow::next : Flow::halt;
    }
    case Op::cio: {
      auto n = integer(in.n[0], t, 0, 99);
      if (!n) return Flow::halt;
      if (*n > 32) {
        fail(t, static_cast<int>(ClmError::io_number), fmt::format("CIO copies {} bits (at most 32)", *n));
        return Flow::halt;
      }
      if (*n > 0 && (!fits(in.bit, *n) || !fits(in.bit2, *n))) {
        fail(t, static_cast<int>(ClmError::command_io), "CIO bits run past the end of the I/O area");
        return Flow::halt;
      }
      for (int i = 0; i < *n; ++i) write_bit(bit_plus(in.bit2, i), image_.bit(bit_plus(in.bit, i)));
      return Flow::next;
    }
    case Op::clc: {
      auto line = integer(in.n[0], t, 0, 2999);
      if (!line) return Flow::halt;
      const Op op = program_[static_cast<std::size_t>(*line)].op;
      if (op == Op::cou || op == Op::bac) counters_[*line] = 0;
      return Flow::next;
    }
    case Op::cpj:
    case Op::cps: {
      const Micro a = vars_[static_cast<std::size_t>(in.var)];
      const Micro b = *value(in.n[0], t);
      const Micro tol = std::abs(*value(in.n[1], t));
      bool r = false;
      switch (in.cmp) {
        case Cmp::eq:
          r = std::abs(a - b) <= tol;
          break;
        case Cmp::ne:
          r = std::abs(a - b) > tol;
          break;
        case Cmp::lt:
          r = a < b;
          break;
        case Cmp::gt:
          r = a > b;
          break;
        case Cmp::le:
          r = a <= b;
          break;
        case Cmp::ge:
          r = a >= b;
          break;
      }
      if (in.op == Op::cps) {
        write_bit(in.bit, r);
        return Flow::next;
      }
      return r ? jump(in.n[2]) : Flow::next;
    }
    case Op::cst: {
      auto which = integer(in.n[0], t, 0, 5);
      auto levels = integer(in.n[1], t, 0, 9);
      if (!which || !levels) return Flow::halt;
      static constexpr std::array<std::array<bool, 5>, 6> sets{{{true, true, false, false, false},
                                                                {true, false, false, false, false},
                                                                {false, true, false, false, false},
                                                                {true, true, false, true, true},
                                                                {false, false, false, true, false},
                                                                {false, false, false, false, true}}};
      for (std::size_t i = 0; i < 5; ++i) {
        if (!sets[static_cast<std::size_t>(*which)][i]) continue;
        auto& st = tasks_[i].stack;
        if (*levels == 0)
          st.clear();
        else
          st.resize(st.size() > static_cast<std::size_t>(*levels) ? st.size() - static_cast<std::size_t>(*levels) : 0);
      }
      return Flow::next;
    }
    case Op::cvt: {
      auto format = integer(in.n[0], t, 0, 1);
      auto dir = integer(in.n[1], t, 0, 1);
      if (!format || !dir) return Flow::halt;
      const int bytes = in.byte.area == Area::marker ? marker_bytes : io_bytes;
      if (in.byte.byte + 8 > bytes) {
        fail(t, static_cast<int>(ClmError::command_io), "CVT needs 8 bytes from the byte named");
        return Flow::halt;
      }
      const auto at = [&](int i) {
        return ByteAddress{in.byte.area, in.byte.source, static_cast<std::uint8_t>(in.byte.byte + i)};
      };
      if (*dir == 0) {
        const Micro v = vars_[static_cast<std::size_t>(in.var)];
        const auto mag = static_cast<std::uint64_t>(v < 0 ? -v : v);
        std::uint64_t frac = mag % 1'000'000, whole = mag / 1'000'000;
        if (*format == 0) {
          // BCD: 3 bytes of 6 decimals (least significant first), 4 bytes of 8 integer digits, sign byte.
          for (int i = 0; i < 3; ++i, frac /= 100)
            write_byte(at(i), static_cast<std::uint8_t>((frac % 10) | ((frac / 10 % 10) << 4)));
          for (int i = 3; i < 7; ++i, whole /= 100)
            write_byte(at(i), static_cast<std::uint8_t>((whole % 10) | ((whole / 10 % 10) << 4)));
          write_byte(at(7), v < 0 ? 0xFF : 0x00);
        } else {
          // Binary [derived]: bytes 0-3 the millionths, bytes 4-7 the integer part, LSB first; sign = bit 7 of byte 7.
          for (int i = 0; i < 4; ++i) write_byte(at(i), static_cast<std::uint8_t>(frac >> (8 * i)));
          const std::uint32_t w = static_cast<std::uint32_t>(whole) | (v < 0 ? 0x8000'0000U : 0U);
          for (int i = 0; i < 4; ++i) write_byte(at(4 + i), static_cast<std::uint8_t>(w >> (8 * i)));
        }
        return Flow::next;
      }
      Micro frac = 0, whole = 0;
      bool neg = false;
      if (*format == 0) {
        Micro scale = 1;
        for (int i = 0; i < 3; ++i, scale *= 100) {
          const std::uint8_t b = image_.byte(at(i));
          if ((b & 0x0F) > 9 || (b >> 4) > 9) {
            fail(t, static_cast<int>(ClmError::bcd_input), "CVT bytes are not BCD");
            return Flow::halt;
          }
          frac += ((b & 0x0F) + 10 * (b >> 4)) * scale;
        }
        scale = 1;
        for (int i = 3; i < 7; ++i, scale *= 100) {
          const std::uint8_t b = image_.byte(at(i));
          if ((b & 0x0F) > 9 || (b >> 4) > 9) {
            fail(t, static_cast<int>(ClmError::bcd_input), "CVT bytes are not BCD");
            return Flow::halt;
          }
          whole += ((b & 0x0F) + 10 * (b >> 4)) * scale;
        }
        neg = image_.byte(at(7)) != 0;
      } else {
        std::uint32_t f = 0, w = 0;
        for (int i = 0; i < 4; ++i) f |= static_cast<std::uint32_t>(image_.byte(at(i))) << (8 * i);
        for (int i = 0; i < 4; ++i) w |= static_cast<std::uint32_t>(image_.byte(at(4 + i))) << (8 * i);
        neg = (w & 0x8000'0000U) != 0;
        whole = w & 0x7FFF'FFFFU;
        frac = f;
        if (frac >= 1'000'000 || whole > 99'999'999) {
          fail(t, static_cast<int>(ClmError::variable_value), "CVT bytes do not form a variable value");
          return Flow::halt;
        }
      }
      const Micro v = whole * micro_one + frac;
      return store_variable(in.var, neg ? -v : v, t) ? Flow::next : Flow::halt;
    }
    case Op::jmp:
      return jump(in.n[0]);
    case Op::jsr: {
      if (k.stack.size() >= static_cast<std::size_t>(max_stack)) {
        fail(t, static_cast<int>(ClmError::jsr_nesting), "more than 127 subroutine levels");
        return Flow::halt;
      }
      const Flow f = jump(in.n[0]);
      if (f == Flow::jump) k.stack.push_back(k.pc + 1);
      return f;
    }
    case Op::rts:
      if (k.stack.empty()) {
        if (k.manual_vector) {  // the manual vector program ends with its RTS
          k.manual_vector = false;
          k.active = false;
          k.pc = k.start;
          return Flow::halt;
        }
        fail(t, static_cast<int>(ClmError::rts_nesting), "RTS without JSR");
        return Flow::halt;
      }
      k.jump_to = k.stack.back();
      k.stack.pop_back();
      return Flow::jump;
    case Op::jst: {
      const Flow f = jump(in.n[0]);
      if (f != Flow::jump) return f;
      k.pc = k.jump_to;
      stop_program(true);
      return Flow::jump;
    }
    case Op::jtk: {
      auto target = integer(in.n[0], t, 0, 2999);
      auto task = integer(in.n[1], t, 1, 5);
      if (!target || !task) return Flow::halt;
      if (*task == 3) {
        fail(t, static_cast<int>(ClmError::invalid_program_command), "JTK cannot redirect task 3");
        return Flow::halt;
      }
      if (*task == t) {
        k.jump_to = *target;
        return Flow::jump;
      }
      Task& other = tasks_[static_cast<std::size_t>(*task - 1)];
      other.pc = *target;
      other.phase = 0;
      return Flow::next;
    }
    case Op::mat: {
      // One shared calculation unit: a second task's MAT waits while it is busy (§5.7 MAT).
      if (k.phase == 0) {
        if (mat_owner_ >= 0 && mat_owner_ != t) return Flow::wait;
        mat_owner_ = t;
        k.phase = 1;
        k.aux = (in.mat_op == '*' || in.mat_op == '/') ? options_.mat_cycles_mul : options_.mat_cycles_add;
      }
      if (--k.aux > 0) return Flow::wait;
      mat_owner_ = -1;
      const i128 a = *value(in.n[0], t);
      const i128 b = *value(in.n[1], t);
      i128 r = 0;
      switch (in.mat_op) {
        case '+':
          r = a + b;
          break;
        case '-':
          r = a - b;
          break;
        case '*':
          r = a * b / micro_one;
          break;
        default:
          if (b == 0) {
            fail(t, static_cast<int>(ClmError::division_by_zero), "MAT division by zero");
            return Flow::halt;
          }
          r = a * micro_one / b;
      }
      if (r > variable_max || r < -variable_max) {
        fail(t, static_cast<int>(ClmError::variable_value), "MAT result out of ±99999999.999999");
        return Flow::halt;
      }
      return store_variable(in.var, static_cast<Micro>(r), t) ? Flow::next : Flow::halt;
    }
    case Op::set:
      return store_variable(in.var, *value(in.n[0], t), t) ? Flow::next : Flow::halt;
    case Op::txt: {
      const int m = static_cast<int>(in.n[0].value / micro_one);
      if (m == 0) {
        // consecutive TXT 0 lines fill status-63 lines 1..4 in one cycle
        int idx = 0;
        for (int l = k.pc - 1; l >= 0 && idx < 3; --l) {
          const Instruction& p = program_[static_cast<std::size_t>(l)];
          if (p.op != Op::txt || p.n[0].value != 0) break;
          ++idx;
        }
        txt63_[static_cast<std::size_t>(idx)] = in.text;
      } else if (m == 1) {
        txt53_ = in.text;
      } else {
        txt53_.clear();
      }
      return Flow::next;
    }
    case Op::wai: {
      if (k.phase == 0) {
        const Micro s = *value(in.n[0], t);
        if (s < 0 || s > 99'999 * micro_one) {
          fail(t, static_cast<int>(ClmError::variable_value), "WAI time out of range");
          return Flow::halt;
        }
        k.phase = 1;
        k.until = now + std::chrono::duration_cast<Duration>(std::chrono::microseconds(s));
      }
      // The wait ends in the cycle in which the time has elapsed.
      return now + cycle_time() / 2 >= k.until ? Flow::next : Flow::wait;
    }
    case Op::rsv: {
      auto terminate = integer(in.n[0], t, 0, 1);
      if (!terminate) return Flow::halt;
      if (!k.restart_program) {
        fail(t, static_cast<int>(ClmError::invalid_program_command), "RSV outside the restart program");
        return Flow::halt;
      }
      const bool outputs = !in.text.empty() && in.text[0] == '1';
      if (*terminate == 0) {
        if (outputs)
          for (std::size_t b = 0; b < 7; ++b)
            write_byte({Area::output, 1, static_cast<std::uint8_t>(b)}, restart_.outputs[b]);
        return Flow::next;
      }
      // restore_restart() put task 1 back where the program was interrupted, a PSI/PSA still
      // waiting for its window included (its phase): Flow::wait leaves that state untouched, so
      // the interrupted feed completes to its saved absolute target (§7.11) and is not fed again.
      restore_restart(outputs);
      return Flow::wait;
    }
    case Op::eos:
    case Op::fol:
    case Op::fun:
    case Op::lmk:
    case Op::lml:
    case Op::lmr:
    case Op::mlo:
    case Op::mlt:
    case Op::aeo:
    case Op::srp:
      return exec_coupled(t, k, in);
    default:
      return exec_motion(t, k, in, now);
  }
}

}  // namespace hil::controllers::clm14
