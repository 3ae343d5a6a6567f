// SPDX-License-Identifier: MIT
// WF 725/726 traversing programs on the controller (docs/wf725.md, "Programs"): single step,
// automatic cycle and automatic single step; M output by MD 8/9; flying block change at the
// braking point or MD 46/47 (G23-29/G73-79); G99 read-in enable; G68/G69 flying measurement and
// flying setting of the actual value; G92/G93, G54/G53, tool offsets, subprograms.
#include <fmt/format.h>

#include <cmath>

#include "hil/controllers/s5/wf725_controller.hpp"

namespace hil::controllers::s5 {
namespace {

using namespace wf_db;
constexpr int loop_budget = 32;  // blocks without motion interpreted per cycle (no run can hang)

}  // namespace

bool Wf725Controller::start_program(TimePoint now, bool single) {
  const int number = db_.read_word(dw_program);
  if (number == 0) return raise_wf(0x80, now), false;
  const Wf725Program* p = store_->find(number);
  if (p == nullptr) return raise_wf(0x81, now, fmt::format("program {}", number)), false;
  if (!p->valid_for(opt_.axis))
    return raise_wf(0x90, now, fmt::format("program {} is valid for {}", number, p->valid_axes)), false;
  if (p->blocks.empty()) return raise_wf(0x82, now, fmt::format("program {}", number)), false;
  if (static_cast<int>(p->blocks.size()) > store_->limits().blocks_per_program)
    return raise_wf(0x68, now, fmt::format("program {} has {} blocks", number, p->blocks.size())), false;
  if (!check_slaves(*p, now)) return false;
  std::size_t index = 0;
  if (submode_ == Submode::single_step) {
    const int bn = db_.dl(dw_enable);
    if (bn == 0) return raise_wf(0x64, now), false;
    const auto* b = p->find(bn);
    if (b == nullptr) return raise_wf(0x67, now, fmt::format("N{} in program {}", bn, number)), false;
    index = static_cast<std::size_t>(b - p->blocks.data());
    if (wf725_pair_partner(*p, index)) --index;  // a pair runs from its first block
  }
  if (md_.integer(42) == 1 && md_.closed_loop() && md_.incremental())
    offset_mm_ = -axis(0).status().command_position;  // roller feed: actual value 0 at every start
  stack_.assign(1, Frame{p, index, 1});
  single_ = single;
  absolute_ = true;
  feed_ = 0;
  target_mm_ = machine_command_mm();
  running_program_ = number;
  job_ = Job::program;
  step_ = Step::fetch;
  after_m_ = -1;
  m0_pending_ = false;
  return true;
}

const Wf725Block* Wf725Controller::current_block() const noexcept {
  if (stack_.empty()) return nullptr;
  const auto& f = stack_.back();
  return f.index < f.program->blocks.size() ? &f.program->blocks[f.index] : nullptr;
}

const Wf725Block* Wf725Controller::peek_next() const noexcept {
  if (stack_.empty()) return nullptr;
  const auto& f = stack_.back();
  return f.index + 1 < f.program->blocks.size() ? &f.program->blocks[f.index + 1] : nullptr;
}

bool Wf725Controller::advance() noexcept {
  while (!stack_.empty()) {
    auto& f = stack_.back();
    if (++f.index < f.program->blocks.size()) return true;
    if (--f.passes_left > 0) {
      f.index = 0;
      return true;
    }
    if (stack_.size() == 1) return false;
    stack_.pop_back();  // back in the caller, after its call block
  }
  return false;
}

void Wf725Controller::end_program() {
  if (running_buffer_ != 0) {
    // A buffer that ran is consumed: the PLC reloads it (same length) before it runs again.
    buffers_[static_cast<std::size_t>(running_buffer_ - 1)].program.blocks.clear();
    running_buffer_ = 0;
  }
  job_ = Job::none;
  stack_.clear();
  step_ = Step::fetch;
  running_program_ = running_block_ = 0;
  continuous_measure_ = false;
}

double Wf725Controller::block_target_mm(const Wf725Block& b, bool absolute) const noexcept {
  const double x = static_cast<double>(*b.x) * um;
  if (!absolute) return target_mm_ + x;
  return x - zero_shift_mm_ + static_cast<double>(offsets_um_[static_cast<std::size_t>(tool_)]) * um;
}

bool Wf725Controller::begin_block(TimePoint now) {
  const Wf725Block* b = current_block();
  if (b == nullptr) {
    end_program();
    return false;
  }
  running_block_ = b->number;
  const auto fail = [&](int code, std::string context = {}) {
    raise_wf(code, now,
             fmt::format("program {} N{}{}{}", stack_.back().program->number, b->number, context.empty() ? "" : ": ",
                         context));
    abort_job();
    return false;
  };
  auto& f = stack_.back();
  if (b->skippable && db_.bit(dw_control, bit_skip)) {
    // An interpolation pair is skipped as a whole (both its blocks are skippable).
    const bool pair = combined_kind(*b) == 2;
    if (f.index + (pair ? 2 : 1) == f.program->blocks.size()) return fail(0x88);
    if (!advance() || (pair && !advance())) {
      end_program();
      return false;
    }
    step_ = Step::fetch;
    return true;
  }
  if (b->call) {
    if (stack_.size() >= 3) return fail(0x91, "a third subprogram level");
    const Wf725Program* sub = store_->find(*b->call);
    if (sub == nullptr) return fail(0x81, fmt::format("L{}", *b->call));
    if (!sub->valid_for(opt_.axis)) return fail(0x90, fmt::format("L{}", *b->call));
    if (sub->blocks.empty()) return fail(0x82, fmt::format("L{}", *b->call));
    stack_.push_back(Frame{sub, 0, b->passes.value_or(1)});
    step_ = Step::fetch;
    return true;
  }
  if (combined_kind(*b) != 0) return begin_combined(now);  // another axis' block, a G17-G19 pair
  const bool any_g = b->group(1) >= 0 || b->group(2) >= 0 || b->group(3) >= 0 || b->group(4) >= 0;
  if (!any_g && !b->x && !b->f && !b->m && !b->tool) return fail(0x61);
  if (b->group(1) == 90) absolute_ = true;
  if (b->group(1) == 91) absolute_ = false;
  const bool roller = md_.integer(42) == 1 && md_.closed_loop() && md_.incremental();
  if (roller && absolute_ && b->x) return fail(0x70, "roller feed (MD 42 = 1) takes G91 only");
  const int g2 = b->group(2), g3 = b->group(3), g4 = b->group(4);
  if (open_loop() && g4 >= 0)
    return fail(0x7A, fmt::format("G{}: the 4th G group is not allowed in open loop (MD 4 = {})", g4, md_.integer(4)));
  change_group_ = (g4 >= 23 && g4 <= 29) ? 46 : (g4 >= 73 && g4 <= 79) ? 47 : 0;
  if (b->tool && g3 != 54) {
    if (*b->tool == 0) {
      if (tool_ == 0) return fail(0x87);
      tool_ = 0;
    } else {
      tool_ = *b->tool;
    }
  }
  const bool continuous = g2 == 68 || g2 == 69;
  if (g3 == 92 && !continuous) {
    if (g92_active_) return fail(0x92);
    if (!b->x) return fail(0x62, "G92 needs the actual value X");
    zero_shift_mm_ = static_cast<double>(*b->x) * um - machine_command_mm();
    g92_active_ = true;
  } else if (g3 == 93) {
    if (!g92_active_) return fail(0x93);
    zero_shift_mm_ = 0.0;
    g92_active_ = false;
  } else if (g3 == 54) {
    const int n = b->tool.value_or(0);
    if (n < 1) return fail(0x62, "G54 selects the offset memory with T1..T20");
    zero_shift_mm_ = -static_cast<double>(offsets_um_[static_cast<std::size_t>(n)]) * um;
    g54_active_ = true;
  } else if (g3 == 53) {
    if (!g54_active_) return fail(0x89);
    zero_shift_mm_ = 0.0;
    g54_active_ = false;
  }
  if (b->f && g2 != 4) feed_ = *b->f;
  m0_pending_ = b->m && *b->m == 0;
  after_m_ = -1;
  const int m = b->m && *b->m != 0 ? *b->m : -1;
  if (g2 == 4) {
    dwell_end_ = now + std::chrono::milliseconds(*b->f);
    if (m >= 0) output_m(m, now);
    step_ = Step::dwell;
    return true;
  }
  if (continuous) {
    // §4.3 MD 15: endless travel in the G68 (-) / G69 (+) direction until the fast input's edge.
    const int e = md_.fast_input_with(3);
    if (e == 0) return fail(0xB9, "no fast input E4..E6 has function 3 in MD 15");
    if (feed_ == 0) return fail(0x73);
    continuous_input_ = e;
    continuous_measure_ = true;
    if (m >= 0) output_m(m, now);
    if (!go_velocity(g2 == 68 ? -1 : 1, feed_, now)) {
      abort_job();
      return false;
    }
    step_ = Step::continuous;
    return true;
  }
  if (g2 == 99) {
    const int e = md_.fast_input_with(4);
    if (e != 0 && !fast_input(e)) {
      step_ = Step::wait_enable;
      return true;
    }
  }
  return begin_motion(now);
}

bool Wf725Controller::begin_motion(TimePoint now) {
  const Wf725Block* b = current_block();
  const int m = b->m && *b->m != 0 ? *b->m : -1;
  const int md9 = static_cast<int>(md_.integer(9));
  const bool moves = b->x && b->group(3) != 92;
  if (moves) {
    if (m >= 0 && md9 == 2) {
      output_m(m, now);  // before the block: the axis waits for the acknowledgement
      step_ = Step::m_before;
      return true;
    }
    if (m >= 0 && md9 == 3) after_m_ = m;
    if (m >= 0 && md9 != 3) output_m(m, now);
    return start_block_motion(now);
  }
  if (m >= 0) {
    output_m(m, now);
    step_ = Step::m_after;
    return true;
  }
  if (!b->f && !b->tool && b->group(3) < 0 && !m0_pending_) {
    raise_wf(0x62, now, fmt::format("N{}: no position, feed, dwell or M function", b->number));
    abort_job();
    return false;
  }
  finish_block();
  return true;
}

bool Wf725Controller::start_block_motion(TimePoint now) {
  const Wf725Block* b = current_block();
  const double target = block_target_mm(*b, absolute_);
  motion::Direction dir = motion::Direction::shortest;
  if (md_.rotary()) {
    dir = absolute_ ? rotary_direction() : (*b->x >= 0 ? motion::Direction::positive : motion::Direction::negative);
  }
  if (!go(target, feed_, now, dir)) {
    abort_job();
    return false;
  }
  target_mm_ = target;
  step_ = Step::motion;
  return true;
}

void Wf725Controller::finish_block() {
  // The axis stays until every M function is acknowledged (leading edge, or the MD 8 time).
  if (m_state_ == MState::strobe || m_state_ == MState::timed) {
    step_ = Step::m_after;
    return;
  }
  if (submode_ == Submode::single_step) {
    end_program();
    return;
  }
  if (m0_pending_ || single_) {
    step_ = Step::wait_start;  // M0 / automatic single step: the next start continues
    return;
  }
  if (running_buffer_ != 0 && buffer_change(last_now_)) return;
  if (!advance()) {
    end_program();
    return;
  }
  step_ = Step::fetch;
}

bool Wf725Controller::flying_change(const CycleTime& cycle) {
  // Flying block change (§4.3 MD 9, MD 46/47, MD 15 G99): only in automatic cycle with M output
  // during the block (MD 9 = 1) and finished, into a motion block in the same direction, at the
  // braking point, or MD 46 (G23-29) / MD 47 (G73-79) before the end if that is shorter.
  // Open loop: every block ends with speed 0 and the PEH window (no flying change, decision).
  if (open_loop() || single_ || m0_pending_ || md_.integer(9) != 1 || m_state_ != MState::idle || after_m_ >= 0 ||
      limit_side_ != 0)
    return false;
  const Wf725Block* n = peek_next();
  if (n == nullptr || !n->x || n->call || n->group(3) >= 0 || combined_kind(*n) != 0) return false;
  if (n->group(2) == 4 || n->group(2) == 68 || n->group(2) == 69) return false;
  if (n->skippable && db_.bit(dw_control, bit_skip)) return false;
  const auto& st = axis(0).status();
  const double v = std::abs(st.command_velocity);
  if (v <= 0.0) return false;
  const bool abs_next = n->group(1) == 90 ? true : n->group(1) == 91 ? false : absolute_;
  if (md_.integer(42) == 1 && abs_next) return false;
  const double next = block_target_mm(*n, abs_next);
  const int dir_now = st.command_velocity > 0 ? 1 : -1;
  if ((next - target_mm_) * dir_now <= 0.0) return false;
  if (n->group(2) == 99) {
    const int e = md_.fast_input_with(4);
    if (e != 0 && !fast_input(e)) return false;
  }
  const double a = axis(0).config().limits.acceleration;
  const double brake = v * v / (2.0 * a);
  const double tol = change_group_ == 46   ? static_cast<double>(md_.integer(46)) * um
                     : change_group_ == 47 ? static_cast<double>(md_.integer(47)) * um
                                           : 0.0;
  const double at = tol > 0.0 && tol < brake ? tol : brake;
  const double remaining = std::abs(to_axis(target_mm_) - st.command_position);
  const double dt = to_seconds(cycle_period());
  if (remaining > at + v * dt) return false;
  block_changes_um_.push_back((machine_command_mm() + zero_shift_mm_) / um);
  if (!advance()) return false;
  step_ = Step::fetch;
  (void)cycle;
  return true;
}

void Wf725Controller::continuous_cycle(TimePoint now) {
  if (motion_done()) {
    // Ran onto the pre-limit switch without the edge.
    if (limit_side_ != 0) raise_wf(limit_side_ < 0 ? 0x95 : 0x96, now);
    abort_job();
    return;
  }
  const int e = continuous_input_;
  if (!io().rising(BitAddress{IoArea::input, 0, static_cast<std::uint8_t>(e - 1)})) return;
  measured_um_ = actual_um();
  continuous_measure_ = false;
  const Wf725Block* b = current_block();
  if (m0_pending_) {
    // Flying measurement: the axis stops on the braking ramp; data code 32 reads the latch.
    (void)axis(0).stop();
    limit_side_ = 0;
    step_ = Step::stopping;
    return;
  }
  if (b->group(3) == 92 && b->x) {
    // Flying setting of the actual value: the edge position becomes X; the old value is lost.
    const double delta = static_cast<double>(*b->x) * um - (machine_mm() + zero_shift_mm_);
    offset_mm_ += delta;
  }
  target_mm_ = machine_command_mm();
  limit_side_ = 0;
  if (!advance()) {
    (void)axis(0).stop();
    end_program();
    return;
  }
  step_ = Step::fetch;  // the next block takes over the moving axis without a stop
}

void Wf725Controller::program_cycle(const CycleTime& cycle) {
  const TimePoint now = cycle.now;
  for (int budget = 0; budget < loop_budget && job_ == Job::program; ++budget) {
    switch (step_) {
      case Step::fetch:
        // The next M output waits for the trailing edge of the last acknowledgement (MD 8).
        if (m_state_ != MState::idle) return;
        if (!begin_block(now)) return;
        continue;
      case Step::m_before:
        // MD 9 = 2: the motion starts when the M function is acknowledged (leading edge).
        if (m_state_ == MState::strobe || m_state_ == MState::timed) return;
        (void)start_block_motion(now);
        return;
      case Step::motion:
        if (flying_change(cycle)) continue;
        if (!motion_done()) return;
        if (limit_side_ != 0) {
          raise_wf(limit_side_ < 0 ? 0x95 : 0x96, now);
          abort_job();
          return;
        }
        if (after_m_ >= 0) {
          output_m(after_m_, now);
          after_m_ = -1;
          step_ = Step::m_after;
          return;
        }
        finish_block();
        continue;
      case Step::m_after:
        if (m_state_ == MState::strobe || m_state_ == MState::timed) return;
        finish_block();
        if (step_ == Step::m_after) return;
        continue;
      case Step::dwell:
        if (now < dwell_end_) return;
        finish_block();
        if (step_ == Step::m_after) return;
        continue;
      case Step::wait_start:
        return;
      case Step::wait_enable: {
        const int e = md_.fast_input_with(4);
        if (e != 0 && !fast_input(e)) return;
        if (!begin_motion(now)) return;
        continue;
      }
      case Step::continuous:
        continuous_cycle(now);
        if (step_ != Step::fetch) return;
        continue;
      case Step::stopping:
        if (!motion_done()) return;
        step_ = Step::wait_start;
        return;
      case Step::combined:
        if (!combined_cycle(now)) return;
        continue;
    }
  }
}

}  // namespace hil::controllers::s5
