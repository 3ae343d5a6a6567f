// SPDX-License-Identifier: MIT
#pragma once
// One IP247 program (G10 flying change, dwell, M functions, G91) run through the scenario runner on
// virtual time with the module's axis on a given drive: BA5 set reference point and BA8 through the
// interface DB, then the final actual value, the M output and the verifier's report. Shared by
// test_ip247_controller.cpp (mock step/dir lines and the sim plant) and test_ip247_gpiosim.cpp (the
// gpio-sim chip in the VM, label kernel): the same program must give the same positions on each.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/mocks/sim_transport.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"

namespace ip247_rig {

namespace fs = std::filesystem;

/// 10 um/pulse: X5 = 500 pulses at 1200 mm/min (2 kHz), flying change to X10 at 600 mm/min, dwell
/// 0.2 s, back 7.5 mm: 2.5 mm = 250 pulses.
inline const char* const program =
    "%4 gpio-sim\nN10 G10 X5 F1200 M10\nN20 X10 F600 M11\nN30 G04 F2\nN40 G91 X-7.5 F1200 M12\nN50 M02\n";

inline std::string scenario(const std::string& drive) {
  return R"(name: ip247 program on one drive
period: 1ms
controller:
  device: ip247
  parameters: ip247-md-linear.s5db
  programs: prog4.txt
machine:
  axes:
    - name: "1"
      drive: )" +
         drive + R"(
program:
  - plc: {write: {db: 10, dw: 0, value: 0x0501}}
  - plc: {write: {db: 10, dw: 4, bit: 0}}
  - plc: {wait: {db: 10, dw: 4, value: 0}}
    timeout: 2s
  - plc: {write: {db: 10, dw: 0, value: 0x0804}}
  - plc: {write: {db: 10, dw: 4, bit: 0}}
  - plc: {expect: {db: 10, dw: 11, value: 0x080A}}
  - plc: {wait: {db: 10, dw: 11, dr: 12}}
    timeout: 5s
  - plc: {wait: {db: 10, dw: 12, bit: 15}}
    timeout: 5s
  - plc: {expect: {db: 10, dw: 5, dd: 2500}}
  - plc: {expect: {db: 10, dw: 11, value: 0x0802}}
  - plc: {expect: {db: 10, dw: 12, dr: 0}}
  - wait: 100ms
expect:
  - {axis: "1", no_fault: true}
)";
}

struct Outcome {
  bool ok = false;
  double final_position_mm = 0.0;
  bool verified = false;  ///< the step/dir verifier reported "timing rules held"
  std::vector<std::string> failures;
  std::vector<std::string> report;
};

inline Outcome run(const std::string& name, const std::string& drive) {
  const fs::path dir = fs::temp_directory_path() / ("hil_ip247_rig_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::copy_file(fs::absolute("examples/controllers/ip247-md-linear.s5db"), dir / "ip247-md-linear.s5db",
                fs::copy_options::overwrite_existing);
  std::ofstream(dir / "prog4.txt") << program;
  const fs::path file = dir / (name + ".yaml");
  std::ofstream(file) << scenario(drive);
  Outcome o;
  auto s = hil::runtime::load_scenario(file);
  if (!s) {
    o.failures.push_back(s.error().describe());
    return o;
  }
  hil::TransportRegistry registry;
  registry.add("sim", [] { return hil::mocks::make_sim_transport(); });
  registry.add("stepdir", [] { return std::make_unique<hil::drives::stepdir::StepDirTransportFactory>(); });
  hil::runtime::RunOptions opts;
  opts.virtual_time = true;
  opts.verify_steps = true;
  auto r = hil::runtime::run_scenario(*s, registry, opts);
  if (!r) {
    o.failures.push_back(r.error().describe());
    return o;
  }
  o.ok = r->ok;
  o.failures = r->failures;
  if (!r->axes.empty()) o.final_position_mm = r->axes[0].final_position;
  for (const auto& rep : r->reports)
    for (const auto& l : rep.report.lines) {
      o.report.push_back(l);
      o.verified = o.verified || l.find("timing rules held") != std::string::npos;
    }
  return o;
}

}  // namespace ip247_rig
