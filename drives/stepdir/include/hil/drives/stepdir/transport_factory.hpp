// SPDX-License-Identifier: MIT
#pragma once
// TransportFactory "stepdir": builds StepDirDrive axes from scenario `drive:` blocks. Without
// `chip:` the lines are mocks (outputs recorded on the run's clock, limit/reference switches as a
// function of the steps output, ready scripted); with `chip: gpiochipN` they are libgpiod lines and
// the edges go out through the real-line writer thread. Every axis's edge stream is verified on the
// fly; finish() reports steps, the first timing violation (run fails with --verify-steps) and the
// writer's measured timing error.
//
// Teardown by ownership (docs/ARCHITECTURE.md, "Teardown"): each axis's lines, sink and writer
// (Axis) are shared by the factory and by the drive it hands out, which destroys the StepDirDrive
// before them (hil::ForwardingDrive), whatever order the run destroys its axes and factories in.

#include <memory>
#include <string>
#include <vector>

#include "hil/core/transport.hpp"

namespace hil::drives::stepdir {

class StepDirDrive;

class StepDirTransportFactory final : public TransportFactory {
 public:
  StepDirTransportFactory();
  ~StepDirTransportFactory() override;
  std::expected<DrivePtr, ConfigError> make_drive(const std::string& axis_name, const YAML::Node& drive_node,
                                                  RunEnvironment& env) override;
  TransportReport finish(const CycleTime& cycle) override;

  struct Axis;  ///< per-axis lines, sink, verifier (defined in axis.hpp)
  [[nodiscard]] const std::vector<std::shared_ptr<Axis>>& axes() const noexcept { return axes_; }

 private:
  std::vector<std::shared_ptr<Axis>> axes_;  ///< shared with the drives (their lines and sink)
  bool verify_ = false;
};

}  // namespace hil::drives::stepdir
