// SPDX-License-Identifier: MIT
// `hilbridge profile calc sinumerik-elg ...`: the setting-up calculations of the SINUMERIK System 3
// ELG manual (13.3 encoder and resolution matching, 12.1 units, 7.2 INC, 2.2 differential
// constants) and the gearing constants the ELG computes on "Compute gearing constants", with its
// alarms 2200/2203. Each group of options prints its figures; exit 1 when the ELG would refuse the
// data (an alarm, a fractional MD 396*, a speed above the counting limit), 2 on bad use.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/cli/calc_command.hpp"
#include "hil/cli/context.hpp"
#include "hil/cli/json_output.hpp"
#include "hil/controllers/elg/calculator.hpp"
#include "hil/controllers/elg/gear.hpp"

namespace hil::cli {
namespace {

namespace elg = hil::controllers::elg;

struct ElgCalcOptions {
  std::optional<long long> pulses;  ///< MD 396* of the axis
  std::optional<double> resolution, lines, gear_ku, fmax, rpm;
  std::optional<long long> increments;
  std::optional<double> module, helix, lead;
  std::optional<int> z0, z2;
  std::string ud_z = "0", ud_y = "0";
  long long n00 = 180000, n02 = 180000, ms_z_nm = 500, ms_y_nm = 500;
  bool json = false;
};

// The figures as a table, or with --json collected into {"lines": [...]} (docs/json.md).
struct Printer {
  bool json = false;
  std::vector<std::string> problems;
  nlohmann::json lines = nlohmann::json::array();
  void line(std::string_view quantity, double value, std::string_view unit, std::string_view where = {}) {
    if (json) {
      lines.push_back({{"quantity", quantity}, {"value", value}, {"unit", unit}, {"enter", where}});
      return;
    }
    fmt::print("{:<34} {:>16.8g} {:<9}{}\n", quantity, value, unit, where.empty() ? "" : std::string(where));
  }
  void text(std::string_view quantity, std::string_view value) {
    if (json) {
      lines.push_back({{"quantity", quantity}, {"value", value}});
      return;
    }
    fmt::print("{:<34} {:>16}\n", quantity, value);
  }
};

constexpr std::string_view prefix = "profile calc sinumerik-elg: ";

std::string rational(const elg::Rational& r) {
  return r.den == 1 ? std::to_string(r.num) : fmt::format("{}/{}", r.num, r.den);
}

void run_elg_calc(Context& ctx, const ElgCalcOptions& o) {
  Printer p;
  p.json = o.json;
  bool any = false;
  const double fmax = o.fmax.value_or(500'000.0);
  // The axis' own encoder: units, counting limit, frequency at a speed, INC step.
  std::optional<long long> pulses = o.pulses;
  std::optional<double> resolution = o.resolution;
  if (o.lines) {
    any = true;
    resolution = elg::resolution_deg(*o.lines, o.gear_ku.value_or(1.0));
    p.line("resolution A = 360/(4 I ku)", *resolution, "deg");
  }
  if (resolution && !pulses) {
    any = true;
    const double n = elg::pulses_for_resolution(*resolution);
    p.line("MD 396* = 360/(4 A)", n, "pulses", "enter in MD 396* (pulses per revolution)");
    if (std::abs(n - std::round(n)) > 1e-9 * std::max(1.0, n)) {
      p.problems.push_back(
          fmt::format("MD 396* = {:.6g} is not a whole number: choose a resolution that gives one", n));
    } else {
      pulses = std::llround(n);
    }
  }
  if (pulses) {
    any = true;
    if (*pulses <= 0 || *pulses > 2'000'000) {
      p.problems.push_back(fmt::format("MD 396* = {} is outside 1..2 000 000 (alarm 2200)", *pulses));
    } else {
      const double ms = elg::ms_unit_deg(*pulses);
      p.line("measuring-system unit MS", ms, "deg");
      p.line("input unit (2 MS)", elg::input_unit_deg(*pulses), "deg");
      const double nmax = elg::max_axis_speed_rpm(fmax, *pulses);
      p.line(fmt::format("max axis speed at {:g} kHz", fmax / 1000.0), nmax, "rpm");
      if (o.rpm) {
        const double f = elg::encoder_frequency_hz(*o.rpm, *pulses);
        p.line(fmt::format("encoder frequency at {:g} rpm", *o.rpm), f, "Hz");
        if (f > fmax) {
          p.problems.push_back(
              fmt::format("{:g} rpm needs {:.0f} Hz per track, above the {:.0f} Hz the input counts", *o.rpm, f, fmax));
        }
      }
      if (o.increments)
        p.line(fmt::format("INC step of {} increments", *o.increments), elg::inc_step_deg(*o.increments, ms), "deg");
    }
  }
  // The differential constants from the gear data (2.2.2, 2.2.3).
  if (o.helix || o.lead) {
    any = true;
    if (!o.module || !(*o.module > 0.0)) {
      ctx.exit_code = report_error(o.json, prefix, "--helix-angle/--lead-angle need --module (normal module, mm)", 2);
      return;
    }
    if (o.helix) {
      p.line("ud_z = sin(b0)/(mN pi) 360", elg::Decimal5::from_double(elg::ud_z_from_gear(*o.helix, *o.module)).value(),
             "deg/mm", "enter in R61 (AXIAL)");
    }
    if (o.lead) {
      p.line("ud_y = cos(g0)/(mN pi) 360", elg::Decimal5::from_double(elg::ud_y_from_gear(*o.lead, *o.module)).value(),
             "deg/mm", "enter in R60 (TANG)");
    }
  }
  // The gearing constants the ELG computes, with its validation.
  if (o.z0 || o.z2) {
    any = true;
    elg::GearInput in;
    in.z0 = o.z0.value_or(0);
    in.z2 = o.z2.value_or(0);
    const auto uz = elg::Decimal5::parse(o.ud_z);
    const auto uy = elg::Decimal5::parse(o.ud_y);
    if (!uz || !uy) {
      ctx.exit_code = report_error(o.json, prefix, !uz ? "--ud-z: " + uz.error() : "--ud-y: " + uy.error(), 2);
      return;
    }
    in.ud_z = *uz;
    in.ud_y = *uy;
    elg::GearMachineData md;
    md.n00 = o.n00;
    md.n02 = o.n02;
    md.ms_z_nm = o.ms_z_nm;
    md.ms_y_nm = o.ms_y_nm;
    const auto k = elg::compute_constants(in, md);
    if (!k) {
      p.problems.push_back(fmt::format("the ELG refuses the data: alarm {} {}", static_cast<int>(k.error()),
                                       elg::alarm_text(k.error())));
    } else {
      p.text("C counts per B count (Z0/Z2 N02/N00)", rational(k->c_per_b));
      p.text("C counts per Z count", rational(k->c_per_z));
      p.text("C counts per Y count", rational(k->c_per_y));
      p.text("one pitch in C counts (4 N02/Z2)", rational(k->pitch));
    }
  }
  if (!any) {
    ctx.exit_code = report_error(o.json, prefix,
                                 "give --pulses-per-rev, --resolution, --lines, --helix-angle/--lead-angle with "
                                 "--module, or --z0/--z2 (see --help)",
                                 2);
    return;
  }
  if (o.json) {
    print_json({{"device", "sinumerik-elg"}, {"ok", p.problems.empty()}, {"lines", p.lines}, {"problems", p.problems}});
  } else {
    for (const auto& problem : p.problems) fmt::print("problem: {}\n", problem);
  }
  ctx.exit_code = p.problems.empty() ? 0 : 1;
}

}  // namespace

void register_sinumerik(Context& ctx) {
  CLI::App* parent = calc_command(ctx);
  if (parent == nullptr) return;  // built without the profile module
  auto o = std::make_shared<ElgCalcOptions>();
  auto* calc = parent->add_subcommand(
      "sinumerik-elg",
      "SINUMERIK System 3 ELG: measuring-system and input units, the highest speed an encoder can be counted at,\n"
      "the encoder frequency of a speed, MD 396* for a resolution, ud_z/ud_y from the gear data, and the gearing\n"
      "constants (alarms 2200/2203). docs/elg.md");
  calc->add_option("--pulses-per-rev", o->pulses, "MD 396* of the axis: encoder pulses per revolution (before x4)");
  calc->add_option("--resolution", o->resolution, "Wanted resolution A in degrees: gives MD 396* = 360/(4 A)");
  calc->add_option("--lines", o->lines, "Encoder lines per revolution I (with --gear-ku): gives A = 360/(4 I ku)");
  calc->add_option("--gear-ku", o->gear_ku, "Gear ratio ku = n_encoder / n_axis (default 1)");
  calc->add_option("--fmax", o->fmax, "Input frequency limit per track in Hz (default 500000; 800000 planned)");
  calc->add_option("--rpm", o->rpm, "An axis speed in rpm: its encoder frequency");
  calc->add_option("--increments", o->increments, "INC: the step of this many increments");
  calc->add_option("--module", o->module, "Normal module m_N in mm (for --helix-angle / --lead-angle)");
  calc->add_option("--helix-angle", o->helix, "Helix angle beta0 of the workpiece teeth in degrees: gives ud_z");
  calc->add_option("--lead-angle", o->lead, "Lead angle gamma0 of the hob in degrees: gives ud_y");
  calc->add_option("--z0", o->z0, "R20: hob threads (negative: up milling)");
  calc->add_option("--z2", o->z2, "R21: workpiece teeth");
  calc->add_option("--ud-z", o->ud_z, "R61 AXIAL, deg/mm, at most 5 decimals (default 0)");
  calc->add_option("--ud-y", o->ud_y, "R60 TANG, deg/mm, at most 5 decimals (default 0)");
  calc->add_option("--n00", o->n00, "MD 396* of the guide axis B (default 180000)");
  calc->add_option("--n02", o->n02, "MD 396* of the drive axis C (default 180000)");
  calc->add_option("--ms-z-nm", o->ms_z_nm, "Measuring-system unit of Z in nm (MD 5002; default 500)");
  calc->add_option("--ms-y-nm", o->ms_y_nm, "Measuring-system unit of Y in nm (default 500)");
  calc->add_flag("--json", o->json, "Print the figures as one JSON object (docs/json.md)");
  calc->callback([&ctx, o] { run_elg_calc(ctx, *o); });
}

}  // namespace hil::cli
