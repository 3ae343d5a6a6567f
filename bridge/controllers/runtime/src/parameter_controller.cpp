// SPDX-License-Identifier: MIT
#include "hil/controllers/parameter_controller.hpp"

#include <fmt/format.h>

#include "hil/controllers/io_address_clm.hpp"
#include "hil/controllers/io_address_s5.hpp"

namespace hil::controllers {
namespace {

IoLayout layout_for(std::size_t axes) {
  const auto n = static_cast<std::uint32_t>(std::max<std::size_t>(axes, 1));
  return IoLayout{{n, n, 1, 0}};
}

}  // namespace

ParameterController::ParameterController(LoadedParameters parameters, DeviceAxes axes, DeviceFaultMap faults)
    : Controller(parameters.profile, std::move(parameters.set), layout_for(axes.axes.size()), axes.cycle),
      faults_(std::move(faults)) {
  catalogue_ = catalogue(faults_.catalogue);
  for (std::size_t i = 0; i < axes.axes.size(); ++i) {
    auto a = std::move(axes.axes[i]);
    const auto byte = static_cast<std::uint32_t>(i);
    const BitAddress minus{IoArea::input, byte, 0}, plus{IoArea::input, byte, 1}, cam{IoArea::input, byte, 2};
    (void)io().name_bit("limit_minus_" + a.name, minus);
    (void)io().name_bit("limit_plus_" + a.name, plus);
    (void)io().name_bit("reference_cam_" + a.name, cam);
    (void)io().name_bit("in_position_" + a.name, {IoArea::output, byte, 0});
    (void)io().name_bit("moving_" + a.name, {IoArea::output, byte, 1});
    (void)io().name_bit("error_" + a.name, {IoArea::output, byte, 2});
    a.limit_switches.negative = minus;
    a.limit_switches.positive = plus;
    if (a.reference) a.reference->cam = cam;
    add_axis(std::move(a));
  }
  (void)io().name_bit("device_error", {IoArea::marker, 0, 0});
}

std::expected<BitAddress, std::string> ParameterController::resolve_bit(std::string_view text) const {
  if (auto a = io().find_bit(text)) return *a;
  // The device's own notation over the generic image (byte i = axis i).
  if (device() == "clm14") {
    if (auto c = parse_clm_address(text)) return to_bit_address(*c);
  } else if (device() == "ip247" || device() == "wf725-726") {
    if (auto s = parse_s5_address(text); s && s->is_bit()) {
      if (auto b = to_bit_address(*s)) return *b;
    }
  }
  std::string names;
  for (const auto& s : io().signals()) names += (names.empty() ? "" : ", ") + s.name;
  return std::unexpected(fmt::format("'{}' is neither an I/O name of the {} controller ({}) nor a {} address", text,
                                     device(), names, device() == "clm14" ? "CLM" : "S5"));
}

void ParameterController::on_cycle(const CycleTime&) noexcept {
  for (std::size_t i = 0; i < axis_count(); ++i) {
    const auto& st = axis(i).status();
    const auto byte = static_cast<std::uint32_t>(i);
    io().set(BitAddress{IoArea::output, byte, 0}, st.in_position);
    io().set(BitAddress{IoArea::output, byte, 1}, st.state == motion::AxisState::moving);
    io().set(BitAddress{IoArea::output, byte, 2}, errors().blocks_motion(static_cast<int>(i)));
  }
  io().set(BitAddress{IoArea::marker, 0, 0}, errors().any());
}

std::optional<DeviceErrorCode> ParameterController::map_axis_fault(std::size_t i, const hil::Fault& fault,
                                                                   const motion::AxisStatus& status) const noexcept {
  if (catalogue_ == nullptr || !faults_.code) return std::nullopt;
  bool negative = fault.code == ControllerFault::hard_limit_negative;
  if (fault.code == hil::MotionFault::software_limit) {
    // The side: the nearer limit (the axis stopped on it).
    const auto& c = axis_specs()[i].config;
    const double to_min = c.soft_limit_min ? std::abs(status.position - *c.soft_limit_min) : 1e300;
    const double to_max = c.soft_limit_max ? std::abs(status.position - *c.soft_limit_max) : 1e300;
    negative = to_min < to_max;
  }
  const auto code = faults_.code(i, fault.code, negative);
  if (!code) return std::nullopt;
  return DeviceErrorCode{catalogue_, *code};
}

namespace {

ControllerFactory factory(std::expected<DeviceAxes, ConfigError> (*axes)(const LoadedParameters&,
                                                                         const ControllerSpec&),
                          DeviceFaultMap (*faults)()) {
  return [axes, faults](const ControllerSpec& spec) -> std::expected<std::unique_ptr<Controller>, ConfigError> {
    if (!spec.programs.empty()) {
      return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.programs",
                                         fmt::format("this hilbridge's {} controller runs no programs (parameters "
                                                     "only); remove 'programs:'",
                                                     spec.device)});
    }
    for (const auto& [key, value] : spec.options) {
      if (key != "axis" && key != "encoder_multiplication") {
        return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller." + key,
                                           fmt::format("unknown controller key '{}' (known: device, parameters, "
                                                       "programs, cycle, axis, encoder_multiplication)",
                                                       key)});
      }
    }
    auto loaded = load_parameter_file(spec.device, spec.parameters);
    if (!loaded) return std::unexpected(loaded.error());
    auto mapped = axes(*loaded, spec);
    if (!mapped) return std::unexpected(mapped.error());
    if (spec.cycle) mapped->cycle = *spec.cycle;
    return std::make_unique<ParameterController>(std::move(*loaded), std::move(*mapped), faults());
  };
}

}  // namespace

ControllerRegistry builtin_controllers() {
  ControllerRegistry r;
  r.add("clm14", factory(&clm14_axes, &clm14_faults));
  r.add("ip247", factory(&ip247_axes, &ip247_faults));
  r.add("wf725-726", factory(&wf725_axes, &wf725_faults));
  return r;
}

}  // namespace hil::controllers
