// SPDX-License-Identifier: MIT
// IP247 machine-data DB -> axis (docs/controllers.md, table "IP247"). The IP247 drives a stepper
// open loop: one increment is one output pulse; BU is the basic unit (1 µm, 0.0001 in, 0.001°).
#include <algorithm>

#include "hil/controllers/parameter_controller.hpp"
#include "parameter_lookup.hpp"

namespace hil::controllers {

std::expected<DeviceAxes, ConfigError> ip247_axes(const LoadedParameters& loaded, const ControllerSpec& spec) {
  using detail::Params;
  const Params p(loaded);
  try {
    ControllerAxis a;
    a.name = spec.options.contains("axis") ? spec.options.find("axis")->second : std::to_string(p.integer("DW3R"));
    const std::int64_t unit = p.integer("DW4");
    const std::int64_t bu_per_unit = unit == 2 ? 10'000 : 1'000;  // inch: 10^4 BU; mm, degree: 10^3 BU
    a.units = unit == 2 ? "inch" : unit == 3 ? "deg" : "mm";
    const std::int64_t pulses = p.integer("DW14");
    const std::int64_t gear = p.integer("DW15");  // BU per motor revolution
    if (gear < pulses)
      p.fail("DW15",
             fmt::format("= {} BU/rev with {} pulses/rev is below 1 BU per pulse (IP247 MD error 9)", gear, pulses));
    auto& c = a.config;
    c.name = a.name;
    // increments (pulses) per unit = pulses * BU_per_unit / gear, exact.
    c.inc_per_unit = detail::reduced(pulses * bu_per_unit, gear);
    const double inc_per_unit = static_cast<double>(c.inc_per_unit.num) / static_cast<double>(c.inc_per_unit.den);
    const double fmax = static_cast<double>(p.number("DW5"));            // Hz = pulses/s
    const double slope = static_cast<double>(p.number("DW9")) * 1000.0;  // Hz/ms -> pulses/s^2
    c.limits.velocity = fmax / inc_per_unit;                             // vmax = fmax * gear / pulses
    c.limits.acceleration = slope / inc_per_unit;
    c.quick_stop_deceleration = c.limits.acceleration;
    a.warnings.push_back(
        "DW 9: the IP247's exponential ramp (slope a at the origin, start-stop frequency DW 7) is planned as a "
        "constant acceleration a; the jump to the start-stop frequency is not modelled");
    c.jog_velocity = std::min(c.limits.velocity, static_cast<double>(p.number("DW17")) / 60.0);
    const bool rotary = p.integer("DW46") == 0x80;
    const double start = static_cast<double>(p.number("DW29")) / static_cast<double>(bu_per_unit);
    const double end = static_cast<double>(p.number("DW31")) / static_cast<double>(bu_per_unit);
    if (rotary) {
      c.rotary = true;
      c.modulo = end - start;
      if (start != 0.0)
        a.warnings.push_back("DW 29: a rotary range not starting at 0 is shown as [0, range) by the motion core");
    } else {
      c.soft_limit_min = start;
      c.soft_limit_max = end;
    }
    c.backlash = static_cast<double>(p.number("DW36")) / static_cast<double>(bu_per_unit);
    // Open loop: no following-error supervision on the module. The window only guards the plant
    // behind the axis (the simulated stepper): 50 ms of travel at vmax, at least 10 pulses.
    const double pulse = 1.0 / inc_per_unit;
    c.following_error.static_window = std::max(0.05 * c.limits.velocity, 10.0 * pulse);
    c.standstill_window = std::max(2.0 * pulse, 1e-9);
    c.in_position_window = pulse;
    c.reaction = motion::FaultReaction::stop;
    a.limit_switches.normally_closed = p.integer("DW33") == 1;
    ReferencePoint r;
    r.position = static_cast<double>(p.number("DW27")) / static_cast<double>(bu_per_unit);
    r.direction = p.integer("DW26") == 0x20 ? -1 : +1;
    r.velocity = static_cast<double>(p.number("DW23")) / 60.0;
    r.normally_closed = a.limit_switches.normally_closed;
    a.reference = r;
    const auto v = motion::validate(c);
    if (!v) p.fail("DW5", "gives an axis the motion core rejects: " + v.error());
    DeviceAxes out;
    out.cycle = std::chrono::milliseconds(2);  // decision: the manual names no module cycle
    out.axes.push_back(std::move(a));
    return out;
  } catch (const detail::MappingFailure& f) {
    return std::unexpected(f.error);
  }
}

DeviceFaultMap ip247_faults() {
  return {"module", [](std::size_t, const std::error_code& f, bool negative) -> std::optional<int> {
            if (f == hil::MotionFault::software_limit) return negative ? 28 : 29;  // SW limit start / end
            if (f == ControllerFault::hard_limit_negative) return 25;              // HW limit "start" overrun
            if (f == ControllerFault::hard_limit_positive) return 26;              // HW limit "end" overrun
            return std::nullopt;
          }};
}

}  // namespace hil::controllers
