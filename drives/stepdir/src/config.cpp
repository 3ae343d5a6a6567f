// SPDX-License-Identifier: MIT
#include "hil/drives/stepdir/config.hpp"

#include <charconv>

#include <fmt/format.h>

namespace hil::drives::stepdir {
namespace {

using hil::yaml::error_at;
using hil::yaml::Where;
using namespace hil::stepdir;

template <class T>
using Ex = std::expected<T, ConfigError>;

Ex<gpio::LineSpec> parse_line(const YAML::Node& node, const Where& w, std::string role, gpio::LineDirection dir) {
  gpio::LineSpec s;
  s.role = std::move(role);
  s.direction = dir;
  YAML::Node id = node;
  if (node.IsMap()) {
    if (auto r = hil::yaml::check_keys(node, w, {"line", "active_low", "bias"}); !r) return std::unexpected(r.error());
    id = node["line"];
    if (!id) return std::unexpected(error_at(node, w, "missing 'line': a chip offset (integer) or a line name"));
    auto al = hil::yaml::get_bool(node, w, "active_low");
    if (!al) return std::unexpected(al.error());
    s.active_low = al->value_or(false);
    auto bias = hil::yaml::get_string(node, w, "bias");
    if (!bias) return std::unexpected(bias.error());
    if (*bias) {
      auto b = gpio::parse_bias(**bias);
      if (!b) {
        return std::unexpected(
            error_at(node["bias"], w.key("bias"),
                     fmt::format("unknown bias '{}': use as-is, disabled, pull-up or pull-down", **bias)));
      }
      s.bias = *b;
    }
  }
  if (!id.IsScalar()) return std::unexpected(error_at(id, w, "expected a chip offset (integer) or a line name"));
  const std::string text = id.Scalar();
  unsigned v = 0;
  auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec == std::errc{} && p == text.data() + text.size()) {
    s.offset = v;
  } else if (!text.empty() && text[0] != '-') {
    s.name = text;
  } else {
    return std::unexpected(error_at(id, w, fmt::format("'{}' is neither an offset >= 0 nor a line name", text)));
  }
  return s;
}

ConfigError md_error(const YAML::Node& node, const Where& w, Ip247MdError e) {
  return error_at(node, w, fmt::format("IP247 MD error {}: {}", static_cast<int>(e), make_error_code(e).message()));
}

}  // namespace

