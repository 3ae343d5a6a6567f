// SPDX-License-Identifier: MIT
// CLM1.4 parameters -> axes (docs/controllers.md, table "CLM1.4"). Input units IU are those of
// the feed constant Ax01 (travel per encoder revolution); one increment is one quadrature edge
// of the encoder: 4 * Ax19 pulses per revolution (controller option encoder_multiplication).
#include <algorithm>
#include <cmath>
#include <limits>

#include "hil/controllers/parameter_controller.hpp"
#include "parameter_lookup.hpp"

namespace hil::controllers {
namespace {

constexpr std::int64_t feed_digits = 5;  // Ax01 format 4.5

}  // namespace

std::expected<DeviceAxes, ConfigError> clm14_axes(const LoadedParameters& loaded, const ControllerSpec& spec) {
  using detail::Params;
  const Params p(loaded);
  try {
    std::int64_t multiplication = 4;
    if (auto it = spec.options.find("encoder_multiplication"); it != spec.options.end()) {
      multiplication = std::atoll(it->second.c_str());
      if (multiplication != 1 && multiplication != 2 && multiplication != 4) {
        return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.encoder_multiplication",
                                           "expected 1, 2 or 4 (edges counted per encoder pulse)"});
      }
    }
    DeviceAxes out;
    for (int n = 1; n <= 4; ++n) {
      if (n > 1 && p.integer(fmt::format("B000.axis{}", n)) != 1) continue;
      const auto id = [&](int k) { return fmt::format("A{}{:02}", n, k); };
      const auto field = [&](int k, std::string_view f) { return fmt::format("A{}{:02}.{}", n, k, f); };
      ControllerAxis a;
      a.name = std::to_string(n);
      a.units = "IU";
      auto& c = a.config;
      c.name = a.name;
      const std::int64_t motion_type = p.integer(field(0, "motion"));
      const std::int64_t pulses = p.integer(field(19, "pulses"));
      const std::int64_t feed = detail::scaled(p.number(id(1)), feed_digits);  // IU * 10^5 per revolution
      if (feed <= 0) p.fail(id(1), "must be > 0 (feed constant, IU per revolution)");
      // inc per IU = multiplication * pulses / Ax01, exact.
      c.inc_per_unit = detail::reduced(multiplication * pulses * 100'000, feed);
      const double vmax = static_cast<double>(p.number(id(6)));
      const double acc_base = static_cast<double>(p.number(id(8)));
      const double acc_pm = static_cast<double>(p.number(field(9, "accel")));
      const double dec_pm = static_cast<double>(p.number(field(9, "decel")));
      const double acc = acc_base * (acc_pm == 0.0 ? 1000.0 : acc_pm) / 1000.0;
      const double dec = acc_base * (dec_pm == 0.0 ? 1000.0 : dec_pm) / 1000.0;
      c.limits.velocity = vmax;
      c.limits.acceleration = std::min(acc, dec);
      c.quick_stop_deceleration = std::max(acc, dec);
      if (acc != dec)
        a.warnings.push_back(
            fmt::format("{}: acceleration {} and deceleration {} IU/s^2: symmetric ramps at the "
                        "smaller, quick stop at the larger",
                        id(9), acc, dec));
      const double jerk_time = static_cast<double>(p.number(id(10)));
      if (jerk_time > 0.0) c.limits.jerk = c.limits.acceleration / jerk_time;  // T = a / j
      c.jog_velocity = std::min(vmax, static_cast<double>(p.number(id(7))));
      if (motion_type == 2) {
        c.rotary = true;
        const double modulo = static_cast<double>(p.number(field(5, "modulo")));
        c.modulo = modulo > 0.0 ? modulo : static_cast<double>(feed) / 100'000.0;
        if (p.integer(field(5, "direction")) == 1) a.warnings.push_back(id(5) + ": shortest-path rotary moves");
      } else if (motion_type == 1) {
        c.soft_limit_min = static_cast<double>(p.number(id(3)));
        c.soft_limit_max = static_cast<double>(p.number(id(4)));
      }
      // Lag supervision (Ax14) around the maximum lag RPM(Ax12) * Ax01 / (Kv * 1000) IU.
      const double kv = static_cast<double>(p.number(field(11, "kv")));
      const double rpm = static_cast<double>(p.number(field(12, "rpm")));
      const double max_lag = rpm * static_cast<double>(feed) / 100'000.0 / (kv * 1000.0);
      const double percent = static_cast<double>(p.number(field(14, "percent")));
      c.following_error.dynamic = true;
      c.following_error.kv_per_s = kv * 1000.0 / 60.0;
      c.following_error.min_window =
          std::max(max_lag * percent / 100.0, 1.0 / std::max(1.0, static_cast<double>(multiplication * pulses)));
      c.following_error.max_window = max_lag * (1.0 + percent / 100.0);
      c.following_error.static_window = c.following_error.max_window;
      const double window = static_cast<double>(p.number(field(28, "window")));
      const double inc = static_cast<double>(c.inc_per_unit.den) / static_cast<double>(c.inc_per_unit.num);
      c.in_position_window = window > 0.0 ? window : 2.0 * inc;
      c.standstill_window = std::max(2.0 * c.in_position_window, c.following_error.min_window);
      c.reaction = motion::FaultReaction::disable;  // drive enables drop (reaction drive_off)
      const auto v = motion::validate(c);
      if (!v) p.fail(id(6), "gives an axis the motion core rejects: " + v.error());
      out.axes.push_back(std::move(a));
    }
    const double b010 = static_cast<double>(p.number("B010"));
    const auto n_axes = out.axes.size();
    out.cycle = b010 > 0.0 ? std::chrono::microseconds(std::llround(b010 * 1000.0))
                           : std::chrono::milliseconds(n_axes <= 2   ? 2
                                                       : n_axes == 3 ? 3
                                                                     : 4);
    return out;
  } catch (const detail::MappingFailure& f) {
    return std::unexpected(f.error);
  }
}

DeviceFaultMap clm14_faults() {
  // Per-axis series of the diagnostic codes: axis 1 4x/5x, axis 2 7x/8x, axis 3 Ax/Bx, axis 4 Dx/Ex.
  return {"diagnostic", [](std::size_t axis, const std::error_code& f, bool negative) -> std::optional<int> {
            static constexpr int base40[] = {0x40, 0x70, 0xA0, 0xD0};
            static constexpr int base50[] = {0x50, 0x80, 0xB0, 0xE0};
            if (axis >= 4) return std::nullopt;
            if (f == hil::MotionFault::software_limit) return base50[axis] + (negative ? 0 : 1);  // target < / > limit
            if (f == ControllerFault::hard_limit_negative) return base40[axis] + 6;               // Min Travel Lmt
            if (f == ControllerFault::hard_limit_positive) return base40[axis] + 7;               // Max Travel Lmt
            if (f == hil::MotionFault::following_error || f == hil::MotionFault::following_error_dynamic)
              return base40[axis] + 3;                                    // Excess Pos Lag
            if (f == hil::MotionFault::not_enabled) return base40[axis];  // Drive not ready
            return std::nullopt;
          }};
}

}  // namespace hil::controllers
