// SPDX-License-Identifier: MIT
#pragma once
// Inputs a scenario drives (the scenario's `io:` block, docs/scenarios.md): set or pulse an input
// at a time or once a condition holds, switch an input over an axis position range (position
// cams, limit switches, reference cams), and registration marks latched at the crossing.
// Each is an IoSource; times are scenario times, counted from the first read() (the run's first
// controller cycle). Thread: the cycle thread; read() never throws or allocates.

#include <functional>
#include <optional>
#include <vector>

#include "hil/controllers/io_image.hpp"
#include "hil/motion/axis.hpp"

namespace hil::controllers {

/// Sets `bit` to `value` at scenario time `at`; with `width` > 0 a pulse: back to !value at
/// at + width. Before `at` it leaves the bit alone (another source or the default 0 holds).
class TimedInput final : public IoSource {
 public:
  TimedInput(BitAddress bit, bool value, Duration at, Duration width = Duration::zero()) noexcept
      : bit_(bit), value_(value), at_(at), width_(width) {}
  void read(TimePoint now, IoImage& image) noexcept override;

 private:
  BitAddress bit_;
  bool value_;
  Duration at_, width_;
  std::optional<TimePoint> origin_;
};

/// Sets `bit` to `value` from the first cycle `condition` holds (checked every controller
/// cycle), for `width` when > 0 (a pulse), else for the rest of the run. `condition` must be
/// cheap and noexcept in effect (it reads axis status or image bits).
class ConditionInput final : public IoSource {
 public:
  ConditionInput(BitAddress bit, bool value, std::function<bool()> condition, Duration width = Duration::zero())
      : bit_(bit), value_(value), condition_(std::move(condition)), width_(width) {}
  void read(TimePoint now, IoImage& image) noexcept override;

 private:
  BitAddress bit_;
  bool value_;
  std::function<bool()> condition_;
  Duration width_;
  std::optional<TimePoint> fired_;
};

/// A switch over a position range of an axis: the input is active while the actual position is
/// in [from, to] (either bound may be open: a limit switch is [45, inf)). `active_low` gives a
/// normally-closed contact (input 0 while active). Rotary axes use the displayed position.
class PositionCam final : public IoSource {
 public:
  PositionCam(BitAddress bit, const motion::Axis& axis, std::optional<double> from, std::optional<double> to,
              bool active_low = false) noexcept
      : bit_(bit), axis_(axis), from_(from), to_(to), active_low_(active_low) {}
  void read(TimePoint now, IoImage& image) noexcept override;
  [[nodiscard]] bool active() const noexcept { return active_; }

 private:
  BitAddress bit_;
  const motion::Axis& axis_;
  std::optional<double> from_, to_;
  bool active_low_;
  bool active_ = false;
};

/// A registration (print) mark at `position`: when the axis' actual position crosses it (either
/// way) between two controller cycles, the input is 1 for `width` (at least one cycle) and the
/// crossing is latched: position = the mark's position quantised to `accuracy` (the latch's
/// stated accuracy), time = linear interpolation of the crossing between the two cycles.
class RegistrationMark final : public IoSource {
 public:
  struct Latch {
    TimePoint t{};
    double position = 0.0;
  };
  RegistrationMark(BitAddress bit, const motion::Axis& axis, double position, double accuracy,
                   Duration width = Duration::zero()) noexcept
      : bit_(bit), axis_(axis), position_(position), accuracy_(accuracy), width_(width) {}
  void read(TimePoint now, IoImage& image) noexcept override;
  /// Every crossing so far (reserve() bounds the allocation; beyond it crossings still pulse).
  [[nodiscard]] const std::vector<Latch>& latches() const noexcept { return latches_; }
  void reserve(std::size_t n) { latches_.reserve(n); }

 private:
  BitAddress bit_;
  const motion::Axis& axis_;
  double position_, accuracy_;
  Duration width_;
  std::optional<double> last_position_;
  TimePoint last_t_{};
  std::optional<TimePoint> pulse_since_;
  std::vector<Latch> latches_;
};

}  // namespace hil::controllers
