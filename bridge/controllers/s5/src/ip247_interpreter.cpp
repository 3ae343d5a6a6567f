// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_interpreter.hpp"

#include <cmath>

namespace hil::controllers::s5 {

using stepdir::Ip247Error;
using Kind = Ip247Action::Kind;

Ip247Error Ip247Interpreter::start(int program, const Ip247MachineData& md, std::int64_t from, bool single_block) {
  const Ip247Program* p = lookup_ ? lookup_(program) : nullptr;
  if (p == nullptr) return Ip247Error::db_not_present;
  md_ = &md;
  kin_ = ip247_kinematics(md);
  depth_ = 1;
  stack_[0] = Frame{.prog = p};
  running_ = true;
  single_block_ = single_block;
  absolute_ = true;
  rotary_ = Ip247Rotary::shortest;
  inch_ = md.unit == Ip247Unit::inch;
  halt_pending_ = false;
  flying_prev_ = false;
  flying_dir_ = 0;
  from_ = from;
  m_out_ = ip247_m_none;
  trace_.clear();
  return Ip247Error::none;
}

const Ip247Program& Ip247Interpreter::current() const noexcept {
  return *stack_[static_cast<std::size_t>(depth_ - 1)].prog;
}

Ip247Action Ip247Interpreter::fail(Ip247Error e, const Ip247Block& b) {
  running_ = false;
  Ip247Action a;
  a.kind = Kind::fault;
  a.error = e;
  a.program = current().number;
  a.block = b.number;
  a.line = b.line;
  return a;
}

void Ip247Interpreter::mark_moved() noexcept {
  for (int i = 0; i < depth_; ++i) stack_[static_cast<std::size_t>(i)].moved = true;
}

void Ip247Interpreter::traced(const Ip247Block& b) {
  ++blocks_;
  if (trace_on_) trace_.push_back({current().number, b.number, m_out_});
}

bool Ip247Interpreter::to_axis_unit(std::int64_t& v) const noexcept {
  if (md_->unit == Ip247Unit::mm && inch_) {
    v = std::llround(static_cast<double>(v) * 2.54);
  } else if (md_->unit == Ip247Unit::inch && !inch_) {
    v = std::llround(static_cast<double>(v) / 2.54);
  }
  return v > -2 * ip247_coordinate_limit && v < 2 * ip247_coordinate_limit;
}

Ip247Action Ip247Interpreter::motion(const Ip247Block& b, Ip247Offsets& off) {
  Ip247Action a;
  a.kind = Kind::motion;
  const std::int64_t range = std::int64_t{md_->sw_end} - md_->sw_start;
  std::int64_t target = from_;
  if (b.g == 74) {
    a.reference = true;
    target = md_->rotary ? from_ + ip247_rotary_delta(from_, md_->reference_coordinate, range, Ip247Rotary::shortest)
                         : std::int64_t{md_->reference_coordinate};
    a.speed = md_->incremental_speed;
  } else {
    std::int64_t v = *b.x_milli;
    if (!to_axis_unit(v)) return fail(Ip247Error::illegal_path, b);
    if (absolute_) {
      if (v <= -ip247_coordinate_limit || v >= ip247_coordinate_limit) return fail(Ip247Error::illegal_path, b);
      if (md_->rotary) {
        // Absolute targets must lie in the (zero-offset shifted) range; both ends are valid.
        if (v < md_->sw_start + off.zero() || v > md_->sw_end + off.zero()) {
          return fail(Ip247Error::traversing_range_exceeded, b);
        }
        target = from_ + ip247_rotary_delta(from_, v - off.zero() - off.tool(), range, rotary_);
      } else {
        target = v - off.zero() - off.tool();
      }
    } else {
      target = from_ + v;
    }
    if (!md_->rotary && (target < md_->sw_start || target > md_->sw_end)) {
      return fail(Ip247Error::traversing_range_exceeded, b);
    }
    if (b.g == 0) {
      a.rapid = true;
      a.speed = kin_.vmax();
    } else {
      double f = *b.f;
      if (md_->unit == Ip247Unit::mm && inch_) f *= 2.54;
      if (md_->unit == Ip247Unit::inch && !inch_) f /= 2.54;
      if (f > kin_.vmax() * (1.0 + 1e-9)) return fail(Ip247Error::speed_too_high, b);
      if (kin_.frequency_hz(f) < 1.0) return fail(Ip247Error::speed_too_low, b);
      a.speed = f;
    }
  }
  const int dir = ip247_sign(target - from_);
  if (flying_prev_ && dir != flying_dir_) {
    return fail(md_->rotary && rotary_ == Ip247Rotary::shortest ? Ip247Error::no_direction_change_in_flying_change
                                                                : Ip247Error::flying_change_failed,
                b);
  }
  a.target = target;
  a.flying = b.g == 10 && b.m != 0;
  flying_dir_ = dir;
  from_ = target;
  return a;
}

Ip247Action Ip247Interpreter::next(Ip247Offsets& off) {
  if (!running_) return Ip247Action{.kind = Kind::end, .m_output = m_out_};
  for (std::size_t n = 0; n < o_.budget; ++n) {
    Frame& f = stack_[static_cast<std::size_t>(depth_ - 1)];
    const Ip247Program& prog = *f.prog;
    if (f.pc >= prog.blocks.size()) {  // past the final block (M02)
      if (depth_ > 1) {
        --depth_;  // subprogram end: its loops are closed (syntax check), so this is a call frame
        continue;
      }
      running_ = false;
      if (flying_prev_) return fail(Ip247Error::flying_change_failed, prog.blocks.back());
      off.zero_prog = 0;  // program zero offsets end with the main program; tool offsets stay
      m_out_ = 2;
      halt_pending_ = false;
      return Ip247Action{.kind = Kind::end,
                         .program = prog.number,
                         .block = prog.blocks.back().number,
                         .line = prog.blocks.back().line,
                         .m_output = 2};
    }
    const Ip247Block& b = prog.blocks[f.pc++];
    if (flying_prev_ && !(b.x_milli && (!b.g || *b.g == 0 || *b.g == 10))) {
      return fail(Ip247Error::flying_change_failed, b);  // the block after G10 must be a plain motion
    }
    if (b.call) {
      if (depth_ > ip247_max_nesting) return fail(Ip247Error::nesting_too_deep, b);
      const Ip247Program* sub = lookup_ ? lookup_(*b.call) : nullptr;
      if (sub == nullptr) return fail(Ip247Error::db_not_present, b);
      traced(b);
      stack_[static_cast<std::size_t>(depth_++)] = Frame{.prog = sub};
      continue;
    }
    if (b.g == 24) {
      if (*b.f == 0 && depth_ > 1) return fail(Ip247Error::endless_loop_not_outer, b);
      if (depth_ > ip247_max_nesting) return fail(Ip247Error::nesting_too_deep, b);
      const std::int32_t passes = *b.f == 0 ? 0 : (o_.loop_count_is_passes ? *b.f : *b.f + 1);
      traced(b);
      stack_[static_cast<std::size_t>(depth_++)] =
          Frame{.prog = &prog, .pc = f.pc, .loop = true, .loop_start = f.pc - 1, .remaining = passes};
      continue;
    }
    if (b.g == 20) {
      traced(b);
      Frame& lf = f;  // the syntax check matched G20 with the G24 of this program's innermost loop
      if (lf.remaining == 0) {
        if (!lf.moved) return fail(Ip247Error::endless_loop_not_outer, b);  // endless loop without a motion/dwell
        lf.pc = lf.loop_start + 1;
        lf.moved = false;
      } else if (--lf.remaining > 0) {
        lf.pc = lf.loop_start + 1;
        lf.moved = false;
      } else {
        const std::size_t pc = lf.pc;
        --depth_;
        stack_[static_cast<std::size_t>(depth_ - 1)].pc = pc;
      }
      continue;
    }
    if (b.g) {
      switch (*b.g) {
        case 25:
          rotary_ = Ip247Rotary::shortest;
          break;
        case 26:
          rotary_ = Ip247Rotary::forward;
          break;
        case 27:
          rotary_ = Ip247Rotary::backward;
          break;
        case 90:
          absolute_ = true;
          break;
        case 91:
          absolute_ = false;
          break;
        case 70:
        case 71:
          if (md_->unit == Ip247Unit::degree) return fail(Ip247Error::g_not_allowed, b);
          inch_ = *b.g == 70;
          break;
        case 40:
          off.tool_prog = 0;
          break;
        case 43:
        case 44: {
          Ip247Offsets t = off;
          t.tool_prog += *b.g == 43 ? md_->tool_offset : -md_->tool_offset;
          const std::int64_t range = std::int64_t{md_->sw_end} - md_->sw_start;
          if (md_->rotary && (t.tool() >= range || t.tool() <= -range)) return fail(Ip247Error::illegal_tool_offset, b);
          const std::int64_t lo = md_->sw_start + t.zero() + t.tool(), hi = md_->sw_end + t.zero() + t.tool();
          if (lo <= -ip247_coordinate_limit || hi >= ip247_coordinate_limit) {
            return fail(Ip247Error::traversing_range_exceeded, b);
          }
          off = t;
          break;
        }
        case 53:
          off.zero_prog = 0;
          break;
        case 54:
        case 55:
        case 56:
        case 57:
          off.zero_prog = -md_->zero_offsets[static_cast<std::size_t>(*b.g - 54)];
          break;
        default:
          break;  // 00, 04, 10, 74: below
      }
    }
    const bool halt = !flying_prev_ && (single_block_ || halt_pending_);
    if (b.is_dwell() || b.has_motion()) {
      Ip247Action a;
      if (b.is_dwell()) {
        if (flying_prev_) return fail(Ip247Error::flying_change_failed, b);
        a.kind = Kind::dwell;
        a.dwell_ms = std::int64_t{*b.f} * 100;
        flying_dir_ = 0;
      } else {
        a = motion(b, off);
        if (a.kind == Kind::fault) return a;
      }
      if (b.m && *b.m != 2) m_out_ = *b.m;
      a.m_output = m_out_;
      a.halt_before = halt;
      a.program = prog.number;
      a.block = b.number;
      a.line = b.line;
      halt_pending_ = b.m == 0;
      flying_prev_ = a.flying;
      mark_moved();
      traced(b);
      return a;
    }
    if (b.m == 0) {  // standalone M00: a motion of length 0
      traced(b);
      halt_pending_ = true;
      if (single_block_ || halt) {
        mark_moved();
        return Ip247Action{.kind = Kind::motion,
                           .program = prog.number,
                           .block = b.number,
                           .line = b.line,
                           .halt_before = true,
                           .m_output = m_out_,
                           .target = from_,
                           .zero_length = true};
      }
      continue;
    }
    traced(b);  // switching/offset block, or the final block: an M here is not output
  }
  return Ip247Action{.kind = Kind::pending, .m_output = m_out_};
}

}  // namespace hil::controllers::s5
