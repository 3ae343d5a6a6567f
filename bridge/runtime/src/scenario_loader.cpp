// SPDX-License-Identifier: MIT
#include "hil/runtime/scenario_loader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "analog_stimulus_loader.hpp"
#include "controller_expectation_loader.hpp"
#include "coupling_loader.hpp"
#include "hil/config/yaml_field.hpp"
#include "hil/core/duration_text.hpp"
#include "hil/core/text_file.hpp"
#include "io_link_loader.hpp"
#include "plc_loader.hpp"

namespace hil::runtime {
namespace {

using yaml::Field;

constexpr int max_parallel_depth = 4;

bool valid_axis_name(const std::string& n) {
  if (n.empty() || n.size() > 32 || n == "all") return false;
  return std::all_of(n.begin(), n.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-'; });
}

class Loader {
 public:
  Loader(std::string file) : file_(std::move(file)) {}

  Scenario load(const YAML::Node& root) {
    Scenario s;
    s.file = file_;
    s.document = root;
    const Field top(root, yaml::Where{file_, ""}, YAML::Mark{});
    if (!root.IsMap())
      top.fail(fmt::format("a scenario is a map with 'machine:' and 'program:', got {}", top.describe()));
    top.expect_map({"name", "description", "period", "duration", "cut_off", "timeout", "realtime", "controller",
                    "machine", "io", "io_links", "program", "expect"});
    if (auto f = top.child("name"); f.present()) s.name = f.as_string("a scenario name");
    if (auto f = top.child("description"); f.present()) s.description = f.as_string("a text");
    if (auto f = top.child("period"); f.present()) {
      s.period = f.as_duration();
      if (s.period < std::chrono::microseconds(50) || s.period > std::chrono::seconds(1))
        f.fail(fmt::format("expected a cycle period between 50us and 1s, got {}", f.describe()));
    }
    if (auto d = top.optional_duration("duration")) {
      if (*d <= Duration::zero()) top.child("duration").fail("expected a duration > 0");
      s.duration = d;
    }
    if (auto d = top.optional_duration("timeout")) {
      if (*d <= Duration::zero()) top.child("timeout").fail("expected a duration > 0");
      s.timeout = *d;
    }
    if (s.duration && *s.duration > s.timeout) s.timeout = *s.duration;
    if (auto f = top.child("cut_off"); f.present()) {
      if (!s.duration) f.fail("'cut_off:' says whether a fixed 'duration:' may cut the program off: add 'duration:'");
      s.cut_off_expected = f.as_enum({"fail", "expected"}) == 1;
    }
    if (auto f = top.child("realtime"); f.present()) s.realtime = load_realtime(f);

    if (auto c = top.child("controller"); c.present()) s.controller = load_controller(c);
    has_controller_ = s.controller.has_value();
    const Field machine = top.required("machine", "the machine: a map with 'axes:'");
    machine.expect_map({"axes", "masters", "cams", "couplings"});
    const Field axes = machine.required("axes", "a list of axes");
    for (const Field& a : axes.items()) s.axes.push_back(load_axis(a, s));
    if (s.axes.empty()) axes.fail("a machine needs at least one axis");
    axes_ = &s.axes;
    detail::load_coupling_machine(machine, s);
    scenario_ = &s;

    if (auto io = top.child("io"); io.present()) {
      if (!s.controller) io.fail("'io:' drives a controller's inputs: add a 'controller:' block");
      for (const Field& f : io.items()) {
        if (f.node().IsMap() && f.child("analog").present())
          s.analog.push_back(detail::load_analog_stimulus(f));
        else
          s.io.push_back(load_stimulus(f));
      }
    }
    if (auto links = top.child("io_links"); links.present()) {
      if (!s.controller) links.fail("'io_links:' wire real I/O to a controller's image: add a 'controller:' block");
      for (const Field& f : links.items()) s.io_links.push_back(load_io_link(f));
    }
    if (auto p = top.child("program"); p.present())
      for (const Field& f : p.items()) s.program.push_back(load_step(f, 0));
    if (auto e = top.child("expect"); e.present()) {
      for (const Field& f : e.items()) {
        if (f.node().IsMap() && f.child("io").present()) {
          if (!s.controller) f.child("io").fail("an I/O expectation needs a 'controller:' block");
          s.io_expectations.push_back(load_io_expectation(f));
        } else if (f.node().IsMap() && (f.child("controller").present() || f.child("device_error").present())) {
          const std::string key = f.child("controller").present() ? "controller" : "device_error";
          if (!s.controller) f.child(key).fail("a controller expectation needs a 'controller:' block");
          s.controller_expectations.push_back(detail::load_controller_expectation(f));
        } else {
          load_expectation(f, s.expectations);
        }
      }
    }
    return s;
  }

 private:
  // `realtime: true` or a map {priority, cpu, lock_memory, dma_latency, fallback}.
  static RealtimeOptions load_realtime(const Field& f) {
    RealtimeOptions o;
    if (!f.node().IsMap()) {
      o.enabled = f.as_bool();
      return o;
    }
    f.expect_map({"enabled", "priority", "cpu", "lock_memory", "dma_latency", "fallback"});
    o.enabled = true;
    if (auto e = f.child("enabled"); e.present()) o.enabled = e.as_bool();
    if (auto p = f.child("priority"); p.present()) {
      const double v = p.as_number("a SCHED_FIFO priority 1..99");
      if (v < 1 || v > 99 || v != std::floor(v))
        p.fail(fmt::format("expected a SCHED_FIFO priority 1..99, got {}", p.describe()));
      o.priority = static_cast<int>(v);
    }
    if (auto c = f.child("cpu"); c.present()) {
      const double v = c.as_number("a CPU number");
      if (v < 0 || v > 1023 || v != std::floor(v))
        c.fail(fmt::format("expected a CPU number 0..1023, got {}", c.describe()));
      o.cpu = static_cast<int>(v);
    }
    if (auto b = f.child("lock_memory"); b.present()) o.lock_memory = b.as_bool();
    if (auto b = f.child("dma_latency"); b.present()) o.dma_latency = b.as_bool();
    if (auto b = f.child("fallback"); b.present()) o.fallback = b.as_bool();
    return o;
  }

  AxisSpec load_axis(const Field& f, const Scenario& s) {
    f.expect_map({"name", "units", "inc_per_unit", "rotary", "modulo", "limits", "soft_limits", "backlash",
                  "supervision", "fault_reaction", "drive"});
    AxisSpec a;
    a.source = {f.line(), f.path()};
    const Field name = f.required("name", "the axis name");
    a.name = name.as_string("an axis name");
    if (!valid_axis_name(a.name))
      name.fail(fmt::format("axis names use letters, digits, '_' and '-' (1..32 characters, not 'all'), got {}",
                            name.describe()));
    if (s.find_axis(a.name)) name.fail(fmt::format("axis '{}' is defined twice", a.name));
    if (has_controller_ && !f.child("inc_per_unit").present()) return load_controller_axis(f, std::move(a));
    if (auto r = f.child("rotary"); r.present()) a.rotary = r.as_bool();
    a.units = a.rotary ? "deg" : "mm";
    if (auto u = f.child("units"); u.present()) a.units = u.as_string("a unit name such as mm or deg");
    const Field ratio = f.required("inc_per_unit", "drive increments per unit: 1000, 4096/5 or 12.5");
    const auto r = parse_ratio(ratio.as_string("a ratio"));
    if (!r)
      ratio.fail(fmt::format("expected increments per unit as an integer, 'num/den' or a decimal (> 0), got {}",
                             ratio.describe()));
    a.inc_per_unit_num = r->first;
    a.inc_per_unit_den = r->second;
    if (auto m = f.child("modulo"); m.present()) {
      if (!a.rotary) m.fail("'modulo' needs 'rotary: true'");
      a.modulo = m.as_positive("units per turn");
    }

    const Field limits = f.required("limits", "a map with velocity, acceleration, ...");
    limits.expect_map({"velocity", "acceleration", "jerk", "quick_stop_deceleration", "jog_velocity"});
    a.max_velocity = limits.required("velocity", "units/s").as_positive("a velocity in units/s");
    a.max_acceleration = limits.required("acceleration", "units/s^2").as_positive("an acceleration in units/s^2");
    if (auto j = limits.child("jerk"); j.present())
      a.max_jerk = j.as_non_negative("a jerk in units/s^3 (0 = trapezoidal)");
    a.quick_stop_deceleration = limits.optional_positive("quick_stop_deceleration", "a deceleration in units/s^2")
                                    .value_or(4.0 * a.max_acceleration);
    if (a.quick_stop_deceleration < a.max_acceleration)
      limits.child("quick_stop_deceleration")
          .fail(fmt::format("expected at least limits.acceleration ({}), a quick stop brakes harder than a stop",
                            a.max_acceleration));
    a.jog_velocity =
        limits.optional_positive("jog_velocity", "a jog velocity in units/s").value_or(a.max_velocity / 10.0);
    if (a.jog_velocity > a.max_velocity)
      limits.child("jog_velocity").fail(fmt::format("expected at most limits.velocity ({})", a.max_velocity));

    if (auto sl = f.child("soft_limits"); sl.present()) {
      sl.expect_map({"min", "max"});
      if (a.rotary) sl.fail("soft limits apply to linear axes only");
      a.soft_limit_min = sl.optional_number("min", "a position in units");
      a.soft_limit_max = sl.optional_number("max", "a position in units");
      if (a.soft_limit_min && a.soft_limit_max && *a.soft_limit_min >= *a.soft_limit_max)
        sl.child("max").fail(fmt::format("expected max > min ({})", *a.soft_limit_min));
    }
    if (auto b = f.child("backlash"); b.present()) a.backlash = b.as_non_negative("a backlash in units");
    if (auto sv = f.child("supervision"); sv.present()) {
      sv.expect_map({"following_error", "standstill", "in_position", "in_position_timeout", "enable_timeout",
                     "feedback_timeout"});
      if (auto w = sv.child("following_error"); w.present()) {
        if (w.node().IsMap()) {
          w.expect_map({"kv", "min", "max"});
          a.following_error_dynamic = true;
          a.following_error_kv_per_s = w.required("kv", "position loop gain Kv in 1/s").as_positive("a gain in 1/s");
          a.following_error_min = w.required("min", "smallest window in units").as_positive("a window in units");
          a.following_error_max = w.required("max", "largest window in units").as_positive("a window in units");
          if (a.following_error_max < a.following_error_min)
            w.child("max").fail(fmt::format("expected max >= min ({})", a.following_error_min));
        } else {
          a.following_error_window = w.as_positive("a window in units, or a map {kv, min, max}");
        }
      }
      if (auto w = sv.child("standstill"); w.present()) a.standstill_window = w.as_positive("a window in units");
      if (auto w = sv.child("in_position"); w.present()) a.in_position_window = w.as_positive("a window in units");
      a.in_position_timeout = sv.optional_duration("in_position_timeout");
      a.enable_timeout = sv.optional_duration("enable_timeout");
      a.feedback_timeout = sv.optional_duration("feedback_timeout");
    }
    if (a.in_position_window <= 0.0) a.in_position_window = 0.01;
    if (a.standstill_window <= 0.0) a.standstill_window = std::max(2.0 * a.in_position_window, 1.0 / ratio_value(a));
    if (a.standstill_window < a.in_position_window)
      f.child("supervision")
          .child("standstill")
          .fail(fmt::format("expected a standstill window >= the in_position window ({})", a.in_position_window));
    if (!a.following_error_dynamic && a.following_error_window <= 0.0)
      a.following_error_window = std::max(10.0 * a.in_position_window, 1.0);
    if (auto r2 = f.child("fault_reaction"); r2.present())
      a.fault_reaction = static_cast<FaultReaction>(r2.as_enum({"quick_stop", "stop", "disable"}));

    const Field drive = f.required("drive", "a map with 'transport:' and the transport's keys");
    if (!drive.node().IsMap()) drive.fail(fmt::format("expected a map with 'transport:', got {}", drive.describe()));
    a.transport = drive.required("transport", "the transport name, e.g. sim, canopen, modbus, stepdir")
                      .as_string("a transport name");
    a.drive = drive.node();
    return a;
  }

  /// An axis of the controller: scaling, limits and supervision come from its parameter file.
  AxisSpec load_controller_axis(const Field& f, AxisSpec a) {
    for (const auto& k : f.expect_map({"name", "units", "inc_per_unit", "rotary", "modulo", "limits", "soft_limits",
                                       "backlash", "supervision", "fault_reaction", "drive"})) {
      if (k != "name" && k != "units" && k != "drive")
        f.child(k).fail(fmt::format(
            "'{}' comes from the controller's parameter file; a controller axis takes name, units and drive "
            "(give 'inc_per_unit' and 'limits' to define an axis outside the controller)",
            k));
    }
    a.from_controller = true;
    if (auto u = f.child("units"); u.present()) a.units = u.as_string("a unit name such as mm or deg");
    a.in_position_window = 0.01;
    const Field drive = f.required("drive", "a map with 'transport:' and the transport's keys");
    if (!drive.node().IsMap()) drive.fail(fmt::format("expected a map with 'transport:', got {}", drive.describe()));
    a.transport = drive.required("transport", "the transport name, e.g. sim, canopen, modbus, stepdir")
                      .as_string("a transport name");
    a.drive = drive.node();
    return a;
  }

  std::string resolve_path(const std::string& p) const {
    std::filesystem::path path(p);
    if (path.is_absolute() || file_.empty()) return path.string();
    return (std::filesystem::path(file_).parent_path() / path).lexically_normal().string();
  }

  ControllerBlock load_controller(const Field& f) {
    if (!f.node().IsMap()) f.fail(fmt::format("expected a map with 'device:' and 'parameters:', got {}", f.describe()));
    ControllerBlock c;
    c.source = {f.line(), f.path()};
    c.device = f.required("device", "the device profile name, e.g. wf725-726, ip247, clm14").as_string("a device");
    c.parameters =
        resolve_path(f.required("parameters", "the device's parameter file (its own format)").as_string("a file path"));
    if (f.child("program").present() && f.child("programs").present())
      f.child("program").fail("give the program files either as 'program: FILE' or as 'programs: [FILES]'");
    // `program: FILE` (one file) and `programs: [FILE, ...]` are the same key.
    if (auto p = f.child(f.child("program").present() ? "program" : "programs"); p.present()) {
      if (p.node().IsScalar()) {
        c.programs.push_back(resolve_path(p.as_string("a file path")));
      } else {
        for (const Field& i : p.items()) c.programs.push_back(resolve_path(i.as_string("a file path")));
      }
    }
    if (auto cy = f.optional_duration("cycle")) {
      if (*cy <= Duration::zero()) f.child("cycle").fail("expected a controller cycle > 0");
      c.cycle = cy;
    }
    for (const auto& kv : f.node()) {
      const std::string key = kv.first.Scalar();
      if (key == "device" || key == "parameters" || key == "program" || key == "programs" || key == "cycle") continue;
      const Field v = f.child(key);
      if (!v.node().IsScalar()) v.fail(fmt::format("controller option '{}' takes a single value", key));
      c.options[key] = v.node().Scalar();
    }
    return c;
  }

  std::string signal_name(const Field& f) const {
    const std::string s = f.as_string("an I/O name or the device's address, e.g. I0.00.3 or 'E 4.1'");
    if (s.empty()) f.fail("expected an I/O name or address");
    return s;
  }

  // `io_links:` entry: one device kind (gpio | modbus | drive) with `inputs:` / `outputs:` maps
  // from signal to the device's address of the bit.
  IoLink load_io_link(const Field& f) {
    const auto keys = f.expect_map({"gpio", "modbus", "drive", "inputs", "outputs"});
    IoLink link;
    link.source = {f.line(), f.path()};
    std::string kind;
    for (const auto& k : keys) {
      if (k == "inputs" || k == "outputs") continue;
      if (!kind.empty()) f.child(k).fail(fmt::format("one device per io_links entry; got '{}' and '{}'", kind, k));
      kind = k;
    }
    if (kind.empty()) f.fail("an io_links entry needs one of: gpio, modbus, drive");
    if (!f.child("inputs").present() && !f.child("outputs").present())
      f.fail(fmt::format("the {} link wires nothing: give 'inputs:' and/or 'outputs:'", kind));
    const auto bits = [&](const std::string& key, bool input, auto load_bit) {
      std::vector<IoLinkBit> out;
      const Field m = f.child(key);
      if (!m.present()) return out;
      if (!m.node().IsMap()) m.fail(fmt::format("expected a map of signal: {} address, got {}", kind, m.describe()));
      for (const auto& kv : m.node()) {
        if (!kv.first.IsScalar()) m.fail("a signal name must be a plain name or device address");
        const Field bit = m.child(kv.first.Scalar());
        IoLinkBit b;
        b.signal = kv.first.Scalar();
        if (b.signal.empty()) bit.fail("expected an I/O name or address");
        b.source = {bit.line(), bit.path()};
        b.where = load_bit(bit, input);
        out.push_back(std::move(b));
      }
      return out;
    };
    if (kind == "drive") {
      const Field d = f.child("drive");
      link.device = DriveLinkDevice{d.as_string("the name of a machine axis (its drive's digital I/O)")};
      const auto load = [&](const Field& bit, bool) { return load_drive_bit(bit); };
      link.inputs = bits("inputs", true, load);
      link.outputs = bits("outputs", false, load);
    } else if (kind == "gpio") {
      const Field g = f.child("gpio");
      g.expect_map({"chip", "consumer"});
      GpioLinkDevice d;
      d.chip = g.required("chip", "a GPIO chip (gpiochip1, /dev/gpiochip1, a label) or 'mock'").as_string("a chip");
      if (d.chip.empty()) g.child("chip").fail("expected a GPIO chip name, path, label or 'mock'");
      if (auto c = g.child("consumer"); c.present()) d.consumer = c.as_string("a consumer label");
      const bool mock = d.chip == "mock";
      link.device = std::move(d);
      const auto load = [&](const Field& bit, bool input) { return load_gpio_bit(bit, input, mock); };
      link.inputs = bits("inputs", true, load);
      link.outputs = bits("outputs", false, load);
    } else if (kind == "modbus") {
      link.device = detail::load_modbus_device(f.child("modbus"));
      const auto load = [&](const Field& bit, bool input) { return detail::load_modbus_bit(bit, input); };
      link.inputs = bits("inputs", true, load);
      link.outputs = bits("outputs", false, load);
    }
    return link;
  }

  // A drive's digital I/O bit: `{bit: 2}` or `2`, 0..31 (CiA 402 0x60FD / 0x60FE:1 layout).
  DriveLinkBit load_drive_bit(const Field& f) {
    if (f.node().IsMap()) (void)f.expect_map({"bit"});
    const Field b = f.node().IsMap() ? f.required("bit", "the drive's bit 0..31") : f;
    const double v = b.as_number("a drive bit 0..31");
    if (v < 0 || v > 31 || v != static_cast<double>(static_cast<unsigned>(v)))
      b.fail(
          fmt::format("expected a drive bit 0..31 (CiA 402 0x60FD inputs / 0x60FE:1 outputs), got {}", b.describe()));
    return DriveLinkBit{static_cast<unsigned>(v)};
  }

  // A GPIO line: `3` (offset), `LIMIT_X` (name) or {line, active_low, bias, mock}.
  GpioLinkBit load_gpio_bit(const Field& f, bool input, bool mock_chip) {
    GpioLinkBit b;
    const auto line = [&](const Field& l) {
      const YAML::Node& n = l.node();
      if (!n.IsScalar()) l.fail(fmt::format("expected a line offset or name, got {}", l.describe()));
      const std::string& text = n.Scalar();
      if (!text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        const double v = l.as_number("a line offset");
        if (v > 1023) l.fail(fmt::format("expected a line offset 0..1023, got {}", l.describe()));
        b.offset = static_cast<unsigned>(v);
      } else {
        if (mock_chip) l.fail(fmt::format("mock lines have offsets, not names: got {}", l.describe()));
        b.name = l.as_string("a line name");
        if (b.name.empty()) l.fail("expected a line offset or name");
      }
    };
    if (!f.node().IsMap()) {
      line(f);
      return b;
    }
    f.expect_map({"line", "active_low", "bias", "mock"});
    line(f.required("line", "the line offset or name"));
    if (auto a = f.child("active_low"); a.present()) b.active_low = a.as_bool();
    if (auto bias = f.child("bias"); bias.present()) {
      if (!input) bias.fail("'bias' applies to input lines");
      (void)bias.as_enum({"as-is", "disabled", "pull-up", "pull-down"});  // the names gpio::parse_bias reads
      b.bias = bias.as_string("a bias");
    }
    if (auto m = f.child("mock"); m.present()) {
      if (!input || !mock_chip) m.fail("'mock' scripts an input line of 'chip: mock'");
      Duration last{-1};
      for (const Field& e : m.items()) {
        e.expect_map({"at", "level"});
        const Duration at = e.required("at", "when the level changes").as_duration();
        if (at <= last) e.child("at").fail("mock levels must be given in increasing time");
        last = at;
        b.mock.emplace_back(at, e.required("level", "the line level, true or false").as_bool());
      }
    }
    return b;
  }

  IoStimulus load_stimulus(const Field& f) {
    const auto keys = f.expect_map({"set", "pulse", "cam", "mark", "value", "at", "when", "width", "axis", "from", "to",
                                    "active_low", "position", "accuracy"});
    IoStimulus st;
    st.source = {f.line(), f.path()};
    std::string kind;
    for (const auto& k : keys) {
      if (k != "set" && k != "pulse" && k != "cam" && k != "mark") continue;
      if (!kind.empty()) f.child(k).fail(fmt::format("one stimulus per entry; got '{}' and '{}'", kind, k));
      kind = k;
    }
    if (kind.empty()) f.fail("an io entry needs one of: set, pulse, cam, mark, analog");
    st.signal = signal_name(f.child(kind));
    auto allow = [&](std::initializer_list<std::string_view> allowed) {
      for (const auto& k : keys) {
        if (k == kind || std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
        f.child(k).fail(fmt::format("'{}' does not apply to '{}'", k, kind));
      }
    };
    if (kind == "set" || kind == "pulse") {
      allow({"value", "at", "when", "width"});
      st.kind = kind == "set" ? IoStimulus::Kind::set : IoStimulus::Kind::pulse;
      if (auto v = f.child("value"); v.present()) st.value = v.as_bool();
      st.at = f.optional_duration("at");
      if (auto w = f.child("when"); w.present()) st.when = load_condition(w);
      if (st.at.has_value() == st.when.has_value())
        f.fail(fmt::format("'{}' needs either 'at: <time>' or 'when: <condition>'", kind));
      if (auto w = f.optional_duration("width")) {
        if (kind == "set") f.child("width").fail("'width' applies to 'pulse' only");
        st.width = *w;
      }
    } else if (kind == "cam") {
      allow({"axis", "from", "to", "active_low"});
      st.kind = IoStimulus::Kind::cam;
      st.axis = axis_name(f.required("axis", "the axis whose position switches the input"));
      st.from = f.optional_number("from", "a position in units");
      st.to = f.optional_number("to", "a position in units");
      if (!st.from && !st.to) f.fail("a cam needs 'from:', 'to:' or both (the active position range)");
      if (st.from && st.to && *st.from > *st.to) f.child("to").fail(fmt::format("expected to >= from ({})", *st.from));
      if (auto v = f.child("active_low"); v.present()) st.active_low = v.as_bool();
    } else {
      allow({"axis", "position", "accuracy", "width"});
      st.kind = IoStimulus::Kind::mark;
      st.axis = axis_name(f.required("axis", "the axis carrying the marks"));
      st.position = f.required("position", "the mark's position in units").as_number("a position in units");
      if (auto a = f.child("accuracy"); a.present()) st.accuracy = a.as_non_negative("an accuracy in units");
      if (auto w = f.optional_duration("width")) st.width = *w;
    }
    return st;
  }

  IoExpectation load_io_expectation(const Field& f) {
    const auto keys = f.expect_map({"io", "state", "at", "edges", "edge", "first_edge", "after", "by"});
    IoExpectation e;
    e.source = {f.line(), f.path()};
    e.signal = signal_name(f.child("io"));
    std::string kind;
    for (const auto& k : keys) {
      if (k != "state" && k != "edges" && k != "first_edge") continue;
      if (!kind.empty()) f.child(k).fail(fmt::format("one I/O expectation per entry; got '{}' and '{}'", kind, k));
      kind = k;
    }
    if (kind.empty()) f.fail("an I/O expectation needs one of: state, edges, first_edge");
    auto allow = [&](std::initializer_list<std::string_view> allowed) {
      for (const auto& k : keys) {
        if (k == "io" || k == kind || std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
        f.child(k).fail(fmt::format("'{}' does not apply to an I/O '{}' expectation", k, kind));
      }
    };
    auto edge = [&] {
      if (auto x = f.child("edge"); x.present())
        e.edge = static_cast<IoExpectation::Edge>(x.as_enum({"rising", "falling", "any"}));
    };
    const Field x = f.child(kind);
    if (kind == "state") {
      allow({"at"});
      e.kind = IoExpectation::Kind::state;
      e.state = x.as_bool();
      e.at = f.optional_duration("at");
    } else if (kind == "edges") {
      allow({"edge"});
      e.kind = IoExpectation::Kind::edges;
      const double n = x.as_non_negative("a number of edges");
      if (n != std::floor(n) || n > 1e12) x.fail(fmt::format("expected a whole number of edges, got {}", x.describe()));
      e.count = static_cast<std::uint64_t>(n);
      edge();
    } else {
      allow({"edge", "after", "by"});
      e.kind = IoExpectation::Kind::first_edge;
      if (!x.as_bool()) x.fail("'first_edge' takes 'true' with 'after:' and/or 'by:'");
      e.after = f.optional_duration("after");
      e.by = f.optional_duration("by");
      if (!e.after && !e.by) f.fail("'first_edge' needs 'after:', 'by:' or both");
      if (e.after && e.by && *e.after > *e.by) f.child("by").fail("expected by >= after");
      edge();
    }
    return e;
  }

  static double ratio_value(const AxisSpec& a) {
    return static_cast<double>(a.inc_per_unit_num) / static_cast<double>(a.inc_per_unit_den);
  }

  std::string axis_name(const Field& f) const {
    const std::string n = f.as_string("an axis name");
    for (const auto& a : *axes_)
      if (a.name == n) return n;
    std::string list;
    for (const auto& a : *axes_) list += (list.empty() ? "" : ", ") + a.name;
    f.fail(fmt::format("unknown axis '{}'; the machine has: {}", n, list));
  }

  /// A name, a list of names, or "all".
  std::vector<std::string> axis_list(const Field& f) const {
    std::vector<std::string> out;
    if (f.node().IsScalar() && f.node().Scalar() == "all") {
      for (const auto& a : *axes_) out.push_back(a.name);
      return out;
    }
    if (f.node().IsSequence()) {
      for (const Field& i : f.items()) out.push_back(axis_name(i));
      if (out.empty()) f.fail("expected at least one axis name");
      return out;
    }
    if (!f.node().IsScalar())
      f.fail(fmt::format("expected an axis name, a list of names or 'all', got {}", f.describe()));
    out.push_back(axis_name(f));
    return out;
  }

  MoveLimits move_limits(const Field& f, bool with_velocity = true) const {
    MoveLimits l;
    if (with_velocity) l.velocity = f.optional_positive("velocity", "a velocity in units/s");
    l.acceleration = f.optional_positive("acceleration", "an acceleration in units/s^2");
    if (auto j = f.child("jerk"); j.present()) l.jerk = j.as_non_negative("a jerk in units/s^3 (0 = trapezoidal)");
    return l;
  }

  static constexpr std::string_view step_keys[] = {
      "enable",        "disable",      "reset",    "home",       "move_absolute", "move_relative",
      "move_velocity", "jog",          "stop",     "quick_stop", "wait",          "wait_in_position",
      "wait_until",    "inject_fault", "parallel", "couple",     "acknowledge",   "plc"};

  Step load_step(const Field& f, int depth) {
    if (!f.node().IsMap())
      f.fail(fmt::format("expected a step: a map with one action ({}), got {}", "enable, move_absolute, wait, ...",
                         f.describe()));
    const auto keys = f.expect_map({"enable",        "disable",          "reset",      "home",         "move_absolute",
                                    "move_relative", "move_velocity",    "jog",        "stop",         "quick_stop",
                                    "wait",          "wait_in_position", "wait_until", "inject_fault", "parallel",
                                    "couple",        "acknowledge",      "plc",        "at",           "timeout",
                                    "blocking"});
    std::string action;
    for (const auto& k : keys) {
      if (k == "at" || k == "timeout" || k == "blocking") continue;
      if (!action.empty())
        f.child(k).fail(
            fmt::format("a step has exactly one action; this one has '{}' and '{}' (use 'parallel:' to "
                        "start several at once)",
                        action, k));
      action = k;
    }
    if (action.empty()) {
      std::string list;
      for (auto k : step_keys) list += (list.empty() ? "" : ", ") + std::string(k);
      f.fail(fmt::format("a step needs one action: {}", list));
    }
    Step st;
    st.source = {f.line(), f.path()};
    st.at = f.optional_duration("at");
    st.timeout = f.optional_duration("timeout");
    if (auto w = f.child("blocking"); w.present()) st.wait = w.as_bool();
    const Field v = f.child(action);
    st.name = action;
    if (action == "enable")
      st.action = EnableStep{axis_list(v)};
    else if (action == "disable")
      st.action = DisableStep{axis_list(v)};
    else if (action == "reset")
      st.action = ResetStep{axis_list(v)};
    else if (action == "home")
      st.action = HomeStep{axis_list(v)};
    else if (action == "quick_stop")
      st.action = QuickStopStep{axis_list(v)};
    else if (action == "wait_in_position")
      st.action = WaitInPositionStep{axis_list(v)};
    else if (action == "stop") {
      st.action = StopStep{axis_list(v)};
    } else if (action == "wait") {
      st.action = WaitStep{v.as_duration()};
    } else if (action == "move_absolute") {
      v.expect_map({"axis", "position", "velocity", "acceleration", "jerk", "direction"});
      MoveAbsoluteStep m;
      m.axis = axis_name(v.required("axis", "the axis to move"));
      m.position = v.required("position", "the target in units").as_number("a position in units");
      m.limits = move_limits(v);
      if (auto d = v.child("direction"); d.present()) {
        const AxisSpec* spec = find(m.axis);
        if (!spec->rotary) d.fail("'direction' applies to rotary axes only");
        m.direction = static_cast<MoveDirection>(d.as_enum({"shortest", "positive", "negative"}));
      }
      st.name += " " + m.axis;
      st.action = m;
    } else if (action == "move_relative") {
      v.expect_map({"axis", "distance", "velocity", "acceleration", "jerk"});
      MoveRelativeStep m;
      m.axis = axis_name(v.required("axis", "the axis to move"));
      m.distance = v.required("distance", "the distance in units").as_number("a distance in units");
      m.limits = move_limits(v);
      st.name += " " + m.axis;
      st.action = m;
    } else if (action == "move_velocity") {
      v.expect_map({"axis", "velocity", "acceleration", "jerk"});
      MoveVelocityStep m;
      m.axis = axis_name(v.required("axis", "the axis to move"));
      m.velocity = v.required("velocity", "a signed velocity in units/s").as_number("a velocity in units/s");
      m.limits = move_limits(v, false);
      st.name += " " + m.axis;
      st.action = m;
    } else if (action == "jog") {
      v.expect_map({"axis", "direction", "duration"});
      JogStep j;
      j.axis = axis_name(v.required("axis", "the axis to jog"));
      j.positive = v.required("direction", "positive or negative").as_enum({"positive", "negative"}) == 0;
      j.duration = v.required("duration", "how long to jog").as_duration();
      st.name += " " + j.axis;
      st.action = j;
    } else if (action == "wait_until") {
      st.action = WaitUntilStep{load_condition(v)};
    } else if (action == "inject_fault") {
      v.expect_map({"axis", "fault", "active"});
      InjectFaultStep i;
      i.axis = axis_name(v.required("axis", "the axis whose drive gets the fault"));
      i.fault = v.required("fault", "a fault name the drive accepts (sim: encoder, not_ready, following_blowup)")
                    .as_string("a fault name");
      if (auto a = v.child("active"); a.present()) i.active = a.as_bool();
      st.name += " " + i.axis + " " + i.fault;
      st.action = i;
    } else if (action == "acknowledge") {
      if (!has_controller_) v.fail("'acknowledge' clears a controller's device errors: add a 'controller:' block");
      AcknowledgeStep a;
      a.how = static_cast<AcknowledgeStep::How>(v.as_enum({"acknowledge", "reset", "power_cycle"}));
      st.name += std::string(" ") + std::array{"acknowledge", "reset", "power_cycle"}[static_cast<std::size_t>(a.how)];
      st.action = a;
    } else if (action == "plc") {
      if (!has_controller_) v.fail("'plc' reads and writes a controller's data blocks: add a 'controller:' block");
      st.action = detail::load_plc_step(v, st.name);
    } else if (action == "couple") {
      CoupleStep c = detail::load_couple_step(v, *scenario_);
      st.name += " " + c.slave;
      st.action = std::move(c);
    } else if (action == "parallel") {
      if (depth >= max_parallel_depth)
        v.fail(fmt::format("'parallel' nested deeper than {} levels", max_parallel_depth));
      ParallelStep p;
      for (const Field& i : v.items()) p.steps.push_back(load_step(i, depth + 1));
      if (p.steps.empty()) v.fail("expected at least one step in 'parallel'");
      st.action = std::move(p);
    }
    return st;
  }

  Condition load_condition(const Field& v) {
    const auto keys =
        v.expect_map({"axis", "position_above", "position_below", "velocity_above", "velocity_below",
                      "following_error_above", "following_error_below", "state", "fault", "standstill", "in_position"});
    Condition c;
    c.axis = axis_name(v.required("axis", "the axis to watch"));
    std::string kind;
    for (const auto& k : keys) {
      if (k == "axis") continue;
      if (!kind.empty()) v.child(k).fail(fmt::format("one condition per wait_until; got '{}' and '{}'", kind, k));
      kind = k;
    }
    if (kind.empty())
      v.fail(
          "a condition needs one of: position_above, position_below, velocity_above, velocity_below, "
          "following_error_above, following_error_below, state, fault, standstill, in_position");
    const Field x = v.child(kind);
    auto compare = [&](Quantity q, Comparison cmp) {
      c.kind = Condition::Kind::compare;
      c.quantity = q;
      c.comparison = cmp;
      c.value = x.as_number("a number in units (or units/s)");
    };
    if (kind == "position_above")
      compare(Quantity::position, Comparison::above);
    else if (kind == "position_below")
      compare(Quantity::position, Comparison::below);
    else if (kind == "velocity_above")
      compare(Quantity::velocity, Comparison::above);
    else if (kind == "velocity_below")
      compare(Quantity::velocity, Comparison::below);
    else if (kind == "following_error_above")
      compare(Quantity::following_error, Comparison::above);
    else if (kind == "following_error_below")
      compare(Quantity::following_error, Comparison::below);
    else if (kind == "state") {
      c.kind = Condition::Kind::state;
      c.state = state_name(x);
    } else if (kind == "fault") {
      c.kind = Condition::Kind::fault;
      c.fault_code = fault_code_or_any(x);
    } else if (kind == "standstill" || kind == "in_position") {
      if (!x.as_bool()) x.fail(fmt::format("'{}' takes 'true' only", kind));
      c.kind = kind == "standstill" ? Condition::Kind::no_motion : Condition::Kind::in_position;
    }
    return c;
  }

  static std::string state_name(const Field& x) {
    constexpr std::string_view names[] = {"disabled", "enabling", "standstill", "moving",
                                          "stopping", "homing",   "error"};
    const std::string n = x.as_string("an axis state name");
    for (auto k : names)
      if (k == n) return n;
    x.fail(
        fmt::format("expected an axis state: disabled, enabling, standstill, moving, stopping, homing, error; got {}",
                    x.describe()));
  }

  static std::string fault_code_or_any(const Field& x) {
    if (!x.node().IsScalar())
      x.fail(fmt::format("expected a fault code such as motion:1 or cia402:0x7305, or 'any'; got {}", x.describe()));
    const std::string s = x.node().Scalar();
    if (s == "any" || s == "true") return "";
    if (!parse_fault_code(s))
      x.fail(fmt::format("expected a fault code 'category:number' such as motion:1 or cia402:0x7305, or 'any'; got {}",
                         x.describe()));
    return s;
  }

  void load_expectation(const Field& f, std::vector<Expectation>& out) {
    const auto keys = f.expect_map(
        {"axis", "position", "tolerance", "at", "by", "fault", "state", "no_fault", "max_following_error", "moves"});
    const auto axes = axis_list(f.required("axis", "an axis name, a list or 'all'"));
    std::string kind;
    for (const auto& k : keys) {
      if (k == "axis" || k == "tolerance" || k == "at" || k == "by") continue;
      if (!kind.empty()) f.child(k).fail(fmt::format("one expectation per entry; got '{}' and '{}'", kind, k));
      kind = k;
    }
    if (kind.empty())
      f.fail(
          "an expectation needs one of: position, fault, state, no_fault, max_following_error, moves (or io:, "
          "controller:, device_error: with a controller)");
    auto only = [&](std::initializer_list<std::string_view> allowed) {
      for (std::string_view k : {"tolerance", "at", "by"}) {
        if (std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
        if (f.child(std::string(k)).present())
          f.child(std::string(k)).fail(fmt::format("'{}' does not apply to a '{}' expectation", k, kind));
      }
    };
    const Field x = f.child(kind);
    ExpectationKind e;
    if (kind == "position") {
      only({"tolerance", "at", "by"});
      PositionExpectation p;
      p.value = x.as_number("a position in units");
      p.at = f.optional_duration("at");
      p.by = f.optional_duration("by");
      if (p.at && p.by) f.child("by").fail("use either 'at' (checked at that instant) or 'by' (reached no later than)");
      if (auto t = f.child("tolerance"); t.present()) p.tolerance = t.as_positive("a tolerance in units");
      // else: each axis' own in-position window (set per axis below)
      e = p;
    } else if (kind == "fault") {
      only({"by"});
      e = FaultExpectation{fault_code_or_any(x), f.optional_duration("by")};
    } else if (kind == "state") {
      only({"at"});
      e = StateExpectation{state_name(x), f.optional_duration("at")};
    } else if (kind == "no_fault") {
      only({});
      if (!x.as_bool()) x.fail("'no_fault' takes 'true' only (use 'fault:' to expect a fault)");
      e = NoFaultExpectation{};
    } else if (kind == "moves") {
      only({});
      const double n = x.as_non_negative("a number of moves");
      if (n != std::floor(n) || n > 1e12) x.fail(fmt::format("expected a whole number of moves, got {}", x.describe()));
      e = MovesExpectation{static_cast<std::uint64_t>(n)};
    } else {
      only({});
      e = MaxFollowingErrorExpectation{x.as_positive("a following error in units")};
    }
    for (const auto& a : axes) {
      Expectation one{a, e, SourceRef{f.line(), f.path()}};
      if (auto* p = std::get_if<PositionExpectation>(&one.kind); p && p->tolerance <= 0.0)
        p->tolerance = find(a)->in_position_window;  // the loader defaults it to > 0
      out.push_back(std::move(one));
    }
  }

  const AxisSpec* find(const std::string& name) const {
    for (const auto& a : *axes_)
      if (a.name == name) return &a;
    return nullptr;
  }

  std::string file_;
  const std::vector<AxisSpec>* axes_ = nullptr;
  const Scenario* scenario_ = nullptr;  ///< for the coupling keys of program steps
  bool has_controller_ = false;
};

}  // namespace

const AxisSpec* Scenario::find_axis(const std::string& n) const noexcept {
  for (const auto& a : axes)
    if (a.name == n) return &a;
  return nullptr;
}

std::string_view to_string(FaultReaction r) noexcept {
  switch (r) {
    case FaultReaction::quick_stop:
      return "quick_stop";
    case FaultReaction::stop:
      return "stop";
    case FaultReaction::disable:
      return "disable";
  }
  return "?";
}

std::string_view to_string(MoveDirection d) noexcept {
  switch (d) {
    case MoveDirection::positive:
      return "positive";
    case MoveDirection::negative:
      return "negative";
    case MoveDirection::shortest:
      return "shortest";
  }
  return "?";
}

std::optional<std::pair<std::int64_t, std::int64_t>> parse_ratio(std::string_view text) {
  constexpr std::int64_t limit = std::int64_t{1} << 40;
  auto integer = [](std::string_view t) -> std::optional<std::int64_t> {
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc{} || end != t.data() + t.size() || v <= 0 || v > limit) return std::nullopt;
    return v;
  };
  if (const auto slash = text.find('/'); slash != std::string_view::npos) {
    auto n = integer(text.substr(0, slash));
    auto d = integer(text.substr(slash + 1));
    if (!n || !d) return std::nullopt;
    return std::pair{*n, *d};
  }
  if (const auto dot = text.find('.'); dot != std::string_view::npos) {
    const std::string_view frac = text.substr(dot + 1);
    if (frac.empty() || frac.size() > 9) return std::nullopt;
    std::int64_t den = 1;
    for (std::size_t i = 0; i < frac.size(); ++i) den *= 10;
    std::string digits(text.substr(0, dot));
    digits += frac;
    while (digits.size() > 1 && digits.front() == '0') digits.erase(digits.begin());
    auto n = integer(digits);
    if (!n) return std::nullopt;
    return std::pair{*n, den};
  }
  auto n = integer(text);
  if (!n) return std::nullopt;
  return std::pair{*n, std::int64_t{1}};
}

std::optional<Duration> parse_duration(std::string_view text) {
  return parse_duration_text(text, "s");  // the one grammar of scenario files and the CLI
}

std::optional<FaultCode> parse_fault_code(std::string_view text) {
  const auto colon = text.find(':');
  if (colon == std::string_view::npos || colon == 0) return std::nullopt;
  FaultCode c;
  c.category = std::string(text.substr(0, colon));
  for (char ch : c.category)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.')) return std::nullopt;
  std::string_view num = text.substr(colon + 1);
  c.text = std::string(num);
  // A device catalogue ("wf725-726.traversing", "clm14.diagnostic") writes its codes as its
  // manual does ("96", "4C"): they are matched as text against the catalogue's code.
  const bool device = c.category.find('.') != std::string::npos;
  if (device && !num.empty() && num.size() <= 8 &&
      std::all_of(num.begin(), num.end(), [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) != 0; })) {
    c.value = -1;
    return c;
  }
  int base = 10;
  if (num.starts_with("0x") || num.starts_with("0X")) {
    base = 16;
    num.remove_prefix(2);
  }
  if (num.empty()) return std::nullopt;
  const auto [end, ec] = std::from_chars(num.data(), num.data() + num.size(), c.value, base);
  if (ec != std::errc{} || end != num.data() + num.size()) return std::nullopt;
  return c;
}

std::expected<Scenario, ConfigError> parse_scenario(std::string_view text, const std::string& file_name) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    return std::unexpected(ConfigError{file_name, e.mark.line >= 0 ? e.mark.line + 1 : 0,
                                       e.mark.column >= 0 ? e.mark.column + 1 : 0, "",
                                       fmt::format("not valid YAML: {}", e.msg)});
  }
  // A Field throws yaml::Failure inside the loader; read_document turns it into the expected.
  return yaml::read_document(file_name, [&] { return Loader(file_name).load(root); });
}

std::expected<Scenario, ConfigError> load_scenario(const std::filesystem::path& file) {
  auto text = read_text_file(file);
  if (!text) return std::unexpected(ConfigError{file.string(), 0, 0, "", text.error()});
  return parse_scenario(*text, file.string());
}

}  // namespace hil::runtime
