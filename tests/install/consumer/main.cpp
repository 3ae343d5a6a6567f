// SPDX-License-Identifier: MIT
// Uses three installed hilbridge libraries: enables a simulated drive on virtual time, loads a
// Modbus register profile and a device profile from the installed share/hilbridge/.
// Usage: consumer <prefix>/share/hilbridge   (exit 0 when all three work)
#include <chrono>
#include <cstdio>
#include <string>

#include "hil/core/drive.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "hil/modbus/profile.hpp"
#include "hil/profiles/loader.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer <prefix>/share/hilbridge\n");
    return 2;
  }
  const std::string share = argv[1];

  hil::mocks::SimDrive drive{hil::mocks::SimDriveConfig{}};
  drive.request(hil::DriveRequest::enable);
  hil::CycleTime cycle;
  for (int i = 0; i < 100 && drive.feedback().state != hil::DriveState::operation_enabled; ++i) {
    cycle.now += cycle.period;
    drive.read(cycle);
    drive.write(cycle, hil::DriveCommand{});
  }
  if (drive.feedback().state != hil::DriveState::operation_enabled) {
    std::fprintf(stderr, "sim drive did not enable: %s\n", std::string(hil::to_string(drive.feedback().state)).c_str());
    return 1;
  }

  auto modbus = hil::modbus::load_profile(share + "/profiles/modbus/cia402.yaml");
  if (!modbus) {
    std::fprintf(stderr, "modbus profile: %s\n", modbus.error().describe().c_str());
    return 1;
  }
  auto device = hil::profiles::load_profile(share + "/profiles/devices/clm14.yaml");
  if (!device) {
    std::fprintf(stderr, "device profile: %s\n", device.error().describe().c_str());
    return 1;
  }
  std::printf("consumer: sim drive %s, modbus profile %s, device profile %s with %zu parameters\n",
              std::string(hil::to_string(drive.feedback().state)).c_str(), modbus->name.c_str(),
              (*device)->device.c_str(), (*device)->all_refs().size());
  return 0;
}
