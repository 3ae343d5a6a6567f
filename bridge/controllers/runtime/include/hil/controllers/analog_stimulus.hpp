// SPDX-License-Identifier: MIT
#pragma once
// Analog inputs a scenario drives (`io: - {analog: NAME, value: V, at: T, ramp: D}`,
// docs/scenarios.md): a device's analog input (the CLM1.4's AE1..AE4 in volts) set to a value at a
// scenario time, or ramped linearly to it over a duration. The device names its analog inputs
// (Controller::resolve_analog) and takes the value through Controller::set_analog.
// Thread: the cycle thread; read() never throws or allocates.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "hil/controllers/io_image.hpp"

namespace hil::controllers {

class Controller;

/// What a device tells about one of its analog inputs.
struct AnalogInputSpec {
  std::size_t handle = 0;  ///< for Controller::set_analog
  double min = 0.0;        ///< the input's range in `unit`
  double max = 0.0;
  std::string unit;  ///< "V"
};

/// One step of an analog input: from scenario time `at` the value ramps linearly from what the
/// input had at `at` to `value` over `ramp` (0 = a step), then holds it.
struct AnalogStep {
  Duration at{};
  double value = 0.0;
  Duration ramp{};
};

/// The value of a schedule (steps in strictly increasing `at`) at scenario time `t`; `initial`
/// before the first step. A step that starts during an earlier ramp starts from that ramp's value.
[[nodiscard]] double analog_value_at(const std::vector<AnalogStep>& steps, double initial, Duration t) noexcept;

/// Drives one analog input of `controller` from a schedule: every read() (each controller cycle,
/// before its logic) sets the value of that scenario time, from the first step on (before it the
/// device's own value holds). Times count from the first read(), like TimedInput.
class AnalogSchedule final : public IoSource {
 public:
  AnalogSchedule(Controller& controller, std::size_t handle, std::vector<AnalogStep> steps, double initial = 0.0)
      : controller_(controller), handle_(handle), steps_(std::move(steps)), initial_(initial) {}
  void read(TimePoint now, IoImage& image) noexcept override;
  /// The scenario time after which the value no longer changes.
  [[nodiscard]] Duration last_change() const noexcept;

 private:
  Controller& controller_;
  std::size_t handle_;
  std::vector<AnalogStep> steps_;
  double initial_;
  std::optional<TimePoint> origin_;
};

}  // namespace hil::controllers
