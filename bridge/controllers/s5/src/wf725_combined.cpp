// SPDX-License-Identifier: MIT
// Combined programs across the axes of a WF 726 (docs/wf725.md, "Combined programs"): the axis
// that is started is the master; a block with another axis' letter moves that axis (a slave in
// submode "0"), one block after the other; a G17/G18/G19 pair moves two axes together by linear
// interpolation (the F of the pair's first block is the path feed, split in the ratio of the
// distances, the ramps scaled the same way, so both axes start and arrive together). Errors:
// 69 (slave) / 6B (master) for a slave not in submode "0", 6A in the master for any slave error
// during the program, 7A (open loop, WF 725), D2 (jerk limit MD 38/39).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/controllers/s5/wf726_module.hpp"

namespace hil::controllers::s5 {
namespace {

using namespace wf_db;

constexpr int max_levels = 3;  // main program and two subprogram levels (91 beyond)

/// Every axis letter the blocks of `p` and the programs it calls name.
void collect_letters(const Wf725ProgramStore& store, const Wf725Program& p, int depth, std::string& letters) {
  if (depth >= max_levels) return;
  for (const auto& b : p.blocks) {
    if (b.axis != 0 && letters.find(b.axis) == std::string::npos) letters.push_back(b.axis);
    if (b.call)
      if (const auto* sub = store.find(*b.call); sub != nullptr && sub != &p)
        collect_letters(store, *sub, depth + 1, letters);
  }
}

}  // namespace

int Wf725Controller::combined_kind(const Wf725Block& b) const noexcept {
  if (!wf725_pair_axes(b.group(4)).empty()) return 2;
  return b.axis != 0 && b.axis != opt_.axis ? 1 : 0;
}

bool Wf725Controller::slave_ready() const noexcept {
  return traversing_ && submode_ == Submode::none && job_ == Job::none && master_ == nullptr;
}

bool Wf725Controller::check_slaves(const Wf725Program& p, TimePoint now) {
  std::string letters;
  collect_letters(*store_, p, 0, letters);
  bool ok = true;
  for (const char l : letters) {
    if (l == opt_.axis) continue;
    Wf725Controller* s = module_ != nullptr ? module_->axis(l) : nullptr;
    if (s == nullptr) {
      raise_wf(0x6B, now, fmt::format("program {} moves axis {}, which this module does not have", p.number, l));
      ok = false;
    } else if (!s->slave_ready()) {
      s->raise_wf(0x69, now,
                  fmt::format("axis {} starts combined program {}: this slave axis must be in traversing with "
                              "submode \"0\" (DR 0 = 0) and no job",
                              opt_.axis, p.number));
      raise_wf(0x6B, now, fmt::format("slave axis {} is not in submode \"0\"", l));
      ok = false;
    }
  }
  return ok;
}

double Wf725Controller::combined_target(const Wf725Block& b, bool absolute) const noexcept {
  const double x = static_cast<double>(*b.x) * um;
  return absolute ? x - zero_shift_mm_ : machine_command_mm() + x;
}

bool Wf725Controller::slave_move(Wf725Controller& master, double target_mm, std::int64_t feed, double acceleration,
                                 TimePoint now) {
  clear_self_acknowledging();
  master_ = &master;
  job_ = Job::slave;
  running_program_ = master.running_program_;
  running_block_ = master.running_block_;
  if (!go(target_mm, feed, now, motion::Direction::shortest, acceleration)) {
    abort_job();
    return false;
  }
  target_mm_ = target_mm;
  return true;
}

void Wf725Controller::release_slaves(bool abort) noexcept {
  for (auto*& a : combined_axes_) {
    if (a != nullptr && a != this && a->master_ == this) {
      if (abort) {
        a->abort_job();  // ramp stop
      } else {
        a->job_ = Job::none;
        a->master_ = nullptr;
        a->running_program_ = a->running_block_ = 0;
      }
    }
    a = nullptr;
  }
}

bool Wf725Controller::begin_combined(TimePoint now) {
  const Wf725Block& b = *current_block();
  const int program = stack_.back().program->number;
  const auto fail = [&](int code, std::string context) {
    raise_wf(code, now, fmt::format("program {} N{}: {}", program, b.number, context));
    abort_job();
    return false;
  };
  const bool pair = combined_kind(b) == 2;
  const Wf725Block* blocks[2] = {&b, pair ? peek_next() : nullptr};
  if (pair && blocks[1] == nullptr) return fail(0x62, "the G17-G19 pair has no second block");
  const int count = pair ? 2 : 1;
  Wf725Controller* axes[2] = {nullptr, nullptr};
  for (int i = 0; i < count; ++i) {
    const char l = blocks[i]->axis;
    axes[i] = l == 0 || l == opt_.axis ? this : (module_ != nullptr ? module_->axis(l) : nullptr);
    if (axes[i] == nullptr) return fail(0x6B, fmt::format("the module has no axis {}", l));
    // Checked again at each block: a buffer or a subprogram reaches a slave the start did not see.
    if (axes[i] != this && !axes[i]->slave_ready()) {
      axes[i]->raise_wf(0x69, now,
                        fmt::format("axis {} runs program {} N{}: this slave axis must be in traversing "
                                    "with submode \"0\" and no job",
                                    opt_.axis, program, blocks[i]->number));
      return fail(0x6B, fmt::format("slave axis {} is not in submode \"0\"", l));
    }
  }
  if (pair) {
    const int g = b.group(4);
    if (md_.series == 725) return fail(0x7A, fmt::format("G{}: interpolation of axis pairs is a WF 726 function", g));
    for (auto* a : axes) {
      if (a->open_loop())
        return fail(0x7A, fmt::format("G{}: axis {} is in open loop (MD 4 = {}); interpolation is closed loop only", g,
                                      a->opt_.axis, a->md_.integer(4)));
      if (a->md_.get(38) != 0 || a->md_.get(39) != 0)
        return fail(0xD2, fmt::format("G{}: axis {} has a jerk limit (MD 38/39)", g, a->opt_.axis));
    }
  }
  // Modal G90/G91 and F are the program's (the master's), whichever axis a block moves.
  for (int i = 0; i < count; ++i) {
    if (blocks[i]->group(1) == 90) absolute_ = true;
    if (blocks[i]->group(1) == 91) absolute_ = false;
  }
  if (b.f) feed_ = *b.f;
  if (!pair && b.group(4) >= 0) change_group_ = 0;
  m0_pending_ = false;
  combined_m_.clear();
  for (int i = 0; i < count; ++i)
    if (blocks[i]->m) {
      if (*blocks[i]->m == 0)
        m0_pending_ = true;
      else
        combined_m_.push_back(*blocks[i]->m);
    }
  if (!b.x) {
    // A block of another axis without position: only its feed / M functions (the master's).
    if (!b.f && combined_m_.empty() && !m0_pending_) return fail(0x62, "no position, feed or M function");
    combined_blocks_ = 1;
    combined_done_ = true;
    step_ = Step::combined;
    return true;
  }
  if (feed_ <= 0) return fail(0x73, "no feed");
  double target[2] = {0.0, 0.0}, from[2] = {0.0, 0.0};
  for (int i = 0; i < count; ++i) {
    auto* a = axes[i];
    target[i] = a == this ? block_target_mm(*blocks[i], absolute_) : a->combined_target(*blocks[i], absolute_);
    from[i] = a == this ? target_mm_ : a->machine_command_mm();
  }
  std::int64_t feeds[2] = {feed_, feed_};
  double acc[2] = {0.0, 0.0};
  if (pair) {
    // Linear interpolation: path feed F split in the ratio of the distances; the path's velocity
    // and acceleration are reduced until neither axis exceeds its own MD 3 / ramp.
    const double d[2] = {std::abs(target[0] - from[0]), std::abs(target[1] - from[1])};
    const double path = std::hypot(d[0], d[1]);
    double v = static_cast<double>(feed_) / 6000.0, a = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 2; ++i) {
      if (d[i] <= 0.0) continue;
      const auto& lim = axes[i]->axis(0).config().limits;
      v = std::min(v, lim.velocity * path / d[i]);
      a = std::min(a, lim.acceleration * path / d[i]);
    }
    for (int i = 0; i < 2; ++i) {
      if (path <= 0.0 || d[i] <= 0.0) continue;
      feeds[i] = std::max<std::int64_t>(1, std::llround(v * d[i] / path * 6000.0));
      acc[i] = a * d[i] / path;
    }
  }
  combined_blocks_ = count;
  combined_done_ = false;
  for (int i = 0; i < count; ++i) {
    auto* a = axes[i];
    combined_axes_[static_cast<std::size_t>(i)] = a;
    if (a == this) {
      if (!go(target[i], feeds[i], now, motion::Direction::shortest, acc[i])) {
        abort_job();
        return false;
      }
      target_mm_ = target[i];
    } else if (!a->slave_move(*this, target[i], feeds[i], acc[i], now)) {
      return fail(0x6A, fmt::format("slave axis {} refused the motion", a->opt_.axis));
    }
  }
  step_ = Step::combined;
  return true;
}

