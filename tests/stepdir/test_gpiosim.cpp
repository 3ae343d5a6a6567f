// SPDX-License-Identifier: MIT
// The libgpiod backend and the same StepDirDrive on a real kernel GPIO chip (gpio-sim), in the VM
// harness (tests/vm/run-in-kernel.sh). Lines: 0 step, 1 dir, 2 enable, 3 ready, 4 limit start,
// 5 limit end, 6 reference. The simulator side: sim_gpioK/value shows an output,
// sim_gpioK/pull (pull-up / pull-down) drives an input.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "drive_rig.hpp"
#include "hil/gpio/io/edge_writer.hpp"
#include "hil/gpio/linux/gpiod_lines.hpp"

namespace {

struct Chip {
  std::string name, sysfs;
};

std::optional<Chip> chip_or_skip_reason(std::string& reason) {
  const char* chip = std::getenv("HIL_GPIOCHIP");
  const char* sysfs = std::getenv("HIL_GPIOSIM_SYSFS");
  if (!chip || !*chip) {
    reason = "HIL_GPIOCHIP is unset: no gpio-sim chip (run under tests/vm/run-in-kernel.sh)";
    return std::nullopt;
  }
  if (!std::filesystem::exists(std::string("/dev/") + chip)) {
    reason = std::string("/dev/") + chip + " does not exist";
    return std::nullopt;
  }
  if (!sysfs || !std::filesystem::exists(sysfs)) {
    reason = "HIL_GPIOSIM_SYSFS is unset or missing: cannot drive the simulated inputs";
    return std::nullopt;
  }
  return Chip{chip, sysfs};
}

std::string sim_read(const Chip& c, int line, const char* attr) {
  std::ifstream f(c.sysfs + "/sim_gpio" + std::to_string(line) + "/" + attr);
  std::string s;
  f >> s;
  return s;
}

void sim_pull(const Chip& c, int line, bool up) {
  std::ofstream f(c.sysfs + "/sim_gpio" + std::to_string(line) + "/pull");
  f << (up ? "pull-up" : "pull-down");
}

#define REQUIRE_CHIP(var)                      \
  std::string skip_reason;                     \
  auto var = chip_or_skip_reason(skip_reason); \
  if (!var) GTEST_SKIP() << skip_reason

}  // namespace

TEST(GpioSim, OutputsShowInSimulatorAndPullsDriveInputs) {
  REQUIRE_CHIP(chip);
  using namespace hil::gpio;
  LineSpec out{"step", 0U, "", LineDirection::output, false, Bias::as_is, false};
  LineSpec out_low{"dir", 1U, "", LineDirection::output, true, Bias::as_is, false};  // active-low
  LineSpec in{"ready", 3U, "", LineDirection::input, false, Bias::as_is, false};
  auto lines = linux_gpiod::GpiodLines::open(chip->name, {out, out_low, in});
  ASSERT_TRUE(lines) << lines.error().message;
  auto& l = **lines;
  EXPECT_EQ(sim_read(*chip, 0, "value"), "0");
  EXPECT_EQ(sim_read(*chip, 1, "value"), "1");  // logical 0 on an active-low line = physical high
  ASSERT_FALSE(l.set_value(0, true));
  ASSERT_FALSE(l.set_value(1, true));
  EXPECT_EQ(sim_read(*chip, 0, "value"), "1");
  EXPECT_EQ(sim_read(*chip, 1, "value"), "0");
  sim_pull(*chip, 3, true);
  EXPECT_EQ(l.get_value(2).value_or(false), true);
  sim_pull(*chip, 3, false);
  EXPECT_EQ(l.get_value(2).value_or(true), false);
  EXPECT_TRUE(l.set_value(2, true));  // an input cannot be driven
  // Offsets outside the chip and unknown names are clear errors.
  LineSpec bad{"x", 4096U, "", LineDirection::output, false, Bias::as_is, false};
  auto e = linux_gpiod::GpiodLines::open(chip->name, {bad});
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("out of range"), std::string::npos);
  LineSpec named{"limit", std::nullopt, "hil-no-such-line", LineDirection::input, false, Bias::pull_up, false};
  auto n = linux_gpiod::GpiodLines::open(chip->name, {named});
  ASSERT_FALSE(n);
  EXPECT_NE(n.error().message.find("not found"), std::string::npos) << n.error().message;
  // The same line busy in a second request: a clear error, not a crash.
  auto busy = linux_gpiod::GpiodLines::open(chip->name, {out});
  ASSERT_FALSE(busy);
  EXPECT_NE(busy.error().message.find("request failed"), std::string::npos) << busy.error().message;
}

