// SPDX-License-Identifier: MIT
#include "hil/controllers/clm14/runtime_controller.hpp"

#include <fmt/format.h>

#include <charconv>
#include <fstream>
#include <sstream>

#include "hil/controllers/io_address_clm.hpp"
#include "hil/profiles/loader.hpp"
#include "hil/serial/clm14/device_data.hpp"

namespace hil::controllers::clm14 {

namespace {

namespace hc = hil::controllers;

std::expected<std::string, ConfigError> read_text(const std::filesystem::path& file, const ControllerSpec& spec,
                                                  std::string_view what) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    return std::unexpected(ConfigError{spec.file, spec.line, 0, fmt::format("controller.{}", what),
                                       fmt::format("cannot read {} file '{}'", what, file.string())});
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\r')) s.remove_suffix(1);
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  return s;
}

/// "B002 019200 0 1 8 1" or "# K B002 019200 0 1 8 1$E4" -> {"B002", "019200 0 1 8 1"}.
std::optional<std::pair<std::string, std::string>> parameter_line(std::string_view l) {
  l = trim(l);
  if (l.empty() || l.front() == ';') return std::nullopt;
  if (l.front() == '#' || l.front() == '!') {
    const auto k = l.find('K');
    if (k == std::string_view::npos) return std::nullopt;
    l = trim(l.substr(k + 1));
    if (const auto d = l.rfind('$'); d != std::string_view::npos && d + 3 == l.size()) l = l.substr(0, d);
  }
  const auto sp = l.find(' ');
  if (sp == std::string_view::npos) return std::pair{std::string(l), std::string{}};
  return std::pair{std::string(l.substr(0, sp)), std::string(trim(l.substr(sp + 1)))};
}

}  // namespace

RuntimeController::RuntimeController(std::shared_ptr<const profiles::Profile> profile,
                                     std::map<std::string, std::string> parameters, Duration cycle, Options options)
    : hc::Controller(std::move(profile), profiles::ParameterSet{}, hc::clm_io_layout(3, 3, 7), cycle),
      parameters_(std::move(parameters)),
      model_(options) {
  model_.set_parameters([this](std::string_view n) {
    const auto it = parameters_.find(std::string(n));
    return it == parameters_.end() ? std::string{} : it->second;
  });
}

