// SPDX-License-Identifier: MIT
// The IP247 module's axis on a real kernel GPIO chip (gpio-sim, in the VM harness
// tests/vm/run-in-kernel.sh; label kernel): the program of ip247_program_rig.hpp through the
// interface DB, the module's pulses output on chip lines 0 (step), 1 (dir), 2 (enable = RS),
// 3 (ready = BB, pulled up here), paced in real time by the edge writer; the step/dir verifier
// passes and the axis ends exactly where the same program puts it on mock lines (2.5 mm = 250
// pulses; test Ip247Controller.SameProgramSamePositionsOnMockLinesAndSim). Outside the VM it
// skips with the reason.
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "ip247_program_rig.hpp"

TEST(Ip247GpioSim, ProgramOnARealChipWithTheVerifierPassing) {
  const char* chip = std::getenv("HIL_GPIOCHIP");
  const char* sysfs = std::getenv("HIL_GPIOSIM_SYSFS");
  if (chip == nullptr || *chip == '\0' || !std::filesystem::exists(std::string("/dev/") + chip))
    GTEST_SKIP() << "HIL_GPIOCHIP is unset or not a device: no gpio-sim chip (run under tests/vm/run-in-kernel.sh)";
  if (sysfs == nullptr || !std::filesystem::exists(sysfs))
    GTEST_SKIP() << "HIL_GPIOSIM_SYSFS is unset or missing: cannot drive the ready input (BB)";
  const auto sim = [&](int line, const char* attr) {
    return std::string(sysfs) + "/sim_gpio" + std::to_string(line) + "/" + attr;
  };
  std::ofstream(sim(3, "pull")) << "pull-up";  // BB: the power section is on
  const std::string drive = std::string("{transport: stepdir, profile: motion, chip: ") + chip +
                            ", fmax_hz: 20000, fss_hz: 500, accel_hz_per_s: 200000, pulse_us: 10, "
                            "lines: {step: 0, dir: 1, enable: 2, ready: 3}, "
                            "writer: {spin_us: 500, late_us: 50, rt_priority: 10}}";
  const auto o = ip247_rig::run("gpiosim", drive);
  for (const auto& f : o.failures) ADD_FAILURE() << f;
  for (const auto& l : o.report) {
    std::printf("%s\n", l.c_str());
    EXPECT_EQ(l.find("VIOLATION"), std::string::npos) << l;
  }
  EXPECT_TRUE(o.ok);
  EXPECT_TRUE(o.verified) << "the step/dir verifier did not report";
  EXPECT_EQ(o.final_position_mm, 2.5);  // 250 pulses, as on mock lines
  std::string v;
  std::ifstream(sim(0, "value")) >> v;
  EXPECT_EQ(v, "0");  // step line idle (positive edge: idle low)
}
