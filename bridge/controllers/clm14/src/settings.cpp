// SPDX-License-Identifier: MIT
#include "hil/controllers/clm14/settings.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace hil::controllers::clm14 {

namespace {

struct Reader {
  const ParameterLookup& lookup;
  std::string failed;  // "A106 'x': why"

  std::vector<std::string> fields(std::string_view number, std::size_t min_fields) {
    const std::string t = lookup(number);
    std::vector<std::string> out;
    std::size_t i = 0;
    while (i < t.size()) {
      while (i < t.size() && t[i] == ' ') ++i;
      const std::size_t b = i;
      while (i < t.size() && t[i] != ' ') ++i;
      if (i > b) out.emplace_back(t.substr(b, i - b));
    }
    if (out.size() < min_fields && failed.empty())
      failed = fmt::format("{} '{}': expected {} field(s)", number, t, min_fields);
    out.resize(std::max(out.size(), min_fields));
    return out;
  }
  double number(std::string_view param, const std::string& f) {
    auto m = parse_micro(f);
    if (!m) {
      if (failed.empty()) failed = fmt::format("{}: '{}' is not a number", param, f);
      return 0.0;
    }
    return to_double(*m);
  }
  int integer(std::string_view param, const std::string& f) { return static_cast<int>(number(param, f)); }
  std::optional<BitAddress> io(std::string_view param, const std::string& f) {
    auto b = parse_optional_bit(f);
    if (!b.ok && failed.empty()) failed = fmt::format("{}: '{}' is not an I/O address", param, f);
    return b.bit;
  }
};

}  // namespace

