// SPDX-License-Identifier: MIT
#pragma once
// The parameter-only controller of a device: its axes configured from the device's parameter
// file (one mapping per device, docs/controllers.md "parameter mapping"), the motion core's
// supervision faults raised in the device's numbers, and a small generic I/O image per axis. It
// runs no program: the scenario commands the axes. Device libraries with an interpreter (CLM1.4,
// S5) register their own controller under the same device name and may reuse the mappings.
//
// Generic image of the parameter controller, per axis i (0-based, in axis order):
//   inputs  byte i: bit 0 limit_minus_<axis>, bit 1 limit_plus_<axis>, bit 2 reference_cam_<axis>
//   outputs byte i: bit 0 in_position_<axis>, bit 1 moving_<axis>, bit 2 error_<axis>
//   markers byte 0: bit 0 device_error (any device error latched)

#include <expected>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hil/controllers/controller.hpp"
#include "hil/controllers/controller_registry.hpp"
#include "hil/controllers/parameter_file.hpp"
#include "hil/core/config_error.hpp"

namespace hil::controllers {

/// What a device's parameters give: its axes and its controller cycle.
struct DeviceAxes {
  std::vector<ControllerAxis> axes;
  Duration cycle{std::chrono::milliseconds(4)};
};

/// The numbers of a device for the faults the runtime reports (empty optional: no device number).
struct DeviceFaultMap {
  std::string catalogue;  ///< catalogue id in the profile ("traversing", "module", "diagnostic")
  /// Device number for `fault` on axis index `axis`; `negative` = the side of a limit fault.
  std::function<std::optional<int>(std::size_t axis, const std::error_code& fault, bool negative)> code;
};

/// Axis mappings, pure: parameters in, axes (with warnings for what the core cannot honour) out.
/// Errors name the parameter file and parameter.
[[nodiscard]] std::expected<DeviceAxes, ConfigError> wf725_axes(const LoadedParameters& p, const ControllerSpec& spec);
[[nodiscard]] std::expected<DeviceAxes, ConfigError> ip247_axes(const LoadedParameters& p, const ControllerSpec& spec);
[[nodiscard]] std::expected<DeviceAxes, ConfigError> clm14_axes(const LoadedParameters& p, const ControllerSpec& spec);
[[nodiscard]] DeviceFaultMap wf725_faults();
[[nodiscard]] DeviceFaultMap ip247_faults();
[[nodiscard]] DeviceFaultMap clm14_faults();

class ParameterController final : public Controller {
 public:
  ParameterController(LoadedParameters parameters, DeviceAxes axes, DeviceFaultMap faults);

  [[nodiscard]] std::expected<BitAddress, std::string> resolve_bit(std::string_view text) const override;

 protected:
  void on_cycle(const CycleTime& cycle) noexcept override;
  [[nodiscard]] std::optional<DeviceErrorCode> map_axis_fault(std::size_t axis, const hil::Fault& fault,
                                                              const motion::AxisStatus& status) const noexcept override;

 private:
  DeviceFaultMap faults_;
  const profiles::ErrorCatalogue* catalogue_ = nullptr;
};

/// A registry with the ParameterController of clm14, ip247 and wf725-726.
[[nodiscard]] ControllerRegistry builtin_controllers();

}  // namespace hil::controllers
