// SPDX-License-Identifier: MIT
// WF 725/726 machine data -> axis (docs/controllers.md, table "WF 725/726"). Positions in the MD
// are µm (10^-3 ° on rotary axes); the axis works in mm (deg). One increment is B_I * A µm with
// the pulse evaluation factor B_I = MD 19 + MD 20 * 10^-8 and the basic resolution A (MD 49).
#include <algorithm>
#include <cstdlib>
#include <limits>

#include "hil/controllers/parameter_controller.hpp"
#include "parameter_lookup.hpp"

namespace hil::controllers {
namespace {

double option(const ControllerSpec& spec, const char* key, double fallback, const detail::Params& p) {
  const auto it = spec.options.find(key);
  if (it == spec.options.end()) return fallback;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end != '\0' || !(v > 0.0))
    p.fail("MD4", fmt::format("open loop: controller key {} = '{}' must be a number > 0", key, it->second));
  return v;
}

// Open loop (AK, MD 4 = 3/4; docs/wf725.md "Open-loop control"): the WF outputs speed levels
// 1..99 (level x 100 mV on X3) to a drive whose speed at 10 V and own acceleration are the
// controller keys open_loop_speed (mm/min, default 10 000) and open_loop_acceleration (mm/s^2,
// default 1000). The motion core runs the axis by velocity steps under these limits; the WF
// checks the actual position itself, so the core's following-error windows are left wide open.
void open_loop_dynamics(const detail::Params& p, const ControllerSpec& spec, ControllerAxis& a) {
  auto& c = a.config;
  const double speed = option(spec, "open_loop_speed", 10000.0, p);
  const double drive_acc = option(spec, "open_loop_acceleration", 1000.0, p);
  const auto ramp = [&](const char* md) {
    // MD 1/2 (WF 726 only) in mV/s; 0 = step change (the drive's own acceleration).
    if (p.text("series").value_or("726") != "726") return drive_acc;
    const double mv_per_s = static_cast<double>(p.number(md));
    const double acc = mv_per_s * speed / 60.0 / 10000.0;
    return acc > 0.0 ? std::min(acc, drive_acc) : drive_acc;
  };
  c.limits.velocity = 0.99 * speed / 60.0;  // level 99
  c.limits.acceleration = std::max(ramp("MD1"), ramp("MD2"));
  c.quick_stop_deceleration = drive_acc;
  c.jog_velocity = c.limits.velocity / 10.0;
  const double range = 1e6;  // mm: no position loop of the WF (open loop)
  c.following_error.dynamic = false;
  c.following_error.static_window = range;
  c.standstill_window = range;
  c.in_position_window = std::max(static_cast<double>(p.number("MD33")) / 1000.0, 1e-6);
  c.in_position_timeout = std::chrono::milliseconds(static_cast<long>(p.number("MD30")));
  c.reaction = motion::FaultReaction::stop;
}

}  // namespace

