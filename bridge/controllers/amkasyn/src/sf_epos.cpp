// SPDX-License-Identifier: MIT
// SF EPOS (type 11, manual §3.12): extended positioning by binary inputs. E1 0->1 starts (or
// continues an interrupted positioning), E2 0->1 stops with the stop deceleration DD10; A1 = 1 at
// standstill, A2 = 1 at constant speed (modulo mode). The output is a position set-point that
// continues from the sink's value at START.
//   velocity   |DD6| (0.0001 rpm) x DD12 (incr/rev), or external (BA bit0): the 16-bit source's
//              increments per cycle x DD12 / DD14; times the override MW[DW16] (1024 = 100 %,
//              0 = no output: the position holds at once);
//   ramps      DD8 (0.001 rev/s^2) x DD12 x the acceleration override MW[DW17] (clamped to
//              102..1024, sampled at each E1 edge); a stop uses DD10;
//   relative   (BA bit1 = 0): each start moves by DD4 from the current set-point; bit3 retrigger:
//              an edge while moving adds DD4 to the residual distance (opposite signs reverse at
//              once, with the ramp); bit4 modulo: with E1 = 1 when the ramp-down would begin the
//              axis runs on for another DD4, with E1 = 0 it stops at the next modulo value;
//   substitutional (bit1 = 1): run at DD6 (its sign = direction) until the drive's reference
//              latch (DriveChannels::reference_count) sees the reference, then position to DD4
//              relative to it (the drive's "continuous homing" zeroes its feedback there; here the
//              reference is located from the latch relative to the 16-bit command); bit2 allows a reversal when the end
//              position is too close or behind, without it the axis stops at the end position without the brake ramp.
// Kinematics per SF cycle: the velocity moves towards min(v, v_stop(d)) by at most the ramp, where
// v_stop(d) = (sqrt(a^2 + 8 a |d|) - a) / 2 is the highest velocity that still stops in the
// remaining distance d with the discrete ramp; the last step lands exactly on the end position.
// VALUE NEW: DD8 and DD10 at once, DD4 and DD6 from the next start edge.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"

namespace hil::controllers::amkasyn {
namespace {

int even_word(int w) noexcept {
  return w & ~1;  // odd addresses act as the next lower even one
}

class Epos final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    if (cmd.dl(0) != 0) return start_error("EPOS", "DL0 fct", cmd.dl(0), "must be 0");
    ba_ = cmd.dl(1);
    if (ba_ > 31) return start_error("EPOS", "DL1 BA", ba_, "0..31 (bits 0..4)");
    if ((ba_ & 2) && (ba_ & 16))
      return start_error("EPOS", "DL1 BA", ba_, "modulo positioning (bit4) is for relative positioning only");
    if (cmd.dw(3) != io.cycle_half_ms)
      return start_error("EPOS", "DW3 SF cycle time", cmd.dw(3), "must equal ID 2 (0.5 ms units)");
    if ((ba_ & 2) && (cmd.dw(3) < 2 || cmd.dw(3) > 18))
      return start_error("EPOS", "DW3 SF cycle time", cmd.dw(3), "2..18 for substitutional positioning (ID 2 >= 1 ms)");
    if (auto f = take(cmd)) return f;
    resolution_ = cmd.dd(12);
    if (resolution_ < 1) return start_error("EPOS", "DD12 drive encoder resolution", resolution_, "1..2^31-1 incr/rev");
    ext_resolution_ = cmd.dd(14);
    if ((ba_ & 1) && ext_resolution_ < 1)
      return start_error("EPOS", "DD14 external master encoder resolution", ext_resolution_,
                         "1..2^31-1 incr/rev with external velocity (BA bit0)");
    vel_word_ = cmd.dw(16);
    acc_word_ = cmd.dw(17);
    if (vel_word_ < 0 || vel_word_ > 127)
      return start_error("EPOS", "DW16 velocity override MW address", vel_word_, "0 (none) or 2..126");
    if (acc_word_ < 0 || acc_word_ > 127)
      return start_error("EPOS", "DW17 acceleration override MW address", acc_word_, "0 (none) or 2..126");
    if (init.sink.address == 0) return start_error("EPOS", "sink address", 0, "EPOS needs a sink");
    if ((ba_ & 2) && !(init.sink.address >= 1 && init.sink.address <= 8 && init.sink.offset == 4))
      return start_error("EPOS", "sink", init.sink.address,
                         "substitutional positioning needs SWQ1 (AW offset 4: position control, no fine "
                         "interpolation)");
    if ((ba_ & 2) && travel_ == 0)
      return start_error("EPOS", "DD4 position command value", 0,
                         "must not be 0 in substitutional positioning (the reference would be seen again)");
    drive_ = init.sink.address >= 1 && init.sink.address <= 8 ? init.sink.address - 1 : 0;
    travel_now_ = travel_;
    velocity_now_ = velocity_;
    encoder_ = hil::motion::EncoderInput(16);
    src_prev_ = encoder_.update(static_cast<std::uint32_t>(io.source.value));
    base_ = io.sink_now;
    p_ = 0.0;
    v_ = 0.0;
    target_ = 0.0;
    state_ = State::idle;
    acc_ovr_ = 1024;
    prev_e1_ = io.e(1);
    prev_e2_ = io.e(2);
    io.a(1, true);
    io.a(2, false);
    return std::nullopt;
  }

