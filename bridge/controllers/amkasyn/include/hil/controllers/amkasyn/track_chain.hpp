// SPDX-License-Identifier: MIT
#pragma once
// The output chain of one cam-controller track, shared by BINEA (manual §3.9) and CAM (§3.13):
//   t = table bit; if mode bit4: t = retriggerable monoflop(t) (a 0->1 change holds 1 for its time);
//   e = E(track+1) ^ bit1; bits3..2 = 01: t & e, 10: t | e; out = t ^ bit0; bit5: output not updated.
// And the velocity-proportional dead-time lead (averaged over the dead-time mean factor).

#include <cstdint>
#include <optional>
#include <vector>

namespace hil::controllers::amkasyn {

struct TrackMode {
  bool invert_out = false, invert_in = false, monoflop = false, output_off = false;
  int logic = 0;  ///< 0 none, 1 AND, 2 OR
  [[nodiscard]] static TrackMode from(std::uint16_t w) noexcept {
    TrackMode m;
    m.invert_out = (w & 1) != 0;
    m.invert_in = (w & 2) != 0;
    m.logic = (w >> 2) & 3;
    m.monoflop = (w & 16) != 0;
    m.output_off = (w & 32) != 0;
    return m;
  }
  [[nodiscard]] bool valid_logic() const noexcept { return logic != 3; }
};

class TrackChain {
 public:
  /// One cycle: the table bit, the track's input bit, the monoflop time of this trigger (0.5 ms
  /// units) and the SF cycle. nullopt when the output is switched off (not updated).
  std::optional<bool> step(const TrackMode& m, bool table_bit, bool input, int monoflop_half_ms,
                           int cycle_half_ms) noexcept;
  void reset() noexcept { *this = TrackChain{}; }

 private:
  bool prev_table_ = false;
  int remaining_half_ms_ = 0;
};

/// Lead = mean velocity (x per cycle over the last N cycles) x dead time / cycle.
class DeadTimeLead {
 public:
  void configure(int mean_factor) {
    n_ = mean_factor <= 0 ? 20 : mean_factor;
    hist_.assign(static_cast<std::size_t>(n_), 0.0);
    sum_ = 0;
    i_ = 0;
    filled_ = 0;
  }
  void push(double delta_per_cycle) noexcept {
    if (n_ == 0) return;
    sum_ += delta_per_cycle - hist_[static_cast<std::size_t>(i_)];
    hist_[static_cast<std::size_t>(i_)] = delta_per_cycle;
    i_ = (i_ + 1) % n_;
    if (filled_ < n_) ++filled_;
  }
  [[nodiscard]] double lead(int dead_half_ms, int cycle_half_ms) const noexcept {
    if (filled_ == 0 || dead_half_ms <= 0 || cycle_half_ms <= 0) return 0.0;
    return sum_ / filled_ * static_cast<double>(dead_half_ms) / static_cast<double>(cycle_half_ms);
  }

 private:
  std::vector<double> hist_;
  double sum_ = 0.0;
  int n_ = 0, i_ = 0, filled_ = 0;
};

}  // namespace hil::controllers::amkasyn
