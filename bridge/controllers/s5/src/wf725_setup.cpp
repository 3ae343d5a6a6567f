// SPDX-License-Identifier: MIT
// `controller: {device: wf725-726, ...}`: the WF 725/726 controller from its MD list, options and
// program files (docs/wf725.md, "Scenarios").
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "hil/controllers/parameter_controller.hpp"
#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/controllers/s5/wf726_module_controller.hpp"

namespace hil::controllers::s5 {
namespace {

std::optional<double> number(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc{} || r.ptr != s.data() + s.size() || v < 0) return std::nullopt;
  return v;
}

}  // namespace

bool wf725_wants_module(const ControllerSpec& spec) noexcept {
  if (!spec.programs.empty()) return true;
  for (const char* key : {"db", "module", "reference_speeds", "jog_feed", "difference_cycles", "open_loop_speed",
                          "open_loop_acceleration", "axis_b", "axis_c", "db_b", "db_c", "split_monitoring", "drift"})
    if (spec.options.contains(key)) return true;
  return false;
}

namespace {

/// One axis from a single-axis `controller:` block.
std::expected<std::unique_ptr<Wf725Controller>, ConfigError> create_axis(const ControllerSpec& spec) {
  {
    const auto fail = [&](std::string key, std::string message) {
      return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller." + key, std::move(message)});
    };
    Wf725Options opt;
    profiles::Settings settings;
    for (const auto& [key, value] : spec.options) {
      if (key == "axis") {
        if (value.size() != 1 || value[0] < 'A' || value[0] > 'C') return fail(key, "axis: A, B or C");
        opt.axis = value[0];
      } else if (key == "module") {
        if (value != "WF725A" && value != "WF725B" && value != "WF726A" && value != "WF726B" && value != "WF726C")
          return fail(key, "module: WF725A, WF725B, WF726A, WF726B or WF726C");
        settings["module"] = value;
        opt.variant = value.back();
      } else if (key == "db") {
        const auto v = number(value);
        if (!v || *v < 1 || *v > 255 || *v != static_cast<int>(*v)) return fail(key, "db: a DB number 1..255");
        opt.db = static_cast<std::uint16_t>(*v);
      } else if (key == "reference_speeds") {
        std::stringstream ss(value);
        std::string item;
        int i = 0;
        while (std::getline(ss, item, ',')) {
          const auto v = number(item);
          if (!v || i >= 3) return fail(key, "reference_speeds: \"RAPID,REDUCED,SLOW\" in mm/min (data codes 8, 9, A)");
          opt.ref_speeds[i++] = std::llround(*v * 100.0);
        }
        if (i != 3) return fail(key, "reference_speeds: three speeds \"RAPID,REDUCED,SLOW\" in mm/min");
      } else if (key == "difference_cycles") {
        if (value != "4" && value != "5")
          return fail(key,
                      "difference_cycles: 4 or 5 (error 33 after that many jumps > MD 34 in a row; the manual "
                      "gives both)");
        opt.difference_cycles = value[0] - '0';
      } else if (key == "open_loop_speed" || key == "open_loop_acceleration") {
        const auto v = number(value);
        if (!v || *v <= 0)
          return fail(key, key == "open_loop_speed"
                               ? "open_loop_speed: the open-loop drive's speed at 10 V (level 100) in mm/min, > 0"
                               : "open_loop_acceleration: the open-loop drive's own acceleration in mm/s^2, > 0");
        (key == "open_loop_speed" ? opt.drive.speed_at_10v_mm_min : opt.drive.acceleration) = *v;
      } else if (key == "split_monitoring") {
        if (value != "bit" && value != "always")
          return fail(key, "split_monitoring: bit (the MD 29 comparison runs while D 2.3 of axis A is set) or always");
        opt.split_monitoring_always = value == "always";
      } else if (key == "drift") {
        // The drive's input offset on X3 in mV, signed (docs/wf725.md "Drift"): within the DAC's +-10 V.
        double v = 0;
        const auto r = std::from_chars(value.data(), value.data() + value.size(), v);
        if (r.ec != std::errc{} || r.ptr != value.data() + value.size() || !std::isfinite(v) || std::abs(v) > 10000.0)
          return fail(key,
                      fmt::format("drift: '{}' is not the drive's offset voltage in mV, -10000..10000 (the speed "
                                  "at zero command: drift / MD 23 x MD 3; open loop drift / 10 V x open_loop_speed)",
                                  value));
        opt.drift_mv = v;
      } else if (key == "jog_feed") {
        const auto v = number(value);
        if (!v) return fail(key, "jog_feed: the set-up speed in mm/min (data code 1C)");
        opt.jog_feed = std::llround(*v * 100.0);
      } else {
        return fail(key, fmt::format("unknown controller key '{}' (known: device, parameters, programs, cycle, axis, "
                                     "module, db, reference_speeds, jog_feed, difference_cycles, open_loop_speed, "
                                     "open_loop_acceleration, axis_b, axis_c, db_b, db_c, split_monitoring, drift)",
                                     key));
      }
    }
    auto loaded = load_parameter_file(spec.device, spec.parameters, settings);
    if (!loaded) return std::unexpected(loaded.error());
    auto mapped = wf725_axes(*loaded, spec);
    if (!mapped) return std::unexpected(mapped.error());
    auto axis = std::move(mapped->axes.front());
    // The pre-limit switches MD 11/13 and range limits MD 12/14 are the controller's own: armed
    // after synchronization, in the module's coordinates (docs/wf725.md).
    axis.config.soft_limit_min.reset();
    axis.config.soft_limit_max.reset();
    std::erase_if(axis.warnings, [](const std::string& w) { return w.starts_with("MD 12/14"); });
    const Duration cycle = spec.cycle ? *spec.cycle : mapped->cycle;
    auto md = wf725_machine_data(*loaded, settings);
    const std::string file = loaded->file.string();
    auto syntax = wf725_program_syntax(*loaded->profile);
    if (!syntax) return fail("device", syntax.error());
    auto c = std::make_unique<Wf725Controller>(std::move(*loaded), md, std::move(axis), cycle, opt);
    for (const auto& path : spec.programs) {
      std::ifstream in(path, std::ios::binary);
      if (!in) return fail("programs", fmt::format("cannot read the program file {}", path.string()));
      std::stringstream ss;
      ss << in.rdbuf();
      auto progs = parse_wf725_programs(ss.str(), *syntax);
      if (!progs) {
        const auto& e = progs.error();
        return std::unexpected(
            ConfigError{path.string(), e.line, 0, fmt::format("program {} N{}", e.program, e.block),
                        fmt::format("WF error {} ({}): {}", e.code,
                                    e.code < 200 ? "program input" : "memory administration", e.message)});
      }
      for (auto& p : *progs) {
        const int n = p.number;
        if (const int e = c->store_program(std::move(p)))
          return std::unexpected(ConfigError{path.string(), 0, 0, fmt::format("program {}", n),
                                             fmt::format("WF error {} (program input): the module's memory refuses "
                                                         "program {} (WF 725: 10 programs, 50 + 50 blocks; WF 726: "
                                                         "64 programs, 350 + 50 blocks)",
                                                         e, n)});
      }
    }
    (void)file;
    return c;
  }
}

}  // namespace

void register_wf725(ControllerRegistry& registry) {
  registry.add("wf725-726", [](const ControllerSpec& spec) -> std::expected<std::unique_ptr<Controller>, ConfigError> {
    // Several axes of one module (docs/wf725.md, "Several axes in a scenario").
    if (spec.options.contains("axis_b") || spec.options.contains("axis_c") || spec.options.contains("db_b") ||
        spec.options.contains("db_c"))
      return make_wf726_module_controller(spec, create_axis);
    auto c = create_axis(spec);
    if (!c) return std::unexpected(c.error());
    return std::unique_ptr<Controller>(std::move(*c));
  });
}

}  // namespace hil::controllers::s5