std::expected<Settings, ProgramError> make_settings(const ParameterLookup& lookup) {
  Reader r{lookup, {}};
  Settings s;
  const auto b000 = r.fields("B000", 3);
  s.axes[0].enabled = true;
  for (std::size_t i = 1; i < 4; ++i) s.axes[i].enabled = b000[i - 1] == "1";
  s.axis_count = 1;
  for (int i = 0; i < 4; ++i)
    if (s.axes[static_cast<std::size_t>(i)].enabled) s.axis_count = i + 1;
  const auto b010 = r.fields("B010", 1);
  s.cycle_ms = r.number("B010", b010[0]);
  if (s.cycle_ms == 0.0) s.cycle_ms = s.axis_count <= 2 ? 2.0 : s.axis_count == 3 ? 3.0 : 4.0;
  const auto b011 = r.fields("B011", 2);
  const auto b012 = r.fields("B012", 2);
  s.task_start[1] = r.integer("B011", b011[0]);
  s.task_start[2] = r.integer("B011", b011[1]);
  s.task_start[3] = r.integer("B012", b012[0]);
  s.task_start[4] = r.integer("B012", b012[1]);
  for (std::size_t t = 1; t < 5; ++t) s.task_used[t] = s.task_start[t] != 0;
  const auto b014 = r.fields("B014", 3);
  s.manual_vector_input = r.io("B014", b014[0]);
  s.manual_vector_on_mode_change = b014[1] == "1";
  s.manual_vector_line = r.integer("B014", b014[2]);
  const auto b015 = r.fields("B015", 4);
  s.interrupt_vector_input = r.io("B015", b015[0]);
  s.interrupt_vector_edge = r.integer("B015", b015[1]);
  s.interrupt_vector_aborts_move = b015[2] == "1";
  s.interrupt_vector_line = r.integer("B015", b015[3]);
  s.restart_line = r.integer("B016", r.fields("B016", 1)[0]);
  if (!lookup("B017").empty()) {
    // [decided, profile] digit order: averaging, override source of axes 1..4, reserved.
    const auto b017 = r.fields("B017", 5);
    s.analog_averaging = r.integer("B017", b017[0]);
    if (r.failed.empty() && (s.analog_averaging < 0 || s.analog_averaging > 9))
      r.failed = fmt::format("B017: analog averaging code {} (0..9)", s.analog_averaging);
    for (std::size_t ax = 0; ax < 4; ++ax) {
      s.override_source[ax] = r.integer("B017", b017[ax + 1]);
      if (r.failed.empty() && (s.override_source[ax] < 0 || s.override_source[ax] > 6))
        r.failed = fmt::format("B017: override source {} of axis {} (0 off, 1-4 analog, 5 binary, 6 Gray)",
                               s.override_source[ax], ax + 1);
    }
  }
  const auto b018 = r.fields("B018", 2);
  s.error_code_byte = r.integer("B018", b018[0]);
  for (std::size_t i = 0; i < 7; ++i) s.output_clear[i] = i < b018[1].size() ? b018[1][i] - '0' : 0;
  for (int ax = 1; ax <= 4; ++ax) {
    AxisSettings& a = s.axes[static_cast<std::size_t>(ax - 1)];
    if (!a.enabled) continue;
    const auto p = [ax](int n) { return fmt::format("A{}{:02d}", ax, n); };
    const auto x00 = r.fields(p(0), 2);
    a.motion = static_cast<MotionType>(std::clamp(r.integer(p(0), x00[0]), 0, 2));
    a.mode = r.integer(p(0), x00[1]);
    a.master = x00.size() > 2 && !x00[2].empty() ? r.integer(p(0), x00[2]) : 0;
    a.test_mode = x00.size() > 3 && x00[3] == "1";
    a.wheel_option2 = x00.size() > 4 && x00[4] == "1";
    a.feed_constant = r.number(p(1), r.fields(p(1), 1)[0]);
    a.min_limit = r.number(p(3), r.fields(p(3), 1)[0]);
    a.max_limit = r.number(p(4), r.fields(p(4), 1)[0]);
    const auto x05 = r.fields(p(5), 2);
    a.modulo = r.number(p(5), x05[0]);
    a.modulo_path = r.integer(p(5), x05[1]);
    a.vmax = r.number(p(6), r.fields(p(6), 1)[0]);
    a.jog_velocity = r.number(p(7), r.fields(p(7), 1)[0]);
    a.acceleration = r.number(p(8), r.fields(p(8), 1)[0]);
    const auto x09 = r.fields(p(9), 2);
    a.accel_permille = r.integer(p(9), x09[0]);
    a.decel_permille = r.integer(p(9), x09[1]);
    a.jerk_time_s = r.number(p(10), r.fields(p(10), 1)[0]);
    const auto x15 = r.fields(p(15), 2);
    a.feed_angle_input = r.io(p(15), x15[0]);
    a.interrupt_input = r.io(p(15), x15[1]);
    if (!lookup(p(16)).empty()) {
      const auto x16 = r.fields(p(16), 3);
      a.wheel_window1 = r.integer(p(16), x16[0]);
      a.wheel_window2 = r.integer(p(16), x16[1]);
      a.tolerance2_output = r.io(p(16), x16[2]);
    }
    if (!lookup(p(31)).empty()) a.wheel_input = r.io(p(31), r.fields(p(31), 1)[0]);
    const auto x19 = r.fields(p(19), 2);
    a.encoder_pulses = r.integer(p(19), x19[0]);
    a.encoder_revolutions = r.integer(p(19), x19[1]);
    a.encoder_type = r.integer(p(20), r.fields(p(20), 1)[0]);
    const auto x23 = r.fields(p(23), 2);
    a.homing_start_input = r.io(p(23), x23[0]);
    a.home_switch_input = r.io(p(23), x23[1]);
    const auto x24 = r.fields(p(24), 3);
    a.homed_output = r.io(p(24), x24[0]);
    a.homing_velocity_permille = r.integer(p(24), x24[1]);
    a.homing_type = r.integer(p(24), x24[2]);
    a.home_offset = r.number(p(25), r.fields(p(25), 1)[0]);
    const auto x27 = r.fields(p(27), 2);
    a.reached_output = r.io(p(27), x27[0]);
    a.reached_window = r.number(p(27), x27[1]);
    const auto x29 = r.fields(p(29), 3);
    a.presignal_output = r.io(p(29), x29[0]);
    a.presignal_pulse_s = r.number(p(29), x29[1]);
    a.presignal_distance = r.number(p(29), x29[2]);
    if (!lookup(p(30)).empty()) {
      const auto x30 = r.fields(p(30), 2);
      a.open_feed_roll_input = r.io(p(30), x30[0]);
      a.open_feed_roll_output = r.io(p(30), x30[1]);
    }
    const auto x32 = r.fields(p(32), 2);
    a.velocity_reached_output = r.io(p(32), x32[0]);
    a.decelerating_output = r.io(p(32), x32[1]);
    const auto x11 = r.fields(p(11), 0);
    a.feedforward = x11.size() > 1 ? r.integer(p(11), x11[1]) : 0;
    if (ax == 1) {
      // Flying cutoff (Ax33-Ax42, axis 1 only); an absent parameter keeps the function off.
      const auto given = [&](int n) { return !lookup(p(n)).empty(); };
      if (given(33)) {
        const auto f = r.fields(p(33), 2);
        a.cut_inhibit_input = r.io(p(33), f[0]);
        a.cut_inhibit_output = r.io(p(33), f[1]);
      }
      if (given(34)) {
        const auto f = r.fields(p(34), 3);
        a.immediate_cut_input = r.io(p(34), f[0]);
        a.manual_cut_line = r.integer(p(34), f[1]);
        a.indexing = f[2] == "1";
      }
      if (given(35)) a.reverse_inhibit_input = r.io(p(35), r.fields(p(35), 1)[0]);
      if (given(36)) {
        const auto f = r.fields(p(36), 2);
        a.rapid_stop_input = r.io(p(36), f[0]);
        a.rapid_stop_line = r.integer(p(36), f[1]);
      }
      if (given(37)) {
        const auto f = r.fields(p(37), 2);
        a.max_stroke = r.number(p(37), f[0]);
        a.max_stroke_line = r.integer(p(37), f[1]);
      }
      if (given(38)) {
        const auto f = r.fields(p(38), 3);
        a.start_0000_input = r.io(p(38), f[0]);
        a.raster_edge = f[1] == "1";
        a.always_0000 = f[2] == "1";
      }
      if (given(39)) {
        const auto f = r.fields(p(39), 2);
        a.reverse_opt_input = r.io(p(39), f[0]);
        a.reverse_opt_output = r.io(p(39), f[1]);
      }
      if (given(40)) {
        const auto f = r.fields(p(40), 3);
        a.reverse_wait_s = r.number(p(40), f[0]);
        a.reverse_min_accel_permille = r.integer(p(40), f[1]);
        a.reverse_velocity_window_permille = r.integer(p(40), f[2]);
      }
      if (given(41)) a.tool_width = r.number(p(41), r.fields(p(41), 1)[0]);
      if (given(42)) {
        const auto f = r.fields(p(42), 2);
        a.crop_length = r.number(p(42), f[0]);
        a.crop_input = r.io(p(42), f[1]);
      }
    }
    if (r.failed.empty() && (a.feed_constant <= 0.0 || a.vmax <= 0.0 || a.acceleration <= 0.0))
      r.failed = fmt::format("{}: feed constant, Vmax (Ax06) and acceleration (Ax08) must be > 0", p(1));
  }
  // Master encoder 1 (§8.4): absent parameters = the profile's defaults are not known here, so
  // an empty C000/C002 means "not used".
  if (!lookup("C000").empty()) s.me1.pulses = r.integer("C000", r.fields("C000", 1)[0]);
  if (!lookup("C001").empty()) {
    const auto c001 = r.fields("C001", 6);
    s.me1.inverted = c001[4] == "1";
    s.me1.averaging = std::clamp(r.integer("C001", c001[5]), 0, 7);
  }
  if (!lookup("C008").empty()) {
    const auto c008 = r.fields("C008", 2);
    s.me1.no_material_input = r.io("C008", c008[0]);
    s.me1.no_material_variable = r.integer("C008", c008[1]);
  }
  s.me1.feed_constant = lookup("C002").empty() ? 0.0 : r.number("C002", r.fields("C002", 1)[0]);
  if (r.failed.empty() && s.me1.feed_constant < 0.0) r.failed = "C002: the feed constant must be >= 0";
  // Master encoder 2 (C004-C006: "the same for master encoder 2", §8.4).
  if (!lookup("C004").empty()) s.me2.pulses = r.integer("C004", r.fields("C004", 1)[0]);
  if (!lookup("C005").empty()) {
    const auto c005 = r.fields("C005", 6);
    s.me2.inverted = c005[4] == "1";
    s.me2.averaging = std::clamp(r.integer("C005", c005[5]), 0, 7);
  }
  s.me2.feed_constant = lookup("C006").empty() ? 0.0 : r.number("C006", r.fields("C006", 1)[0]);
  if (r.failed.empty() && s.me2.feed_constant < 0.0) r.failed = "C006: the feed constant must be >= 0";
  // Measuring wheel (§7.2): axis 1 on master encoder 1, axis 2 on master encoder 2; the encoder
  // must be in use (its feed constant set).
  for (int ax = 1; ax <= 2; ++ax) {
    const AxisSettings& a = s.axes[static_cast<std::size_t>(ax - 1)];
    const MasterEncoderSettings& me = ax == 1 ? s.me1 : s.me2;
    if (r.failed.empty() && a.enabled && a.measuring_wheel() && !me.used())
      r.failed = fmt::format("A{}00: measuring-wheel mode {} needs master encoder {} ({} > 0)", ax, a.mode, ax,
                             ax == 1 ? "C002" : "C006");
  }
  if (!r.failed.empty()) return std::unexpected(ProgramError{ClmError::parameter_invalid, -1, r.failed});
  return s;
}

}  // namespace hil::controllers::clm14
