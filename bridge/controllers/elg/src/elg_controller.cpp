// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/elg_controller.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

#include "hil/core/text_file.hpp"
#include "hil/profiles/validation.hpp"

namespace hil::controllers::elg {
namespace {

constexpr std::uint32_t out_byte = 0, in_byte = 0, panel_byte = 1, select_byte = 2;

/// Reads a number (value or default) from the loaded tape; a missing one is a ConfigError.
struct Tape {
  const LoadedParameters& p;
  profiles::Scope scope;
  explicit Tape(const LoadedParameters& loaded) : p(loaded), scope(*loaded.profile, &loaded.set, {}) {}
  std::expected<std::int64_t, ConfigError> integer(const std::string& name) const {
    const auto v = scope.lookup(name);
    if (v) {
      if (const auto* d = std::get_if<long double>(&*v)) return static_cast<std::int64_t>(std::llround(*d));
    }
    return std::unexpected(ConfigError{p.file.string(), 0, 0, name, name + " has no value in the tape or profile"});
  }
};

/// Measuring-system unit of the linear axes in nm from MD 5002 bits 2-0 (12.1).
std::optional<std::int64_t> linear_ms_nm(std::int64_t code) {
  switch (code) {
    case 0:
      return 5000;  // 0.5e-2 mm
    case 1:
      return 12700;  // 0.5e-3 inch
    case 2:
      return 500;  // 0.5e-3 mm (released)
    case 3:
      return 1270;  // 0.5e-4 inch
    case 4:
      return 50;  // 0.5e-4 mm
    case 5:
      return 127;  // 0.5e-5 inch
    case 6:
      return 200;  // 2e-4 mm
    case 7:
      return 508;  // 2e-5 inch
    default:
      return std::nullopt;
  }
}

ControllerAxis make_axis(const std::string& name, const std::string& units, motion::Ratio ratio, double velocity,
                         double window) {
  ControllerAxis a;
  a.name = name;
  a.units = units;
  auto& c = a.config;
  c.name = name;
  c.inc_per_unit = ratio;
  // [I] The ELG's MD list has no acceleration: a 0.1 s ramp to the maximum speed (docs/elg.md).
  c.limits = {velocity, velocity * 10.0, velocity * 200.0};
  c.quick_stop_deceleration = velocity * 20.0;
  c.jog_velocity = velocity / 10.0;
  c.following_error.static_window = window;
  c.standstill_window = window;
  c.in_position_window = window / 2.0;
  c.in_position_timeout = std::chrono::seconds(2);
  return a;
}

/// "KEY=VALUE,KEY=VALUE" (blanks around either trimmed), as the controller options write maps.
std::expected<std::vector<std::pair<std::string, std::string>>, std::string> split_pairs(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> out;
  auto trim = [](std::string v) {
    v.erase(0, v.find_first_not_of(' '));
    v.erase(v.find_last_not_of(' ') + 1);
    return v;
  };
  std::size_t pos = 0;
  while (pos < text.size()) {
    const auto comma = text.find(',', pos);
    const std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    pos = comma == std::string::npos ? text.size() : comma + 1;
    const auto eq = item.find('=');
    if (eq == std::string::npos) return std::unexpected("'" + item + "' is not KEY=VALUE");
    std::string key = trim(item.substr(0, eq)), value = trim(item.substr(eq + 1));
    if (key.empty() || value.empty()) return std::unexpected("'" + item + "' is not KEY=VALUE");
    out.emplace_back(std::move(key), std::move(value));
  }
  return out;
}

/// A whole decimal number, nothing else.
std::optional<int> whole_number(const std::string& text) {
  int n = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return n;
}

}  // namespace

ElgController::ElgController(LoadedParameters parameters, HobbingConfig config, NcProgram program,
                             std::vector<ControllerAxis> axes, std::vector<int> circuits, bool auto_start,
                             Duration cycle)
    : Controller(parameters.profile, std::move(parameters.set), IoLayout{{3, 1, 2, 0}}, cycle),
      config_(std::move(config)),
      program_(std::move(program)),
      auto_start_(auto_start),
      circuits_(std::move(circuits)) {
  for (auto& a : axes) add_axis(std::move(a));
  alarms_ = catalogue("alarms");
  (void)io().name_bit("cycle_start", {IoArea::input, in_byte, 0});
  (void)io().name_bit("fe_monitor", {IoArea::input, in_byte, 1});
  (void)io().name_bit("reset", {IoArea::input, in_byte, 2});
  // The machine control panel (12.4.3), see elg_controller.hpp.
  const char* keys[] = {"key_plus", "key_minus", "rapid", "rapid_override", "ref_cam"};
  for (std::uint8_t i = 0; i < 5; ++i) (void)io().name_bit(keys[i], {IoArea::input, in_byte, std::uint8_t(3 + i)});
  const char* panel[] = {"override_1", "override_2", "override_4", "override_8", "mode_1", "mode_2", "mode_4"};
  for (std::uint8_t i = 0; i < 7; ++i) (void)io().name_bit(panel[i], {IoArea::input, panel_byte, i});
  (void)io().name_bit("inc_1", {IoArea::input, select_byte, 0});
  (void)io().name_bit("inc_2", {IoArea::input, select_byte, 1});
  (void)io().name_bit("inc_4", {IoArea::input, select_byte, 2});
  (void)io().name_bit("data_start", {IoArea::input, select_byte, 3});
  (void)io().name_bit("computed", {IoArea::output, out_byte, 0});
  (void)io().name_bit("coupled", {IoArea::output, out_byte, 1});
  (void)io().name_bit("tooth_gap_reached", {IoArea::output, out_byte, 2});
  (void)io().name_bit("elg_alarm", {IoArea::output, out_byte, 3});
  (void)io().name_bit("contact_closed", {IoArea::output, out_byte, 4});
  (void)io().name_bit("program_running", {IoArea::output, out_byte, 5});
  (void)io().name_bit("referenced", {IoArea::output, out_byte, 6});
  (void)io().name_bit("c_traversing", {IoArea::output, out_byte, 7});
  (void)io().name_byte("tooth", ByteAddress{IoArea::marker, 1});
}

PanelSignals ElgController::read_panel() const noexcept {
  auto bit = [&](std::uint32_t byte, std::uint8_t b) { return io().get(BitAddress{IoArea::input, byte, b}); };
  auto code = [&](std::uint32_t byte, std::uint8_t first, std::uint8_t width) {
    int v = 0;
    for (std::uint8_t i = 0; i < width; ++i) v |= bit(byte, std::uint8_t(first + i)) ? 1 << i : 0;
    return v;
  };
  PanelSignals p;
  p.key_plus = bit(in_byte, 3);
  p.key_minus = bit(in_byte, 4);
  p.rapid = bit(in_byte, 5);
  p.rapid_override = bit(in_byte, 6);
  p.ref_cam = bit(in_byte, 7);
  p.override_position = code(panel_byte, 0, 4) + 1;  // code 0 = position 1 = 0 %
  const int mode = code(panel_byte, 4, 3);
  p.mode = mode >= 1 && mode <= 3 ? static_cast<PanelMode>(mode) : PanelMode::automatic;
  static constexpr std::int64_t factors[] = {1, 10, 100, 1000, 10000};
  const int inc = code(select_byte, 0, 3);
  p.inc_factor = factors[std::min(inc, 4)];
  return p;
}

void ElgController::on_cycle(const CycleTime& cycle) noexcept {
  if (!machine_) {
    HobbingAxes axes{&axis(0), &axis(1), &axis(2), &axis(3), axis_count() > 4 ? &axis(4) : nullptr};
    machine_ = std::make_unique<HobbingMachine>(program_, config_, axes);
  }
  // Power-up: enable the axes (the PC's controller enables), then start the NC program.
  const bool ready = power_up_axes();
  if (!started_ && ready && (auto_start_ || io().rising(BitAddress{IoArea::input, in_byte, 0}))) {
    machine_->start();
    started_ = true;
  }
  machine_->pc_signals().fe_monitor = io().get(BitAddress{IoArea::input, in_byte, 1});
  machine_->pc_signals().reset = io().get(BitAddress{IoArea::input, in_byte, 2});
  machine_->pc_signals().data_start = io().get(BitAddress{IoArea::input, select_byte, 3});
  machine_->pc_signals().panel = read_panel();
  // The direction keys in INC also drive the HAE offset motion while coupled (4.2).
  const bool hae_keys = machine_->gearbox().status().coupled && machine_->pc_signals().panel.mode == PanelMode::inc;
  machine_->pc_signals().inc_plus = hae_keys && machine_->pc_signals().panel.key_plus;
  machine_->pc_signals().inc_minus = hae_keys && machine_->pc_signals().panel.key_minus;
  machine_->step(cycle);

  const auto& gb = machine_->gearbox();
  const auto& st = gb.status();
  io().set(BitAddress{IoArea::output, out_byte, 0}, st.computed);
  io().set(BitAddress{IoArea::output, out_byte, 1}, st.coupled);
  io().set(BitAddress{IoArea::output, out_byte, 2}, st.tooth_gap_reached);
  io().set(BitAddress{IoArea::output, out_byte, 3}, st.alarm);
  io().set(BitAddress{IoArea::output, out_byte, 4}, st.contact_closed);
  io().set(BitAddress{IoArea::output, out_byte, 5}, machine_->nc().state() == NcState::running && started_);
  io().set(BitAddress{IoArea::output, out_byte, 6}, st.referenced);
  io().set(BitAddress{IoArea::output, out_byte, 7}, gb.setup().moving());
  io().set(ByteAddress{IoArea::marker, 1}, static_cast<std::uint8_t>(std::clamp(st.tooth, 0, 255)));

  // ELG alarms become device errors of the catalogue "alarms" on the table axis C.
  // An alarm the ELG no longer holds was cleared there (RESET with the coupling off).
  const auto& alarms = gb.alarms();
  if (alarms_ != nullptr && alarms != reported_) {
    for (Alarm a : alarms)
      if (std::find(reported_.begin(), reported_.end(), a) == reported_.end())
        raise(*alarms_, static_cast<int>(a), cycle.now, 1);
    for (Alarm a : reported_)
      if (!gb.has_alarm(a)) (void)clear_error(*alarms_, static_cast<int>(a), 1);
    reported_ = alarms;
  }
  if (!machine_->error().empty() && alarms_ != nullptr && !errors().any()) {
    // A command the motion core refused (the NC asked for more than an axis allows): stop.
    raise(*alarms_, 2207, cycle.now, 1, machine_->error());
  }
}

std::optional<DeviceErrorCode> ElgController::map_axis_fault(std::size_t axis, const hil::Fault& fault,
                                                             const motion::AxisStatus&) const noexcept {
  // The ELG's axis-specific reset alarms (10.2), base + measuring circuit. Its own coupled
  // following-error monitor (2215) is the gearbox's; the motion core's supervision maps onto the
  // monitors the ELG runs on an axis (docs/controllers.md, ELG table).
  if (alarms_ == nullptr || axis >= circuits_.size() || circuits_[axis] < 0) return std::nullopt;
  int base = 0;
  const std::error_code& f = fault.code;
  if (f == hil::MotionFault::following_error || f == hil::MotionFault::following_error_dynamic)
    base = 1160;  // contour monitoring (MD 332* band)
  else if (f == hil::MotionFault::standstill || f == hil::MotionFault::in_position_timeout)
    base = 1120;  // monitoring of standstill (MD 156 / MD 212*)
  else if (f == hil::MotionFault::drive_lost)
    base = 1320;  // hardware control loop: the measuring signals are missing
  else if (f == hil::MotionFault::not_enabled)
    base = 1680;  // controller enable for traversing axis refused
  else
    return std::nullopt;
  return DeviceErrorCode{alarms_, base + circuits_[axis]};
}

std::expected<ElgSetup, ConfigError> elg_setup_from_tape(const LoadedParameters& loaded, const HobbingConfig& options,
                                                         Duration cycle) {
  HobbingConfig config = options;
  const Tape tape(loaded);
  auto get = [&](const std::string& name) { return tape.integer(name); };
  auto guide = get("MD5020.guide_axis"), drive = get("MD5020.drive_axis"), axial = get("MD5021.axial_z"),
       tangential = get("MD5021.tangential_y"), units = get("MD5002.measuring_unit");
  for (auto* v : {&guide, &drive, &axial, &tangential, &units})
    if (!*v) return std::unexpected(v->error());
  auto& md = config.gearbox.md;
  md.axis_declaration_ok = *guide >= 1 && *guide <= 4 && *drive >= 1 && *drive <= 4 && *guide != *drive;
  const std::int64_t guide_i = std::clamp<std::int64_t>(*guide, 1, 4) - 1;
  const std::int64_t drive_i = std::clamp<std::int64_t>(*drive, 1, 4) - 1;
  auto per_axis = [&](const char* md_name, std::int64_t index) { return get(fmt::format("{}{}", md_name, index)); };
  auto n00 = per_axis("MD396", guide_i), n02 = per_axis("MD396", drive_i), kv = per_axis("MD252", drive_i),
       vb = per_axis("MD280", guide_i), vc = per_axis("MD280", drive_i);
  auto md166 = get("MD166"), md169 = get("MD169"), md170 = get("MD170");
  for (auto* v : {&n00, &n02, &kv, &vb, &vc, &md166, &md169, &md170})
    if (!*v) return std::unexpected(v->error());
  const auto ms = linear_ms_nm(*units);
  if (!ms)
    return std::unexpected(
        ConfigError{loaded.file.string(), 0, 0, "MD5002", "MD 5002 measuring unit code out of range"});
  if (*n00 <= 0 || *n02 <= 0)
    return std::unexpected(
        ConfigError{loaded.file.string(), 0, 0, "MD396*", "MD 396* of the guide and drive axes must be > 0 pulses"});
  md.n00 = *n00;
  md.n02 = *n02;
  config.gearbox.setup.zero_mark_counts = 4 * *n02;  // [I] one zero mark per revolution of C
  config.ssfk.revolution = 4 * *n02;
  md.ms_z_nm = md.ms_y_nm = *ms;
  md.contour_factor_c = static_cast<std::int32_t>(*kv);
  md.hae_speed = static_cast<std::int32_t>(*md170);
  // The setting-up modes of C (ch. 7): MD 100-114, 240*, 280*-300*, 564* bit 0.
  auto& su = config.gearbox.setup;
  for (std::size_t i = 0; i < su.override_percent.size(); ++i) {
    auto v = get(fmt::format("MD{}", 100 + i));
    if (!v) return std::unexpected(v.error());
    su.override_percent[i] = *v;
  }
  auto md240 = per_axis("MD240", drive_i), md280 = per_axis("MD280", drive_i), md284 = per_axis("MD284", drive_i),
       md288 = per_axis("MD288", drive_i), md292 = per_axis("MD292", drive_i), md296 = per_axis("MD296", drive_i),
       md300 = per_axis("MD300", drive_i), ref_minus = get(fmt::format("MD564{}.ref_minus", drive_i));
  for (auto* v : {&md240, &md280, &md284, &md288, &md292, &md296, &md300, &ref_minus})
    if (!*v) return std::unexpected(v->error());
  su.ref_coordinate = *md240;
  su.max_speed = *md280;
  su.ref_cutoff_speed = *md284;
  su.jog_speed = *md288;
  su.rapid_speed = *md292;
  su.ref_speed = *md296;
  su.inc_speed = *md300;
  su.ref_minus = *ref_minus != 0;
  su.axis_index = static_cast<int>(drive_i);
  // SSFK of C (ssfk.hpp): MD 5016 bits 1-2, MD 316*-328*, the flags MD 6000-6249.
  {
    auto& k = config.ssfk;
    auto active = get("MD5016.ssfk"), dir = get("MD5016.ssfk_direction"), p_plus = per_axis("MD316", drive_i),
         p_minus = per_axis("MD320", drive_i), dist = per_axis("MD324", drive_i), step = per_axis("MD328", drive_i);
    for (auto* v : {&active, &dir, &p_plus, &p_minus, &dist, &step})
      if (!*v) return std::unexpected(v->error());
    k.active = *active != 0;
    k.direction_dependent = *dir != 0;
    k.pointer_plus = *p_plus;
    k.pointer_minus = *p_minus;
    k.distance = *dist;
    k.step = *step;
    if (k.active) {  // the 250 flag bytes are read only when SSFK is on
      for (std::size_t b = 0; b < k.flags.size(); ++b) {
        std::uint8_t byte = 0;
        for (int point = 1; point <= 4; ++point) {
          auto no = get(fmt::format("MD{}.p{}_no", 6000 + b, point)),
               plus = get(fmt::format("MD{}.p{}_plus", 6000 + b, point));
          if (!no) return std::unexpected(no.error());
          if (!plus) return std::unexpected(plus.error());
          byte = static_cast<std::uint8_t>(byte | (*no != 0 ? 1 : 0) << (2 * (point - 1)) |
                                           (*plus != 0 ? 1 : 0) << (2 * (point - 1) + 1));
        }
        k.flags[b] = byte;
      }
    }
  }
  config.gearbox.gearing_on_tolerance = *md166;
  config.gearbox.fe_tolerance_min = *md169;
  config.gearbox.cycle_s = hil::to_seconds(cycle);

  // Speeds: MD 280* in 1000 units/min, 1 unit = 2 MS (12.1).
  auto rotary_speed = [](std::int64_t max_speed, std::int64_t n) {
    return static_cast<double>(max_speed) * 1000.0 * 180.0 / static_cast<double>(n) / 60.0;
  };
  const double linear_speed = 10000.0 * 1000.0 * 2.0 * static_cast<double>(*ms) * 1e-6 / 60.0;
  std::vector<ControllerAxis> axes;
  axes.push_back(make_axis("B", "deg", rotary_counts_per_degree(md.n00), rotary_speed(*vb, md.n00), 5.0));
  axes.push_back(make_axis("C", "deg", rotary_counts_per_degree(md.n02), rotary_speed(*vc, md.n02), 1.0));
  axes.push_back(make_axis("Z", "mm", linear_counts_per_mm(*ms), linear_speed, 1.0));
  axes.push_back(make_axis("X", "mm", linear_counts_per_mm(*ms), linear_speed, 1.0));
  if (*tangential != 0) axes.push_back(make_axis("Y", "mm", linear_counts_per_mm(*ms), linear_speed, 1.0));
  for (auto& a : axes) {
    if (auto v = motion::validate(a.config); !v)
      return std::unexpected(ConfigError{loaded.file.string(), 0, 0, "axis " + a.name, v.error()});
  }
  if (*axial == 0)
    axes[2].warnings.push_back("MD 5021 declares no axial axis: the Z term of the linkage is off (ud_z unused)");
  config.rapid_mm_per_s = linear_speed;

  // Measuring circuits (MD 5020/5021 axis numbers 1..4); X is the NC's, not the ELG's.
  std::vector<int> circuits{static_cast<int>(guide_i), static_cast<int>(drive_i),
                            *axial >= 1 && *axial <= 4 ? static_cast<int>(*axial - 1) : -1, -1};
  if (*tangential != 0)
    circuits.push_back(*tangential >= 1 && *tangential <= 4 ? static_cast<int>(*tangential - 1) : -1);
  return ElgSetup{std::move(config), std::move(axes), std::move(circuits)};
}

void register_elg(ControllerRegistry& registry) {
  registry.add(
      "sinumerik-elg", [](const ControllerSpec& spec) -> std::expected<std::unique_ptr<Controller>, ConfigError> {
        auto fail = [&](std::string key, std::string message) {
          return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller." + key, std::move(message)});
        };
        if (spec.programs.size() != 1) return fail("programs", "the ELG runs one NC program: programs: [FILE.nc]");
        HobbingConfig config;
        bool auto_start = true;
        for (const auto& [key, value] : spec.options) {
          if (key == "start") {
            if (value != "auto" && value != "input") return fail(key, "start: auto or input");
            auto_start = value == "auto";
          } else if (key == "index") {
            if (value != "grid" && value != "relative") return fail(key, "index: grid or relative");
            config.gearbox.index_on_grid = value == "grid";
          } else if (key == "m_functions") {
            auto pairs = split_pairs(value);
            if (!pairs) return fail(key, pairs.error() + ": write M=COMMAND");
            MFunctionMap map;
            for (const auto& [m_text, name] : *pairs) {
              const auto m = whole_number(m_text);
              const auto command = parse_elg_command(name);
              if (!m || *m < 0 || *m > 99 || !command)
                return fail(key, "'" + m_text + "=" + name +
                                     "': write M=COMMAND (commands: gearing_on, gearing_off, compute, "
                                     "single_pitch_on, single_pitch_off, index_plus, index_minus, "
                                     "fe_monitor_on, fe_monitor_off, hae_on, hae_off)");
              map[*m] = *command;
            }
            config.m_functions = std::move(map);
          } else if (key == "r_parameters") {
            auto pairs = split_pairs(value);
            if (!pairs) return fail(key, pairs.error());
            for (const auto& [name, r_text] : *pairs) {
              const auto number = whole_number(r_text);
              if (!number) return fail(key, "'" + name + "=" + r_text + "': VALUE must be a number");
              const int r = *number;
              if (r < 0 || r > 999) return fail(key, name + ": an R number 0..999");
              if (name == "z0")
                config.r_z0 = r;
              else if (name == "z2")
                config.r_z2 = r;
              else if (name == "ud_z")
                config.r_ud_z = r;
              else if (name == "ud_y")
                config.r_ud_y = r;
              else if (name == "toler")
                config.r_toler = r;
              else
                return fail(key, "'" + name + "': known are z0, z2, ud_z, ud_y, toler");
            }
          } else {
            return fail(key,
                        "unknown controller key '" + key +
                            "' (known: device, parameters, programs, cycle, start, index, m_functions, r_parameters)");
          }
        }
        auto loaded = load_parameter_file(spec.device, spec.parameters);
        if (!loaded) return std::unexpected(loaded.error());
        const Duration cycle = spec.cycle.value_or(std::chrono::milliseconds(2));
        auto setup = elg_setup_from_tape(*loaded, config, cycle);
        if (!setup) return std::unexpected(setup.error());
        auto text = read_text_file(spec.programs.front());
        if (!text) return fail("programs", text.error());
        auto program = parse_nc_program(*text);
        if (!program) {
          return std::unexpected(
              ConfigError{spec.programs.front().string(), program.error().line, 0, "program", program.error().what()});
        }
        return std::make_unique<ElgController>(std::move(*loaded), std::move(setup->config), std::move(*program),
                                               std::move(setup->axes), std::move(setup->circuits), auto_start, cycle);
      });
}

}  // namespace hil::controllers::elg
