// SPDX-License-Identifier: MIT
// CLI module `sim`: registers the `sim` transport (hil::mocks::SimDrive on the plant model), the
// default for scenarios with no hardware.
#include "hil/cli/context.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace hil::cli {
namespace {

class SimTransport final : public TransportFactory {
 public:
  std::expected<DrivePtr, ConfigError> make_drive(const std::string& axis_name, const YAML::Node& drive_node,
                                                  RunEnvironment& env) override {
    auto config = mocks::parse_sim_drive_config(drive_node, yaml::Where{env.source_file, env.drive_path(axis_name)});
    if (!config) return std::unexpected(config.error());
    config->name = axis_name;
    return std::make_unique<mocks::SimDrive>(std::move(*config));
  }
};

}  // namespace

void register_sim(Context& ctx) {
  ctx.transports.add("sim", [] { return std::make_unique<SimTransport>(); });
}

}  // namespace hil::cli