std::expected<std::unique_ptr<hc::Controller>, ConfigError> RuntimeController::create(const ControllerSpec& spec) {
  auto profile = profiles::find_profile("clm14");
  if (!profile) return std::unexpected(profile.error());
  auto text = read_text(spec.parameters, spec, "parameters");
  if (!text) return std::unexpected(text.error());
  std::map<std::string, std::string> params;
  // the profile's defaults first (as after !CSETPA); the file overrides them
  auto data = serial::clm14::load_device_data();
  if (!data) return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller", data.error()});
  for (const auto& n : (*data)->parameter_numbers(4)) params[n] = (*data)->parameter_default(n);
  {
    std::istringstream in(*text);
    std::string line;
    while (std::getline(in, line))
      if (auto p = parameter_line(line)) params[p->first] = p->second;
  }
  auto settings = make_settings([&](std::string_view n) {
    const auto it = params.find(std::string(n));
    return it == params.end() ? std::string{} : it->second;
  });
  if (!settings)
    return std::unexpected(ConfigError{spec.parameters.string(), 0, 0, "controller.parameters",
                                       fmt::format("CLM error 02: {}", settings.error().message)});
  // Controller keys: master_encoder = the machine axis whose drive counts master encoder 1;
  // homing = clm | drive; marker1..marker4 = an encoder count offset or a CLM input address.
  // test_speed_step = the flying cutoff test mode's speed step (0..31) the operator keys in on
  // each entry into Automatic (the CTA's keys; docs/clm14.md).
  std::string master_name;
  std::string master2_name;
  std::optional<int> test_step;
  Options options;
  for (const auto& [key, value] : spec.options) {
    const auto bad = [&](std::string what) {
      return std::unexpected(ConfigError{spec.file, spec.line, 0, fmt::format("controller.{}", key), std::move(what)});
    };
    if (key == "master_encoder") {
      master_name = value;
    } else if (key == "master_encoder2") {
      if (!settings->me2.used())
        return bad(fmt::format("master_encoder2 '{}': {} sets C006 = 0 (master encoder 2 not used)", value,
                               spec.parameters.string()));
      if (value.size() == 1 && value[0] >= '1' && value[0] <= '4')
        return bad(fmt::format("master_encoder2 '{}' is the name of CLM axis {}: give the encoder axis its own name",
                               value, value));
      master2_name = value;
    } else if (key == "test_speed_step") {
      int v = -1;
      const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
      if (ec != std::errc{} || end != value.data() + value.size() || v < 0 || v >= clm14::Controller::test_speed_steps)
        return bad(fmt::format("test_speed_step '{}': expected a step 0..31", value));
      if (!settings->axes[0].test_mode || settings->axes[0].mode != 5)
        return bad(fmt::format("test_speed_step needs the flying cutoff's test mode (A100 = x 5 x 1 x) in {}",
                               spec.parameters.string()));
      test_step = v;
    } else if (key == "homing") {
      if (value != "clm" && value != "drive")
        return bad(
            fmt::format("homing '{}': expected clm (the CLM's own homing options, Ax23-Ax25) or drive "
                        "(the drive's homing method)",
                        value));
      options.drive_homing = value == "drive";
    } else if (key == "wheel_window") {
      if (value != "iu" && value != "percent")
        return bad(fmt::format(
            "wheel_window '{}': expected iu (the Ax16 windows in IU per wheel revolution) or percent (in % of "
            "the wheel's feed constant C002 / C006)",
            value));
      options.wheel_window = value == "iu" ? WheelWindowUnit::iu : WheelWindowUnit::percent;
    } else if (key.size() == 7 && key.starts_with("marker") && key[6] >= '1' && key[6] <= '4') {
      MarkerSource& m = options.markers[static_cast<std::size_t>(key[6] - '1')];
      if (auto b = parse_bit(value); b && b->byte.area == Area::input) {
        m.input = *b;
      } else {
        std::int64_t n = 0;
        const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
        if (ec != std::errc{} || end != value.data() + value.size())
          return bad(
              fmt::format("{} '{}': expected the marker's count offset (an integer, increments of the "
                          "axis' encoder) or a CLM input address such as I1.05.0",
                          key, value));
        m.offset_inc = n;
      }
    } else {
      return bad(fmt::format(
          "unknown clm14 controller key '{}' (known: master_encoder, master_encoder2, test_speed_step, homing, "
          "marker1..marker4, wheel_window)",
          key));
    }
  }
  if (!master_name.empty()) {
    if (!settings->me1.used())
      return std::unexpected(
          ConfigError{spec.file, spec.line, 0, "controller.master_encoder",
                      fmt::format("master_encoder '{}': {} sets C002 = 0 (master encoder 1 not used)", master_name,
                                  spec.parameters.string())});
    for (int ax = 1; ax <= 4; ++ax)
      if (master_name == std::to_string(ax))
        return std::unexpected(ConfigError{
            spec.file, spec.line, 0, "controller.master_encoder",
            fmt::format("master_encoder '{}' is the name of CLM axis {}: give the encoder axis its own name",
                        master_name, ax)});
  }
  const Duration cycle = spec.cycle.value_or(
      std::chrono::duration_cast<Duration>(std::chrono::duration<double, std::milli>(settings->cycle_ms)));
  auto c = std::make_unique<RuntimeController>(*profile, std::move(params), cycle, options);
  c->test_step_ = test_step;
  for (int ax = 1; ax <= 4; ++ax) {
    const auto& as = settings->axes[static_cast<std::size_t>(ax - 1)];
    if (!as.enabled) continue;
    hc::ControllerAxis a;
    a.name = std::to_string(ax);
    a.units = "IU";
    a.config = make_axis_config(as, a.name);
    c->add_axis(std::move(a));
    ++c->clm_axes_;
  }
  if (!master_name.empty()) {
    // Master encoder 1 (C000 × 4 counts per C002 IU): a machine axis the scenario moves (the
    // material, the measuring wheel); the CLM reads its actual increments as the encoder count.
    hc::ControllerAxis a;
    a.name = master_name;
    a.units = "IU";
    a.config = master_encoder_config(settings->me1, settings->axes[0], master_name);
    c->add_axis(std::move(a));
    c->has_master_ = true;
  }
  if (!master2_name.empty()) {
    if (master2_name == master_name)
      return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.master_encoder2",
                                         fmt::format("master_encoder2 '{}' is master encoder 1's axis", master2_name)});
    // Master encoder 2 (C004 × 4 counts per C006 IU; the measuring wheel of axis 2): one more
    // machine axis, limits as master encoder 1's from axis 2 (axis 1 when axis 2 is disabled).
    hc::ControllerAxis a;
    a.name = master2_name;
    a.units = "IU";
    a.config = master_encoder_config(settings->me2, settings->axes[settings->axes[1].enabled ? 1 : 0], master2_name);
    c->add_axis(std::move(a));
    c->has_master2_ = true;
  }
  std::vector<std::pair<int, std::string>> lines;
  for (const auto& prg : spec.programs) {
    auto p = read_text(prg, spec, "program");
    if (!p) return std::unexpected(p.error());
    std::istringstream in(*p);
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      const std::string_view l = trim(line);
      if (l.empty() || l.front() == ';') continue;
      if (l.size() < 6 || l.substr(0, 4).find_first_not_of("0123456789") != std::string_view::npos || l[4] != ' ')
        return std::unexpected(
            ConfigError{prg.string(), n, 1, "program", fmt::format("'{}': expected 'NNNN MNEMONIC operands'", l)});
      lines.emplace_back(std::stoi(std::string(l.substr(0, 4))), std::string(trim(l.substr(5))));
    }
    if (auto r = c->model_.load_program(lines); !r)
      return std::unexpected(
          ConfigError{prg.string(), 0, 0, "program",
                      fmt::format("CLM error {:02X}: {}", static_cast<int>(r.error().error), r.error().message)});
  }
  return std::unique_ptr<hc::Controller>(std::move(c));
}

