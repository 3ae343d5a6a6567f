// SPDX-License-Identifier: MIT
#pragma once
// Which device name builds which controller. A scenario's `controller: {device: ...}` is looked
// up here; each device library registers one factory (a device model with programs replaces the
// parameter-only controller of builtin_controllers() by registering under the same name).
// Thread: configuration time only.

#include <expected>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hil/controllers/controller.hpp"
#include "hil/core/config_error.hpp"

namespace hil::controllers {

/// Builds a controller from the scenario's block. Errors name the scenario file and line (or the
/// parameter file's line for a parameter problem) and say what to do.
using ControllerFactory = std::function<std::expected<std::unique_ptr<Controller>, ConfigError>(const ControllerSpec&)>;

class ControllerRegistry {
 public:
  /// Registers (or replaces) the factory of `device`.
  void add(std::string device, ControllerFactory factory);
  /// Builds spec.device's controller; an unknown device is a ConfigError listing the known ones.
  [[nodiscard]] std::expected<std::unique_ptr<Controller>, ConfigError> create(const ControllerSpec& spec) const;
  [[nodiscard]] std::vector<std::string> names() const;
  [[nodiscard]] bool contains(std::string_view device) const;

 private:
  std::map<std::string, ControllerFactory, std::less<>> factories_;
};

}  // namespace hil::controllers