Ex<StepDirConfig> parse_stepdir_config(const YAML::Node& drive, const Where& where) {
  if (auto r = hil::yaml::check_keys(drive, where, {"transport",      "chip",
                                                    "lines",          "profile",
                                                    "fmax_hz",        "fss_hz",
                                                    "accel_hz_per_s", "pulse_us",
                                                    "pulse_rounding", "step_space_ns",
                                                    "dir_setup_ns",   "dir_hold_ns",
                                                    "polarity",       "dir_forward_level",
                                                    "backlash",       "limit_switches",
                                                    "reset_pulse_ms", "ready_timeout_ms",
                                                    "homing",         "mock",
                                                    "writer"});
      !r) {
    return std::unexpected(r.error());
  }
  StepDirConfig c;
  auto num = [&](std::string_view key, double def) -> Ex<double> {
    auto v = hil::yaml::get_double(drive, where, key);
    if (!v) return std::unexpected(v.error());
    return v->value_or(def);
  };
  auto integer = [&](const YAML::Node& n, const Where& w, std::string_view key, long long def) -> Ex<long long> {
    auto v = hil::yaml::get_int(n, w, key);
    if (!v) return std::unexpected(v.error());
    return v->value_or(def);
  };
  auto str = [&](const YAML::Node& n, const Where& w, std::string_view key, std::string def) -> Ex<std::string> {
    auto v = hil::yaml::get_string(n, w, key);
    if (!v) return std::unexpected(v.error());
    return v->value_or(def);
  };

  auto chip = hil::yaml::get_string(drive, where, "chip");
  if (!chip) return std::unexpected(chip.error());
  c.chip = *chip;

  auto profile = str(drive, where, "profile", "motion");
  if (!profile) return std::unexpected(profile.error());
  if (*profile == "motion") {
    c.profile = PlannerMode::follow;
  } else if (*profile == "ip247") {
    c.profile = PlannerMode::ramp;
  } else {
    return std::unexpected(error_at(drive["profile"], where.key("profile"),
                                    fmt::format("unknown profile '{}': use motion (follow the motion core's "
                                                "jerk-limited command) or ip247 (exponential ramp to the command)",
                                                *profile)));
  }
  Ex<double> fmax = num("fmax_hz", 5'000), fss = num("fss_hz", 200), accel = num("accel_hz_per_s", 50'000);
  if (!fmax) return std::unexpected(fmax.error());
  if (!fss) return std::unexpected(fss.error());
  if (!accel) return std::unexpected(accel.error());
  c.ramp = {*fmax, *fss, *accel};

  auto pulse = integer(drive, where, "pulse_us", 2);
  if (!pulse) return std::unexpected(pulse.error());
  auto rounding = str(drive, where, "pulse_rounding", "up");
  if (!rounding) return std::unexpected(rounding.error());
  if (*rounding != "up" && *rounding != "down") {
    return std::unexpected(error_at(drive["pulse_rounding"], where.key("pulse_rounding"), "expected up or down"));
  }
  auto polarity = str(drive, where, "polarity", "positive");
  if (!polarity) return std::unexpected(polarity.error());
  if (*polarity != "positive" && *polarity != "negative") {
    return std::unexpected(md_error(drive["polarity"], where.key("polarity"), Ip247MdError::edge_polarity));
  }
  auto setup = integer(drive, where, "dir_setup_ns", 5'000), hold = integer(drive, where, "dir_hold_ns", 5'000);
  if (!setup) return std::unexpected(setup.error());
  if (!hold) return std::unexpected(hold.error());
  auto timing =
      make_ip247_timing(static_cast<int>(std::clamp<long long>(*pulse, -1, 1000)),
                        *rounding == "up" ? PulseRounding::up : PulseRounding::down, *fmax,
                        *polarity == "positive" ? Polarity::positive_edge : Polarity::negative_edge, *setup, *hold);
  if (!timing) {
    const char* key = timing.error() == Ip247MdError::max_frequency ? "fmax_hz" : "pulse_us";
    return std::unexpected(md_error(drive[key] ? drive[key] : drive, where.key(key), timing.error()));
  }
  c.timing = *timing;
  if (drive["step_space_ns"]) {
    auto sp = integer(drive, where, "step_space_ns", 0);
    if (!sp) return std::unexpected(sp.error());
    c.timing.step_space_ns = *sp;
    auto v = validate(c.timing);
    if (!v) return std::unexpected(md_error(drive["step_space_ns"], where.key("step_space_ns"), v.error()));
  }
  if (drive["dir_forward_level"]) {
    auto lv = integer(drive, where, "dir_forward_level", 1);
    if (!lv) return std::unexpected(lv.error());
    if (*lv != 0 && *lv != 1) {
      return std::unexpected(error_at(drive["dir_forward_level"], where.key("dir_forward_level"), "expected 0 or 1"));
    }
    c.timing.dir_forward_level = *lv == 1;
  }
  if (auto r = Ip247Ramp::make(c.ramp, c.timing.min_period_ns()); !r) {
    const char* key = r.error() == Ip247MdError::start_stop_frequency ? "fss_hz"
                      : r.error() == Ip247MdError::frequency_increase ? "accel_hz_per_s"
                                                                      : "fmax_hz";
    return std::unexpected(md_error(drive[key] ? drive[key] : drive, where.key(key), r.error()));
  }
  auto backlash = integer(drive, where, "backlash", 0);
  if (!backlash) return std::unexpected(backlash.error());
  if (*backlash < 0 || *backlash > 64'999) {
    return std::unexpected(md_error(drive["backlash"], where.key("backlash"), Ip247MdError::backlash));
  }
  c.backlash_steps = *backlash;
  auto ls = str(drive, where, "limit_switches", "normally_open");
  if (!ls) return std::unexpected(ls.error());
  if (*ls != "normally_open" && *ls != "normally_closed") {
    return std::unexpected(error_at(drive["limit_switches"], where.key("limit_switches"),
                                    "expected normally_open (IP247 'pos') or normally_closed ('neg')"));
  }
  c.limits_normally_closed = *ls == "normally_closed";
  auto rp = integer(drive, where, "reset_pulse_ms", 100), rt = integer(drive, where, "ready_timeout_ms", 1000);
  if (!rp) return std::unexpected(rp.error());
  if (!rt) return std::unexpected(rt.error());
  if (*rp < 0 || *rt <= 0)
    return std::unexpected(error_at(drive, where, "reset_pulse_ms must be >= 0 and ready_timeout_ms > 0"));
  c.reset_pulse = std::chrono::milliseconds(*rp);
  c.ready_timeout = std::chrono::milliseconds(*rt);

  if (const YAML::Node wr = drive["writer"]) {
    const Where ww = where.key("writer");
    if (auto r = hil::yaml::check_keys(wr, ww, {"spin_us", "late_us", "rt_priority"}); !r)
      return std::unexpected(r.error());
    auto spin = integer(wr, ww, "spin_us", 200), late = integer(wr, ww, "late_us", 50),
         prio = integer(wr, ww, "rt_priority", 0);
    if (!spin) return std::unexpected(spin.error());
    if (!late) return std::unexpected(late.error());
    if (!prio) return std::unexpected(prio.error());
    if (*spin < 0 || *spin > 100'000 || *late < 1 || *prio < 0 || *prio > 99) {
      return std::unexpected(error_at(wr, ww, "expected spin_us 0..100000, late_us >= 1, rt_priority 0..99"));
    }
    c.writer_spin = std::chrono::microseconds(*spin);
    c.writer_late = std::chrono::microseconds(*late);
    c.writer_rt_priority = static_cast<int>(*prio);
  }

  // Lines.
  const YAML::Node lines = drive["lines"];
  const Where lw = where.key("lines");
  if (lines) {
    if (!lines.IsMap()) return std::unexpected(error_at(lines, lw, "expected a map of role: offset or name"));
    if (auto r = hil::yaml::check_keys(lines, lw,
                                       {"step", "dir", "enable", "ready", "limit_start", "limit_end", "reference"});
        !r) {
      return std::unexpected(r.error());
    }
  } else if (c.chip) {
    return std::unexpected(error_at(drive, where, "'chip' needs 'lines' with at least step and dir"));
  }
  auto line = [&](const char* role, gpio::LineDirection d, unsigned mock_offset,
                  bool required) -> Ex<std::optional<gpio::LineSpec>> {
    if (!lines || !lines[role]) {
      if (required && c.chip) return std::unexpected(error_at(lines, lw, fmt::format("missing line '{}'", role)));
      if (c.chip) return std::optional<gpio::LineSpec>{};
      gpio::LineSpec s;  // mock: every line exists
      s.role = role;
      s.offset = mock_offset;
      s.direction = d;
      return std::optional<gpio::LineSpec>{s};
    }
    auto s = parse_line(lines[role], lw.key(role), role, d);
    if (!s) return std::unexpected(s.error());
    return std::optional<gpio::LineSpec>{*s};
  };
  using D = gpio::LineDirection;
  auto step = line("step", D::output, 0, true), dir = line("dir", D::output, 1, true),
       en = line("enable", D::output, 2, false);
  auto ready = line("ready", D::input, 3, false), l0 = line("limit_start", D::input, 4, false);
  auto l1 = line("limit_end", D::input, 5, false), ref = line("reference", D::input, 6, false);
  for (auto* r : {&step, &dir, &en, &ready, &l0, &l1, &ref}) {
    if (!*r) return std::unexpected(r->error());
  }
  c.step = **step;
  c.dir = **dir;
  c.enable = *en;
  c.ready = *ready;
  c.limit_start = *l0;
  c.limit_end = *l1;
  c.reference = *ref;
  c.step.initial = c.timing.step_idle_level();
  c.dir.initial = c.timing.dir_forward_level;
  if (c.enable) c.enable->initial = true;  // reset asserted until enabled (IP247 RS)

  // Homing.
  if (const YAML::Node h = drive["homing"]) {
    const Where hw = where.key("homing");
    if (auto r = hil::yaml::check_keys(
            h, hw, {"direction", "speed_hz", "coordinate", "sync", "patterns", "cam_watchdog_steps"});
        !r) {
      return std::unexpected(r.error());
    }
    auto d = str(h, hw, "direction", "backward");
    if (!d) return std::unexpected(d.error());
    if (*d != "forward" && *d != "backward") {
      return std::unexpected(md_error(h["direction"], hw.key("direction"), Ip247MdError::reference_direction));
    }
    c.homing.direction = *d == "forward" ? 1 : -1;
    auto sp = hil::yaml::get_double(h, hw, "speed_hz");
    if (!sp) return std::unexpected(sp.error());
    c.homing.speed_hz = sp->value_or(std::min(c.ramp.f_max_hz, c.ramp.f_ss_hz * 2));
    if (!(c.homing.speed_hz > c.ramp.f_ss_hz && c.homing.speed_hz <= c.ramp.f_max_hz)) {
      return std::unexpected(
          md_error(h["speed_hz"] ? h["speed_hz"] : h, hw.key("speed_hz"), Ip247MdError::reference_speed));
    }
    auto co = integer(h, hw, "coordinate", 0), pa = integer(h, hw, "patterns", 4),
         wd = integer(h, hw, "cam_watchdog_steps", 2500);
    if (!co) return std::unexpected(co.error());
    if (!pa) return std::unexpected(pa.error());
    if (!wd) return std::unexpected(wd.error());
    if (*pa < 4 || *pa > 40)
      return std::unexpected(md_error(h["patterns"], hw.key("patterns"), Ip247MdError::patterns));
    if (*wd < 1)
      return std::unexpected(error_at(h["cam_watchdog_steps"], hw.key("cam_watchdog_steps"), "expected >= 1"));
    auto sy = hil::yaml::get_bool(h, hw, "sync");
    if (!sy) return std::unexpected(sy.error());
    c.homing.coordinate = *co;
    c.homing.patterns = static_cast<int>(*pa);
    c.homing.cam_watchdog_steps = *wd;
    c.homing.sync = sy->value_or(false);
  } else {
    c.homing.speed_hz = std::min(c.ramp.f_max_hz, c.ramp.f_ss_hz * 2);
  }

  // Mock switches.
  if (const YAML::Node m = drive["mock"]) {
    const Where mw = where.key("mock");
    if (c.chip) return std::unexpected(error_at(m, mw, "'mock' is only for runs without 'chip'"));
    if (auto r = hil::yaml::check_keys(m, mw, {"limit_start_at", "limit_end_at", "cam", "initial_position", "ready"});
        !r) {
      return std::unexpected(r.error());
    }
    auto a = hil::yaml::get_int(m, mw, "limit_start_at"), b = hil::yaml::get_int(m, mw, "limit_end_at");
    auto ip = hil::yaml::get_int(m, mw, "initial_position");
    auto rd = hil::yaml::get_bool(m, mw, "ready");
    if (!a) return std::unexpected(a.error());
    if (!b) return std::unexpected(b.error());
    if (!ip) return std::unexpected(ip.error());
    if (!rd) return std::unexpected(rd.error());
    c.mock.limit_start_at = *a;
    c.mock.limit_end_at = *b;
    c.mock.initial_position = ip->value_or(0);
    c.mock.ready = rd->value_or(true);
    if (const YAML::Node cam = m["cam"]) {
      if (!cam.IsSequence() || cam.size() != 2) {
        return std::unexpected(error_at(cam, mw.key("cam"), "expected [from, to] in steps"));
      }
      try {
        auto lo = cam[0].as<long long>(), hi = cam[1].as<long long>();
        if (lo > hi) return std::unexpected(error_at(cam, mw.key("cam"), "from must be <= to"));
        c.mock.cam = std::pair<std::int64_t, std::int64_t>{lo, hi};
      } catch (const YAML::Exception&) {
        return std::unexpected(error_at(cam, mw.key("cam"), "expected two integers [from, to]"));
      }
    }
  }
  return c;
}

}  // namespace hil::drives::stepdir
