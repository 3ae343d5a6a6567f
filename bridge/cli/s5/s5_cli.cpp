// SPDX-License-Identifier: MIT
// `hilbridge profile calc ip247 ...`: the IP247 machine-data calculator (docs/ip247.md). Registered
// under `profile calc` (calc_command.hpp), one subcommand per device.
#include <fmt/format.h>

#include <memory>
#include <optional>

#include "hil/cli/calc_command.hpp"
#include "hil/cli/context.hpp"
#include "hil/cli/json_output.hpp"
#include "hil/controllers/s5/ip247_calc.hpp"

namespace hil::cli {

namespace {
struct CalcOptions {
  double step_angle = 0.0;
  bool half_step = false;
  int ppr = 0;
  double gear = 0.0, speed = 0.0, fmax = 0.0, fss = 0.0, accel = 0.0, range = 0.0;
  bool json = false;
};

void run_calc(Context& ctx, const CalcOptions& o) {
  namespace s5 = hil::controllers::s5;
  s5::Ip247CalcInput in;
  const auto opt = [](double v) { return v > 0 ? std::optional<double>(v) : std::nullopt; };
  in.step_angle_deg = opt(o.step_angle);
  in.half_step = o.half_step;
  if (o.ppr > 0) in.pulses_per_rev = o.ppr;
  in.gear_um_per_rev = opt(o.gear);
  in.speed_per_min = opt(o.speed);
  in.fmax_hz = opt(o.fmax);
  in.fss_hz = opt(o.fss);
  in.accel_hz_per_ms = opt(o.accel);
  in.range_bu = opt(o.range);
  const auto r = s5::ip247_calculate(in);
  if (r.lines.empty()) {
    ctx.exit_code =
        report_error(o.json, "profile calc ip247: ", "give at least --step-angle or --pulses-per-rev (see --help)", 2);
    return;
  }
  if (o.json) {
    nlohmann::json lines = nlohmann::json::array();
    for (const auto& l : r.lines)
      lines.push_back({{"quantity", l.quantity}, {"value", l.value}, {"unit", l.unit}, {"md", l.md}});
    print_json({{"device", "ip247"}, {"ok", r.problems.empty()}, {"lines", lines}, {"problems", r.problems}});
  } else {
    for (const auto& l : r.lines) {
      fmt::print("{:<24} {:>14.6g} {:<10}{}\n", l.quantity, l.value, l.unit, l.md.empty() ? "" : "enter in MD " + l.md);
    }
    for (const auto& p : r.problems) fmt::print("problem: {}\n", p);
  }
  ctx.exit_code = r.problems.empty() ? 0 : 1;
}
}  // namespace

void register_s5(Context& ctx) {
  CLI::App* parent = calc_command(ctx);
  if (parent == nullptr) return;  // built without the profile module
  auto o = std::make_shared<CalcOptions>();
  auto* calc = parent->add_subcommand(
      "ip247",
      "IP247 machine data: resolution, pulse frequency of a speed, vmax, ramp F/tau/t_b, braking distance,\n"
      "pulse-width bound, rotary reference reproducibility; says which MD to enter. Exit 1 when an MD rule fails.");
  calc->add_option("--step-angle", o->step_angle, "Motor step angle in degrees (pulses/rev = 360/angle)");
  calc->add_flag("--half-step", o->half_step, "Half-step operation (doubles pulses/rev)");
  calc->add_option("--pulses-per-rev", o->ppr, "Pulses per revolution (instead of --step-angle)");
  calc->add_option("--gear", o->gear, "Travel per motor revolution in base units (um, 0.0001 in, m-degree)");
  calc->add_option("--speed", o->speed, "A speed in unit/min (mm/min, 0.1 in/min, degree/min): its frequency");
  calc->add_option("--fmax", o->fmax, "Maximum frequency in Hz (default: the frequency of --speed)");
  calc->add_option("--fss", o->fss, "Start-stop frequency in Hz");
  calc->add_option("--accel", o->accel, "Frequency increase a in Hz/ms");
  calc->add_option("--range", o->range, "Rotary range (end - start) in base units");
  calc->add_flag("--json", o->json, "Print the figures as one JSON object (docs/json.md)");
  calc->callback([&ctx, o] { run_calc(ctx, *o); });
}

}  // namespace hil::cli
