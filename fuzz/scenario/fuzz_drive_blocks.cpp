// SPDX-License-Identifier: MIT
// Scenario drive blocks: the first byte picks the transport (sim, stepdir), the rest is the YAML
// of the block. Any bytes give a drive or a ConfigError naming the key; never a crash, an escaping
// exception or a hang. A drive that builds is enabled and moved for 50 cycles on virtual time, so
// every accepted number (a plant gain, a ramp, a timing) must keep a cycle finite and bounded.
#include <cstdint>
#include <cstdlib>
#include <string>

#include <yaml-cpp/yaml.h>

#include "hil/core/clock.hpp"
#include "hil/core/transport.hpp"
#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace {

void exercise(hil::Drive& drive, hil::VirtualClock& clock) {
  const hil::Duration period = std::chrono::milliseconds(1);
  drive.request(hil::DriveRequest::enable);
  for (int i = 0; i < 50; ++i) {
    const hil::CycleTime t{clock.now(), period};
    drive.read(t);
    drive.write(t, hil::DriveCommand{hil::CommandMode::position, 40 * i, 40'000.0, 0.0});
    clock.advance(period);
  }
  (void)drive.feedback();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  YAML::Node node;
  try {
    node = YAML::Load(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  } catch (const YAML::Exception&) {
    return 0;  // not YAML: the scenario loader reports it before a drive block is read
  }
  if (!node.IsMap()) return 0;
  const hil::yaml::Where where{"fuzz.yaml", "machine.axes[0].drive"};
  hil::VirtualClock clock;
  if (data[0] % 2 == 0) {
    auto c = hil::mocks::parse_sim_drive_config(node, where);
    if (!c) {
      if (c.error().message.empty()) std::abort();
      return 0;
    }
    hil::mocks::SimDrive drive(*c);
    exercise(drive, clock);
  } else {
    hil::RunEnvironment env{clock, true, nullptr, "fuzz.yaml", std::chrono::milliseconds(1), false, {}};
    env.verify_edge_streams = true;
    hil::drives::stepdir::StepDirTransportFactory factory;
    auto d = factory.make_drive("x", node, env);
    if (!d) {
      if (d.error().message.empty()) std::abort();
      return 0;
    }
    exercise(**d, clock);
    (void)factory.finish(hil::CycleTime{clock.now(), std::chrono::milliseconds(1)});
  }
  return 0;
}
