// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/nc_interpreter.hpp"

#include <algorithm>
#include <cmath>

namespace hil::controllers::elg {

NcInterpreter::NcInterpreter(NcProgram program) : program_(std::move(program)) {
  if (program_.blocks.empty()) state_ = NcState::ended;
}

int NcInterpreter::block_number() const noexcept {
  if (state_ != NcState::running || pc_ >= program_.blocks.size()) return -1;
  return program_.blocks[pc_].number;
}

bool NcInterpreter::jump_taken(const NcJump& j) const noexcept {
  const double a = r(j.ra), b = r(j.rb);
  switch (j.condition) {
    case 0:
      return true;
    case 1:
      return a == b;
    case 2:
      return a != b;
    case 3:
      return a > b;
    case 4:
      return a >= b;
    case 5:
      return a < b;
    case 6:
      return a <= b;
    default:
      return false;
  }
}

void NcInterpreter::start_block(double now_s, NcMachine& machine) {
  const NcBlock& b = program_.blocks[pc_];
  ++executed_;
  for (const RAssign& a : b.r) {
    const double operand = a.from_r ? r(*a.from_r) : a.value;
    double& target = r_[static_cast<std::size_t>(a.r)];
    switch (a.op) {
      case RAssign::Op::set:
        target = operand;
        break;
      case RAssign::Op::add:
        target += operand;
        break;
      case RAssign::Op::sub:
        target -= operand;
        break;
    }
  }
  bool dwell = false;
  for (int g : b.g) {
    switch (g) {
      case 0:
        rapid_ = true;
        break;
      case 1:
        rapid_ = false;
        break;
      case 4:
        dwell = true;
        break;
      case 90:
        absolute_ = true;
        break;
      case 91:
        absolute_ = false;
        break;
      case 94:
        per_rev_ = false;
        break;
      case 95:
        per_rev_ = true;
        break;
      default:
        break;  // G17-G19, G40-G42: recorded, no effect on the path (docs/elg.md)
    }
  }
  if (b.f && !dwell) feed_ = *b.f;
  if (b.s) spindle_rpm_ = *b.s;
  bool spindle_changed = b.s.has_value();
  for (int m : b.m) {
    if (m == 3 || m == 4 || m == 5) {
      spindle_dir_ = m == 3 ? 1 : m == 4 ? -1 : 0;
      spindle_changed = true;
    }
  }
  if (spindle_changed) machine.spindle(spindle_rpm_, spindle_dir_);
  for (int m : b.m) {
    if (m != 2 && m != 30 && m != 3 && m != 4 && m != 5) machine.m_function(m);
  }
  if (b.x || b.y || b.z) {
    NcTargets t;
    const NcTargets now = machine.position();
    auto resolve = [&](const std::optional<double>& word,
                       const std::optional<double>& current) -> std::optional<double> {
      if (!word) return std::nullopt;
      return absolute_ ? *word : current.value_or(0.0) + *word;
    };
    t.x = resolve(b.x, now.x);
    t.y = resolve(b.y, now.y);
    t.z = resolve(b.z, now.z);
    const double feed_mm_per_s = per_rev_ ? feed_ * spindle_rpm_ / 60.0 : feed_ / 60.0;
    if (!rapid_ && feed_mm_per_s <= 0.0) {
      state_ = NcState::error;
      error_ = "N" + std::to_string(b.number) + ": G1 without a feed (F, and S with G95)";
      return;
    }
    machine.move(t, rapid_, feed_mm_per_s);
  }
  dwell_until_ = dwell && b.f ? now_s + std::max(0.0, *b.f) : now_s;
  in_block_ = true;
}

NcState NcInterpreter::step(double now_s, NcMachine& machine) {
  if (state_ != NcState::running) return state_;
  if (!in_block_) {
    if (pc_ >= program_.blocks.size()) {
      state_ = NcState::ended;
      return state_;
    }
    start_block(now_s, machine);
    if (state_ != NcState::running) return state_;
  }
  if (!machine.in_position() || now_s < dwell_until_) return state_;
  // The block is done: end of program, jump, or the next block.
  const NcBlock& b = program_.blocks[pc_];
  in_block_ = false;
  if (std::find(b.m.begin(), b.m.end(), 30) != b.m.end() || std::find(b.m.begin(), b.m.end(), 2) != b.m.end()) {
    // End of program: as on the System 3, M02/M30 also stop the spindle.
    if (spindle_dir_ != 0) machine.spindle(spindle_rpm_, 0);
    spindle_dir_ = 0;
    state_ = NcState::ended;
    return state_;
  }
  if (b.jump && jump_taken(*b.jump)) {
    pc_ = static_cast<std::size_t>(program_.find(b.jump->target));
  } else {
    ++pc_;
  }
  return state_;
}

}  // namespace hil::controllers::elg
