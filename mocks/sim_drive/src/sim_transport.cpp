// SPDX-License-Identifier: MIT
#include "hil/mocks/sim_transport.hpp"

#include "hil/config/yaml_config.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace hil::mocks {
namespace {

class SimTransport final : public TransportFactory {
 public:
  std::expected<DrivePtr, ConfigError> make_drive(const std::string& axis_name, const YAML::Node& drive_node,
                                                  RunEnvironment& env) override {
    auto config = parse_sim_drive_config(drive_node, yaml::Where{env.source_file, env.drive_path(axis_name)});
    if (!config) return std::unexpected(config.error());
    config->name = axis_name;
    return std::make_unique<SimDrive>(std::move(*config));
  }
};

}  // namespace

std::unique_ptr<TransportFactory> make_sim_transport() {
  return std::make_unique<SimTransport>();
}

}  // namespace hil::mocks