std::expected<hc::BitAddress, std::string> RuntimeController::resolve_bit(std::string_view text) const {
  if (auto named = hc::Controller::resolve_bit(text)) return named;
  auto a = hc::parse_clm_address(text);
  if (!a) return std::unexpected(a.error());
  return hc::to_bit_address(*a);
}

void RuntimeController::on_cycle(const CycleTime& cycle) noexcept {
  if (ports_.empty()) {
    for (std::size_t i = 0; i < clm_axes_; ++i) {
      ports_.push_back(std::make_unique<MotionAxisPort>(axis(i)));
      model_.attach_axis(static_cast<int>(i + 1), ports_.back().get());
    }
    if (has_master_) {
      master_ = std::make_unique<MotionMasterEncoder>(axis(clm_axes_));
      model_.attach_master_encoder(master_.get());
    }
    if (has_master2_) {
      master2_ = std::make_unique<MotionMasterEncoder>(axis(clm_axes_ + (has_master_ ? 1 : 0)));
      model_.attach_master_encoder2(master2_.get());
    }
  }
  // The runtime's image holds CLM group x byte yy at x * 64 + yy (io_address_clm.hpp).
  auto& im = model_.image();
  for (std::uint8_t s = 0; s < 3; ++s)
    for (std::uint8_t b = 0; b < io_bytes; ++b)
      im.set_byte({Area::input, s, b}, io().get(hc::ByteAddress{hc::IoArea::input, s * hc::clm_group_stride + b}));
  model_.cycle(cycle.now);
  if (test_step_ && model_.mode() == Mode::automatic && last_mode_ != Mode::automatic)
    model_.set_test_speed_step(*test_step_);  // the operator keys the test speed in
  last_mode_ = model_.mode();
  for (std::uint8_t s = 0; s < 3; ++s)
    for (std::uint8_t b = 0; b < io_bytes; ++b)
      io().set(hc::ByteAddress{hc::IoArea::output, s * hc::clm_group_stride + b}, im.byte({Area::output, s, b}));
  for (std::uint8_t g = 0; g < 7; ++g)
    for (std::uint8_t b = 0; b < marker_bytes; ++b)
      io().set(hc::ByteAddress{hc::IoArea::marker, g * hc::clm_group_stride + b}, im.byte({Area::marker, g, b}));
  const int e = model_.error();
  if (e != shown_error_) {
    // An axis' error (codes 40-6F / 70-9F / A0-CF / D0-FF, §11.1) is reported on that axis, so a
    // scenario expects it there (`{axis: "2", fault: "clm14.diagnostic:73"}`); 00-3F are the
    // whole controller's.
    const int clm_axis = e < 0x40 ? 0 : 1 + (e - 0x40) / 0x30;
    int axis_index = -1;
    for (std::size_t i = 0; i < axis_specs().size(); ++i)
      if (clm_axis != 0 && axis_specs()[i].name == std::to_string(clm_axis)) axis_index = static_cast<int>(i);
    if (const auto* cat = catalogue("diagnostic")) {
      if (shown_error_ != 0) (void)clear_error(*cat, shown_error_, shown_axis_);
      if (e != 0) raise(*cat, e, cycle.now, axis_index, model_.error_message());
    }
    shown_error_ = e;
    shown_axis_ = axis_index;
  }
}

std::optional<hc::DeviceErrorCode> RuntimeController::map_axis_fault(std::size_t axis, const hil::Fault&,
                                                                     const motion::AxisStatus&) const noexcept {
  // Supervision faults are the CLM's "Excess Pos Lag" of that axis (43/73/A3/D3); the model
  // raises and reports it itself, so the runtime keeps the motion fault as it is.
  (void)axis;
  return std::nullopt;
}

void register_clm14(ControllerRegistry& registry) {
  registry.add("clm14", [](const ControllerSpec& spec) { return RuntimeController::create(spec); });
}

}  // namespace hil::controllers::clm14