  std::optional<SfFault> value_new(const DataBlock& cmd, SfIo&) override { return take(cmd); }

  void step(SfIo& io) noexcept override {
    const std::int64_t src = encoder_.update(static_cast<std::uint32_t>(io.source.value));
    const std::int64_t src_delta = src - src_prev_;
    src_prev_ = src;
    const bool e1 = io.e(1), e2 = io.e(2);
    const bool start_edge = e1 && !prev_e1_, stop_edge = e2 && !prev_e2_;
    prev_e1_ = e1;
    prev_e2_ = e2;
    const double half = io.cycle_half_ms;
    if (start_edge) on_start(io);
    if (stop_edge && state_ != State::idle) state_ = State::stopping;
    const int ovr = vel_word_ ? io.image.mw(even_word(vel_word_)) : 1024;
    // Increments per cycle (one division each, so round figures stay exact): 0.0001 rpm x incr/rev
    // x Tsf (half ms) / (600000 x 2000); 0.001 rev/s^2 x incr/rev x Tsf^2 / (1000 x 2000^2).
    const auto res = static_cast<double>(resolution_);
    double vmax = (ba_ & 1) ? static_cast<double>(std::llabs(src_delta)) * res / static_cast<double>(ext_resolution_)
                            : std::fabs(static_cast<double>(velocity_now_)) * res * half / 1.2e9;
    vmax *= std::max(ovr, 0) / 1024.0;
    const double a = static_cast<double>(acceleration_) * res * half * half / 4e9 * acc_ovr_ / 1024.0;
    const double a_stop = static_cast<double>(deceleration_) * res * half * half / 4e9 * acc_ovr_ / 1024.0;
    bool cruise = false;
    if (ovr <= 0) {
      v_ = 0.0;  // override 0: no output
    } else {
      switch (state_) {
        case State::idle:
          break;
        case State::stopping:
          v_ = v_ > 0 ? std::max(v_ - a_stop, 0.0) : std::min(v_ + a_stop, 0.0);
          p_ += v_;
          if (v_ == 0.0) state_ = State::interrupted;
          break;
        case State::interrupted:
          break;
        case State::searching: {  // substitutional: run until the reference, then position
          const double dir = velocity_now_ < 0 ? -1.0 : 1.0;
          v_ = dir > 0 ? std::min(v_ + a, vmax) : std::max(v_ - a, -vmax);
          p_ += v_;
          const auto& d = io.image.aw[drive_];
          if (d.reference_count != ref_seen_) {
            // The drive's command and feedback share one frame: the reference lies int16(ref - cmd)
            // from the current 16-bit command (SWQ1), whatever the following error.
            ref_seen_ = d.reference_count;
            const std::int64_t cmd_now = base_ + std::llround(p_);
            const auto to_ref = static_cast<std::int16_t>(static_cast<std::uint16_t>(
                static_cast<std::uint32_t>(d.reference_position) - static_cast<std::uint32_t>(cmd_now)));
            target_ = std::round(p_) + to_ref + static_cast<double>(travel_now_);
            state_ = State::positioning;
          }
          break;
        }
        case State::positioning:
          cruise = position(e1, vmax, a);
          break;
      }
    }
    io.sink = static_cast<std::int32_t>(base_ + std::llround(p_));
    io.a(1, v_ == 0.0 && state_ != State::searching && state_ != State::positioning);
    io.a(2, (ba_ & 16) != 0 && cruise);
  }

 private:
  enum class State : std::uint8_t { idle, positioning, searching, stopping, interrupted };