std::expected<DeviceAxes, ConfigError> wf725_axes(const LoadedParameters& loaded, const ControllerSpec& spec) {
  using detail::Params;
  const Params p(loaded);
  try {
    const bool open_loop = p.text("control").value_or("LR") != "LR";
    ControllerAxis a;
    a.name = spec.options.contains("axis") ? spec.options.find("axis")->second : p.text("axis").value_or("A");
    const std::int64_t resolution = p.integer("resolution");  // µm per resolution step: 1, 10, 100
    const std::int64_t b = p.integer("MD19") * 100'000'000 + p.integer("MD20");
    if (b == 0) p.fail("MD20", "and MD 19 are both 0: the pulse evaluation factor must not be 0 (WF error 19)");
    const std::int64_t md18 = p.integer("MD18");
    auto& c = a.config;
    c.name = a.name;
    c.rotary = md18 >= 2;
    a.units = c.rotary ? "deg" : "mm";
    // inc per mm (deg) = 1000 µm / (B_I * A µm per inc) = 10^11 / (b * A), exact.
    c.inc_per_unit = detail::reduced(100'000'000'000, b * resolution);
    if (c.rotary) {
      c.modulo = static_cast<double>(md18) / 1000.0;
      // increments per turn = MD18/1000 * num/den must be an integer (num/den is reduced).
      const std::int64_t num = c.inc_per_unit.num, den = c.inc_per_unit.den;
      const bool whole = md18 % den == 0 && ((md18 / den) % 1000) * (num % 1000) % 1000 == 0;
      if (!whole)
        p.fail("MD18",
               fmt::format("= {} is not a whole number of increments ({} per 1000 µm): the motion core needs "
                           "an integer number of increments per turn; adjust MD 19/20 or MD 18",
                           md18, static_cast<double>(c.inc_per_unit.num) / static_cast<double>(c.inc_per_unit.den)));
    }
    if (open_loop) {
      open_loop_dynamics(p, spec, a);
    } else {
      const double md1 = static_cast<double>(p.number("MD1"));
      const double md2 = static_cast<double>(p.number("MD2"));
      c.limits.velocity = static_cast<double>(p.number("MD3")) / 60.0;  // mm/min -> mm/s
      c.limits.acceleration = std::min(md1, md2);
      c.quick_stop_deceleration = std::max(md1, md2);
      if (md1 != md2)
        a.warnings.push_back(
            fmt::format("MD 1 = {} and MD 2 = {} mm/s^2: the motion core plans symmetric ramps at the "
                        "smaller value; MD 2 is the quick-stop deceleration",
                        md1, md2));
      const double j1 = static_cast<double>(p.number("MD38"));
      const double j2 = static_cast<double>(p.number("MD39"));
      if (j1 > 0.0 || j2 > 0.0) {
        c.limits.jerk = j1 > 0.0 && j2 > 0.0 ? std::min(j1, j2) : std::max(j1, j2);
        if (j1 != j2) a.warnings.push_back("MD 38 != MD 39: one jerk limit (the smaller) is used for both ramps");
      }
      c.jog_velocity = std::min(c.limits.velocity, std::max(c.limits.velocity / 10.0, 1e-3));
      // Pre-limit switches MD 11/13: the axis brakes and stops exactly on them (errors 95/96).
      if (!c.rotary) {
        c.soft_limit_min = static_cast<double>(p.number("MD11")) / 1000.0;
        c.soft_limit_max = static_cast<double>(p.number("MD13")) / 1000.0;
        a.warnings.push_back(
            "MD 12/14 (range limit switches, errors 15/16) are not a second software limit in the motion core: "
            "they are served by the limit-switch inputs limit_minus/limit_plus");
      }
      c.backlash = static_cast<double>(p.number("MD31")) / 1000.0;
      c.following_error.dynamic = true;
      c.following_error.kv_per_s = static_cast<double>(p.number("MD22")) * 1000.0 / 60.0;  // (m/min)/mm -> 1/s
      c.following_error.min_window = static_cast<double>(p.number("MD26")) / 1000.0;
      c.following_error.max_window = static_cast<double>(p.number("MD24")) / 1000.0;
      c.following_error.static_window = c.following_error.max_window;
      c.standstill_window = static_cast<double>(p.number("MD25")) / 1000.0;
      c.in_position_window = static_cast<double>(p.number("MD33")) / 1000.0;
      c.in_position_timeout = std::chrono::milliseconds(static_cast<long>(p.number("MD30")));
      c.reaction = motion::FaultReaction::stop;  // "axis stops" on a supervision error
    }
    if (p.text("encoder").value_or("I") == "I") {
      ReferencePoint r;
      r.position = static_cast<double>(p.number("MD16")) / 1000.0;
      a.reference = r;
    }
    const auto v = motion::validate(c);
    if (!v) p.fail("MD3", "gives an axis the motion core rejects: " + v.error());
    DeviceAxes out;
    out.cycle = c.limits.jerk_limited() ? std::chrono::milliseconds(8) : std::chrono::milliseconds(4);
    out.axes.push_back(std::move(a));
    return out;
  } catch (const detail::MappingFailure& f) {
    return std::unexpected(f.error);
  }
}

DeviceFaultMap wf725_faults() {
  return {"traversing", [](std::size_t, const std::error_code& f, bool negative) -> std::optional<int> {
            if (f == hil::MotionFault::software_limit) return negative ? 0x95 : 0x96;  // pre-limit MD 11 / MD 13
            if (f == ControllerFault::hard_limit_negative) return 0x15;                // range limit MD 12
            if (f == ControllerFault::hard_limit_positive) return 0x16;                // range limit MD 14
            if (f == hil::MotionFault::following_error || f == hil::MotionFault::following_error_dynamic) return 0x11;
            if (f == hil::MotionFault::standstill) return 0x10;
            if (f == hil::MotionFault::in_position_timeout) return 0x22;
            if (f == hil::MotionFault::not_enabled) return 0x13;
            if (f == hil::MotionFault::drive_fault) return 0x14;
            return std::nullopt;
          }};
}

}  // namespace hil::controllers
