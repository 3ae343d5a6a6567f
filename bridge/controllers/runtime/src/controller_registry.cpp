// SPDX-License-Identifier: MIT
#include "hil/controllers/controller_registry.hpp"

#include <fmt/format.h>

namespace hil::controllers {

void ControllerRegistry::add(std::string device, ControllerFactory factory) {
  factories_[std::move(device)] = std::move(factory);
}

std::expected<std::unique_ptr<Controller>, ConfigError> ControllerRegistry::create(const ControllerSpec& spec) const {
  const auto it = factories_.find(spec.device);
  if (it == factories_.end()) {
    std::string known;
    for (const auto& [name, f] : factories_) known += (known.empty() ? "" : ", ") + name;
    return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.device",
                                       fmt::format("unknown controller device '{}'; this hilbridge knows: {}",
                                                   spec.device, known.empty() ? "(none)" : known)});
  }
  return it->second(spec);
}

std::vector<std::string> ControllerRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, f] : factories_) out.push_back(name);
  return out;
}

bool ControllerRegistry::contains(std::string_view device) const {
  return factories_.contains(device);
}

}  // namespace hil::controllers