TEST(GpioSim, EdgeWriterOutputsEveryEdgeAndMeasuresItsTiming) {
  REQUIRE_CHIP(chip);
  using namespace hil::gpio;
  LineSpec out{"step", 0U, "", LineDirection::output, false, Bias::as_is, false};
  auto lines = linux_gpiod::GpiodLines::open(chip->name, {out});
  ASSERT_TRUE(lines) << lines.error().message;
  hil::SteadyClock clock;
  EdgeWriter w(**lines, clock);
  std::vector<Edge> edges;
  const std::int64_t t0 = clock.now().time_since_epoch().count() + 1'000'000;
  for (int i = 0; i < 500; ++i) {  // 500 pulses at 1 kHz, 100 us wide
    edges.push_back({t0 + i * 1'000'000LL, 0, true});
    edges.push_back({t0 + i * 1'000'000LL + 100'000, 0, false});
  }
  EXPECT_FALSE(w.write(edges));
  EXPECT_EQ(w.stats().edges, 1000U);
  EXPECT_EQ(w.stats().io_errors, 0U);
  EXPECT_EQ(sim_read(*chip, 0, "value"), "0");
  std::printf("gpio-sim writer: mean %.1f us, p99 <= %.1f us, max %.1f us, late %llu of %llu\n",
              w.stats().mean_error_ns() / 1000.0, static_cast<double>(w.stats().quantile_bound_ns(0.99)) / 1000.0,
              static_cast<double>(w.stats().max_error_ns) / 1000.0, static_cast<unsigned long long>(w.stats().late),
              static_cast<unsigned long long>(w.stats().edges));
}

TEST(GpioSim, StepDirDriveOnARealChip) {
  REQUIRE_CHIP(chip);
  sim_pull(*chip, 3, true);   // ready
  sim_pull(*chip, 4, false);  // limits NO, released
  sim_pull(*chip, 5, false);
  sim_pull(*chip, 6, false);
  DriveRig r("transport: stepdir\nchip: " + chip->name +
             "\nfmax_hz: 5000\nfss_hz: 200\naccel_hz_per_s: 50000\npulse_us: 30\n"
             "lines: {step: 0, dir: 1, enable: 2, ready: 3, limit_start: 4, limit_end: 5, reference: 6}\n"
             "writer: {spin_us: 500, late_us: 50, rt_priority: 10}\n");
  ASSERT_TRUE(r.drive);
  EXPECT_EQ(sim_read(*chip, 2, "value"), "1");  // reset asserted while disabled
  ASSERT_TRUE(r.enable());
  for (int i = 1; i <= 100; ++i) r.cycle(i * 2);  // 200 steps at 2 kHz
  for (int i = 0; i < 5; ++i) r.cycle(200);
  r.refresh();
  EXPECT_EQ(r.drive->feedback().position_inc, 200);
  auto rep = r.factory.finish(hil::CycleTime{r.clock.now(), r.period});  // drains the writer thread
  for (const auto& l : rep.lines) std::printf("%s\n", l.c_str());
  EXPECT_TRUE(rep.ok);
  const auto ws = r.axis().writer->stats();
  EXPECT_FALSE(r.axis().writer->realtime_error()) << "SCHED_FIFO as root in the VM";
  EXPECT_EQ(ws.edges, 2U * 200U + 1U);  // 200 pulses + the reset release
  EXPECT_EQ(ws.io_errors, 0U);
  EXPECT_EQ(sim_read(*chip, 0, "value"), "0");  // step idle
  EXPECT_EQ(sim_read(*chip, 2, "value"), "0");  // reset released
  // Limit end while moving forward: error 26.
  sim_pull(*chip, 5, true);
  r.cycle(210);
  r.refresh();
  EXPECT_EQ(r.drive->feedback().fault.code.value(), 26);
  // Ready lost: error 53 (the first error stays latched, so acknowledge first).
  sim_pull(*chip, 5, false);
  r.drive->request(hil::DriveRequest::fault_reset);
  r.cycle(r.drive->feedback().position_inc);
  sim_pull(*chip, 3, false);
  r.cycle(r.drive->feedback().position_inc);
  r.refresh();
  EXPECT_EQ(r.drive->feedback().fault.code.value(), 53);
  sim_pull(*chip, 3, true);
}
