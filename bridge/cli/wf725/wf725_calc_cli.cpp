// SPDX-License-Identifier: MIT
// `hilbridge profile calc wf725-726 ...`: the WF 725/726 machine-data calculator (docs/wf725.md,
// "Machine-data calculator"), registered under `profile calc` (calc_command.hpp).
#include <fmt/format.h>

#include <memory>
#include <optional>

#include "hil/cli/calc_command.hpp"
#include "hil/cli/context.hpp"
#include "hil/cli/json_output.hpp"
#include "hil/controllers/s5/wf725_calc.hpp"

namespace hil::cli {

namespace {

struct WfCalcOptions {
  std::string module = "WF726";
  bool jerk = false, absolute = false, rotary = false, json = false;
  int resolution = 0, multiplication = 0;
  double pitch = 0, range = 0, ratio = 0, pulses = 0, factor = 0, rpm = 0, motor_ratio = 0, vmax = 0, ramp = 0, kv = 0,
         dac = 0, md24 = 0, md26 = 0, feed = 0, used = 0, possible = 0, standstill = 0;
  int level = 0, creep = 0;
  double drive_speed = 0, md2 = -1, drive_acc = 0;
};

void run_wf_calc(Context& ctx, const WfCalcOptions& o) {
  namespace s5 = hil::controllers::s5;
  const auto opt = [](double v) { return v > 0 ? std::optional<double>(v) : std::nullopt; };
  s5::Wf725CalcInput in;
  in.series = o.module == "WF725" ? 725 : 726;
  in.jerk_limit = o.jerk;
  if (o.resolution > 0) in.resolution_um = o.resolution;
  in.absolute = o.absolute;
  in.rotary = o.rotary;
  in.pitch_um = opt(o.pitch);
  in.range_um = opt(o.range);
  in.ratio = opt(o.ratio);
  in.encoder_pulses = opt(o.pulses);
  in.factor = opt(o.factor);
  if (o.multiplication > 0) in.multiplication = o.multiplication;
  in.motor_rpm = opt(o.rpm);
  in.motor_ratio = opt(o.motor_ratio);
  in.vmax_mm_min = opt(o.vmax);
  in.ramp_s = opt(o.ramp);
  in.kv = opt(o.kv);
  in.dac_mv = opt(o.dac);
  in.md24_um = opt(o.md24);
  in.md26_um = opt(o.md26);
  in.feed_mm_min = opt(o.feed);
  in.used_steps = opt(o.used);
  in.possible_steps = opt(o.possible);
  if (o.standstill != 0) in.standstill_um = o.standstill;
  if (o.level > 0) in.level = o.level;
  if (o.creep > 0) in.creep_level = o.creep;
  in.drive_speed_mm_min = opt(o.drive_speed);
  if (o.md2 >= 0) in.md2_mv_s = o.md2;
  in.drive_acceleration = opt(o.drive_acc);
  const auto r = s5::wf725_calculate(in);
  if (r.lines.empty() && r.problems.empty()) {
    ctx.exit_code = report_error(o.json, "profile calc wf725-726: ",
                                 "nothing to compute: give e.g. --resolution with --pitch and --pulses, or --vmax "
                                 "with --kv (see --help)",
                                 2);
    return;
  }
  if (o.json) {
    nlohmann::json lines = nlohmann::json::array();
    for (const auto& l : r.lines)
      lines.push_back({{"quantity", l.quantity}, {"value", l.value}, {"unit", l.unit}, {"md", l.md}});
    print_json({{"device", "wf725-726"}, {"ok", r.problems.empty()}, {"lines", lines}, {"problems", r.problems}});
  } else {
    for (const auto& l : r.lines)
      fmt::print("{:<30} {:>16.10g} {:<14}{}\n", l.quantity, l.value, l.unit,
                 l.md.empty() ? "" : (l.md.starts_with("MD") ? "enter in " : "") + l.md);
    for (const auto& p : r.problems) fmt::print("problem: {}\n", p);
  }
  ctx.exit_code = r.problems.empty() ? 0 : 1;
}

}  // namespace

void register_wf725(Context& ctx) {
  CLI::App* parent = calc_command(ctx);
  if (parent == nullptr) return;  // built without the profile module
  auto o = std::make_shared<WfCalcOptions>();
  auto* calc = parent->add_subcommand(
      "wf725-726",
      "WF 725/726 machine data from the manual's formulas (§4.3): encoder selection and the pulse evaluation\n"
      "factor MD 19/20 with MD 21/34, MD 3 from the motor speed, MD 1/2 from a ramp time, DAC scaling (MD 22/23,\n"
      "Factor_DAC < 3), MD 24/26 and the feeds where the following-error window changes, the minimum MD 34 of\n"
      "an absolute encoder, MD 7 masking, MD 33/35, open loop: MD 1/2 in mV/s and MD 48 from the creep level;\n"
      "says which MD to enter. Exit 1 when an MD rule fails.");
  calc->add_option("--module", o->module, "WF725 or WF726 (cycle time for MD 34 of absolute encoders)")
      ->check(CLI::IsMember({"WF725", "WF726"}))
      ->capture_default_str();
  calc->add_flag("--jerk-limit", o->jerk, "WF 726 with a jerk limit (MD 38/39): 8 ms cycle");
  calc->add_option("--resolution", o->resolution, "Basic resolution A in um: 1, 10 or 100 (MD 49)");
  calc->add_flag("--absolute", o->absolute, "Absolute encoder (MD 4 = 2/4); default incremental");
  calc->add_option("--pitch", o->pitch, "S: spindle pitch in um (rotary: increments of one revolution, 10^-3 degree)");
  calc->add_flag("--rotary", o->rotary, "--pitch is one revolution of a rotary axis (MD 18 = S)");
  calc->add_option("--range", o->range, "S_G: absolute encoder, maximum traversing range in um");
  calc->add_option("--ratio", o->ratio, "i_GS: spindle : encoder speed ratio (default 1)");
  calc->add_option("--pulses", o->pulses,
                   "I_G: encoder lines per revolution (incremental) or total steps (absolute, e.g. 262144)");
  calc->add_option("--factor", o->factor, "B_I given directly (MD 19 + MD 20 x 10^-8) instead of --pitch/--pulses");
  calc->add_option("--multiplication", o->multiplication, "MD 21 pulse multiplication 1, 2, 4 (default 4)");
  calc->add_option("--motor-speed", o->rpm, "n: maximum motor speed in 1/min (computes MD 3)");
  calc->add_option("--motor-ratio", o->motor_ratio, "i_GM: motor : encoder speed ratio (default 1)");
  calc->add_option("--vmax", o->vmax, "Maximum feed in mm/min (instead of --motor-speed)");
  calc->add_option("--ramp-time", o->ramp, "Seconds to reach the maximum feed (computes MD 1/MD 2)");
  calc->add_option("--kv", o->kv, "K_v in (m/min)/mm (MD 22)");
  calc->add_option("--dac", o->dac, "MD 23: command voltage at MD 3 in mV (default 8000)");
  calc->add_option("--md24", o->md24, "A given MD 24 in um (default 1.2 v_max / K_v)");
  calc->add_option("--md26", o->md26, "A given MD 26 in um (default 0.1 s_max)");
  calc->add_option("--feed", o->feed, "A programmed feed in mm/min: its following-error limit s_Limit");
  calc->add_option("--possible-steps", o->possible, "MD 7 (parallel absolute): steps the encoder has (e.g. 512)");
  calc->add_option("--used-steps", o->used, "MD 7 (parallel absolute): steps used of them (e.g. 360)");
  calc->add_option("--standstill-error", o->standstill, "Measured standstill following error in um (MD 33, MD 35)");
  calc->add_option("--level", o->level,
                   "Open loop: G_soll, the speed level 1..99 --ramp-time reaches (MD 1/2 in mV/s)");
  calc->add_option("--drive-speed", o->drive_speed, "Open loop: the drive's speed at 10 V in mm/min");
  calc->add_option("--creep-level", o->creep, "Open loop: MD 44, the last level before speed 0 (computes MD 48)");
  calc->add_option("--md2", o->md2, "Open loop: MD 2, the voltage decrease ramp in mV/s (0 = step change)");
  calc->add_option("--drive-acceleration", o->drive_acc, "Open loop: the drive's own acceleration in mm/s^2");
  calc->add_flag("--json", o->json, "Print the figures as one JSON object (docs/json.md)");
  calc->footer(
      "Examples (the manual's):\n"
      "  hilbridge profile calc wf725-726 --resolution 10 --pitch 360000 --rotary --ratio 2.51 --pulses 5000\n"
      "  hilbridge profile calc wf725-726 --resolution 100 --absolute --range 25000000 --pulses 262144\n"
      "  hilbridge profile calc wf725-726 --vmax 10000 --kv 1 --dac 8000 --resolution 1\n"
      "  hilbridge profile calc wf725-726 --module WF725 --absolute --resolution 10 --factor 2.5 --vmax 10000\n"
      "  hilbridge profile calc wf725-726 --level 60 --ramp-time 5 --drive-speed 10000 --creep-level 5 --md2 0 "
      "--drive-acceleration 1000");
  calc->callback([&ctx, o] { run_wf_calc(ctx, *o); });
}

}  // namespace hil::cli