  std::optional<SfFault> take(const DataBlock& cmd) {
    const std::int64_t acc = cmd.dd(8), dec = cmd.dd(10), vel = cmd.dd(6);
    if (acc < 1 || acc > 100000000) return start_error("EPOS", "DD8 acceleration", acc, "1..10^8 (0.001 rev/s^2)");
    if (dec < acc || dec > 100000000)
      return start_error("EPOS", "DD10 deceleration at stop", dec, "DD8..10^8 (at least the acceleration)");
    if (vel == 0 || vel == INT32_MIN)
      return start_error("EPOS", "DD6 velocity", vel, "+-(1..2^31-1) (0.0001 rpm; the sign is the direction)");
    acceleration_ = acc;  // immediately
    deceleration_ = dec;
    travel_ = cmd.dd(4);  // from the next start edge
    velocity_ = vel;
    return std::nullopt;
  }

  void on_start(SfIo& io) noexcept {
    if (state_ == State::interrupted) {  // continue the interrupted positioning
      state_ = ref_pending_ ? State::searching : State::positioning;
      return;
    }
    const bool moving = state_ == State::positioning || state_ == State::searching;
    if (moving) {
      if ((ba_ & 2) == 0 && (ba_ & 8) && (ba_ & 16) == 0) target_ += static_cast<double>(travel_);  // retrigger
      return;
    }
    if (state_ == State::stopping) return;
    acc_ovr_ = acc_word_ ? std::clamp<int>(io.image.mw(even_word(acc_word_)), 102, 1024) : 1024;
    travel_now_ = travel_;
    velocity_now_ = velocity_;
    if (ba_ & 2) {
      ref_seen_ = io.image.aw[drive_].reference_count;
      ref_pending_ = true;
      state_ = State::searching;
    } else {
      target_ = std::round(p_) + static_cast<double>(travel_now_);
      state_ = State::positioning;
    }
  }

  // Towards target_: returns true while at constant (commanded) speed.
  bool position(bool e1, double vmax, double a) noexcept {
    ref_pending_ = false;
    double d = target_ - p_;
    const auto stop_speed = [a](double dist) { return (std::sqrt(a * a + 8.0 * a * std::fabs(dist)) - a) / 2.0; };
    if ((ba_ & 16) && e1 && stop_speed(d) < vmax && std::fabs(v_) >= vmax - 1e-9 &&
        d * static_cast<double>(travel_now_) > 0) {
      target_ += static_cast<double>(travel_now_);  // modulo: run on for another DD4
      d = target_ - p_;
    }
    const double dir = d > 0 ? 1.0 : (d < 0 ? -1.0 : 0.0);
    const double vt = dir * std::min(vmax, stop_speed(d));
    const bool reversal = (ba_ & 2) && (ba_ & 4);
    const bool wrong_way = v_ * dir < 0.0;
    if ((ba_ & 2) && !reversal && (wrong_way || std::fabs(v_) > stop_speed(d) + a)) {
      // No reversal: an end position behind stops the axis where it is; one too close for the
      // ramp is reached at the current speed and the axis stops there without the brake ramp.
      const double next = p_ + v_;
      if (wrong_way || (dir > 0 && next >= target_) || (dir < 0 && next <= target_)) {
        if (!wrong_way) p_ = target_;
        v_ = 0.0;
        state_ = State::idle;
      } else {
        p_ = next;
      }
      return false;
    }
    const double v_before = v_;
    v_ = v_ < vt ? std::min(v_ + a, vt) : std::max(v_ - a, vt);
    const double next = p_ + v_;
    const bool passes = (dir > 0 && next >= target_) || (dir < 0 && next <= target_) || dir == 0.0;
    if (passes && (std::fabs(v_) <= stop_speed(d) + 1e-9 || !reversal)) {
      p_ = target_;
      v_ = 0.0;
      state_ = State::idle;
      return false;
    }
    p_ = next;
    return std::fabs(v_) >= vmax - 1e-9 && std::fabs(v_before) >= vmax - 1e-9;
  }

  int ba_ = 0, vel_word_ = 0, acc_word_ = 0, acc_ovr_ = 1024;
  std::size_t drive_ = 0;
  std::int64_t travel_ = 0, velocity_ = 1, acceleration_ = 1, deceleration_ = 1;
  std::int64_t travel_now_ = 0, velocity_now_ = 1, resolution_ = 1, ext_resolution_ = 1;
  hil::motion::EncoderInput encoder_{16};
  std::int64_t src_prev_ = 0, base_ = 0;
  double p_ = 0.0, v_ = 0.0, target_ = 0.0;
  State state_ = State::idle;
  std::uint32_t ref_seen_ = 0;
  bool prev_e1_ = false, prev_e2_ = false, ref_pending_ = false;
};

}  // namespace

std::unique_ptr<FastFunction> make_epos() {
  return std::make_unique<Epos>();
}

}  // namespace hil::controllers::amkasyn
