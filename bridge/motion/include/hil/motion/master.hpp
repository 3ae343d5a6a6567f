// SPDX-License-Identifier: MIT
#pragma once
// Masters of a coupling. A coupling law (Gear, CamCoupling) takes the master as an integer
// position in master increments once per cycle; these small step functions produce it:
//   - another axis: its command position (AxisStatus::command_position, via the axis' scaling)
//     or its actual position (AxisStatus::position_inc);
//   - VirtualMaster: a master axis that exists only in the controller (exact velocity, ramps);
//   - EncoderInput: an external encoder counter of 16 or 32 bits (a drive's second encoder, a
//     scenario-generated signal), unwrapped into 64 bits;
//   - TimeMaster: time itself (distance-time cams, the SF time modes).
// All are pure and clock-free: the caller hands each update the cycle period.

#include <cstdint>

#include "hil/core/clock.hpp"

namespace hil::motion {

enum class MasterKind : std::uint8_t { axis_command, axis_actual, virtual_axis, encoder, time };
[[nodiscard]] const char* to_string(MasterKind k) noexcept;

/// A master axis in software: velocity in increments/s, changed with a linear ramp at
/// `acceleration` (inc/s^2, > 0; infinity = step). The position is the exact integral of the
/// velocity: the fractional increments carry from cycle to cycle, so the master never drifts.
class VirtualMaster {
 public:
  explicit VirtualMaster(std::int64_t position_inc = 0) noexcept : position_(position_inc) {}
  /// Ramp to `velocity_inc_per_s` (signed) at `acceleration_inc_per_s2` (> 0).
  void set_velocity(double velocity_inc_per_s, double acceleration_inc_per_s2) noexcept;
  /// Advance by one cycle of `period` and return the new position (increments).
  std::int64_t update(hil::Duration period) noexcept;
  [[nodiscard]] std::int64_t position() const noexcept { return position_; }
  /// Position including the carried fraction (increments).
  [[nodiscard]] double exact_position() const noexcept { return static_cast<double>(position_) + frac_; }
  [[nodiscard]] double velocity() const noexcept { return velocity_; }

 private:
  std::int64_t position_ = 0;
  double frac_ = 0.0;  ///< [0, 1)
  double velocity_ = 0.0, target_ = 0.0, acceleration_ = 1.0;
};

/// An external encoder counter of `bits` (16 or 32) bits, unwrapped: each sample's difference
/// to the last is taken modulo 2^bits as a signed value (|step| < 2^(bits-1) per cycle, as the
/// AMKASYN 16-bit channels require) and summed into 64 bits.
class EncoderInput {
 public:
  explicit EncoderInput(int bits = 32) noexcept : bits_(bits == 16 ? 16 : 32) {}
  /// Feed the raw counter value (only the low `bits` bits count); returns the unwrapped position.
  std::int64_t update(std::uint32_t raw) noexcept;
  [[nodiscard]] std::int64_t position() const noexcept { return position_; }
  /// Set the unwrapped position the next sample continues from.
  void set_position(std::int64_t p) noexcept { position_ = p; }

 private:
  int bits_;
  bool first_ = true;
  std::uint32_t last_ = 0;
  std::int64_t position_ = 0;
};

/// Time as a master: the position counts `resolution` steps since start (e.g. 500 us for the
/// AMKASYN 0.5 ms unit). Exact: the elapsed time is summed in nanoseconds.
class TimeMaster {
 public:
  explicit TimeMaster(hil::Duration resolution = std::chrono::microseconds(1)) noexcept
      : resolution_ns_(resolution.count() > 0 ? resolution.count() : 1) {}
  std::int64_t update(hil::Duration period) noexcept {
    elapsed_ns_ += period.count();
    return position();
  }
  [[nodiscard]] std::int64_t position() const noexcept { return elapsed_ns_ / resolution_ns_; }
  void reset() noexcept { elapsed_ns_ = 0; }

 private:
  std::int64_t resolution_ns_;
  std::int64_t elapsed_ns_ = 0;
};

}  // namespace hil::motion