bool Wf725Controller::combined_cycle(TimePoint now) {
  if (!combined_done_) {
    bool done = true;
    for (auto* a : combined_axes_) {
      if (a == nullptr) continue;
      if (a == this) {
        done = done && motion_done();
        continue;
      }
      // A slave error (or the slave's own stop, RESET, change of mode) ends the program on every axis.
      const bool lost = a->master_ != this || a->job_ != Job::slave;
      if (lost || a->errors().blocks_motion(0)) {
        int code = 0;
        for (const auto& e : a->errors().active())
          if (e.catalogue == a->traversing_cat_) code = e.code;
        raise_wf(0x6A, now,
                 code != 0 ? fmt::format("slave axis {}: error {:02X}", a->opt_.axis, code)
                           : fmt::format("slave axis {} left the combined program", a->opt_.axis));
        abort_job();
        return false;
      }
      done = done && a->motion_done();
    }
    if (!done) return false;
    for (auto* a : combined_axes_) {
      if (a == nullptr || a->limit_side_ == 0) continue;
      // Ran onto a pre-limit switch: 95/96 in that axis, 6A in the master for a slave.
      a->raise_wf(a->limit_side_ < 0 ? 0x95 : 0x96, now);
      if (a != this) raise_wf(0x6A, now, fmt::format("slave axis {}: pre-limit switch", a->opt_.axis));
      abort_job();
      return false;
    }
    release_slaves(false);
    combined_done_ = true;
  }
  // The M functions of the combined blocks: the master's, after the motion, in block order.
  if (m_state_ != MState::idle) return false;
  if (!combined_m_.empty()) {
    output_m(combined_m_.front(), now);
    combined_m_.erase(combined_m_.begin());
    return false;
  }
  for (int i = 1; i < combined_blocks_; ++i) (void)advance();  // onto the pair's second block
  combined_blocks_ = 0;
  finish_block();
  return step_ != Step::m_after;
}

}  // namespace hil::controllers::s5
