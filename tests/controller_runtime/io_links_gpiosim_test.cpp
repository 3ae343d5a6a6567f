// SPDX-License-Identifier: MIT
// `io_links: - gpio:` on a real kernel GPIO chip (gpio-sim, in the VM harness:
// tests/vm/run-in-kernel.sh). The WF 725/726 axis' positive limit switch is line 4, its `moving`
// output line 7. The test pulls line 4 up at 100 ms of the run (sim_gpio4/pull) from an observer
// on the cycle thread, so the run stays on virtual time: the input edge reaches the image at the
// controller's next cycle, the WF reports 16, and line 7 shows the output (sim_gpio7/value).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "sim_registry.hpp"

namespace hil::runtime {
namespace {

using std::chrono::milliseconds;

class SimPins final : public RunObserver {
 public:
  explicit SimPins(std::string sysfs) : sysfs_(std::move(sysfs)) {}
  void on_cycle(Duration t, const Machine&) noexcept override {
    if (!pulled_ && t >= milliseconds(100)) {
      pull(4, true);
      pulled_ = true;
    }
    const bool moving = value(7);
    if (moving && first_high_ < Duration::zero()) first_high_ = t;
    if (!moving && first_high_ >= Duration::zero() && last_fall_ < Duration::zero()) last_fall_ = t;
  }
  void pull(int line, bool up) const noexcept {
    std::ofstream f(sysfs_ + "/sim_gpio" + std::to_string(line) + "/pull");
    f << (up ? "pull-up" : "pull-down");
  }
  [[nodiscard]] bool value(int line) const noexcept {
    std::ifstream f(sysfs_ + "/sim_gpio" + std::to_string(line) + "/value");
    int v = 0;
    f >> v;
    return v != 0;
  }
  Duration first_high_{-1}, last_fall_{-1};

 private:
  std::string sysfs_;
  bool pulled_ = false;
};

TEST(IoLinksGpioSim, LimitSwitchLineAndMovingOutputOnARealChip) {
  const char* chip = std::getenv("HIL_GPIOCHIP");
  const char* sysfs = std::getenv("HIL_GPIOSIM_SYSFS");
  if (chip == nullptr || *chip == '\0' || sysfs == nullptr || !std::filesystem::exists(sysfs))
    GTEST_SKIP() << "HIL_GPIOCHIP / HIL_GPIOSIM_SYSFS unset: no gpio-sim chip (run under tests/vm/run-in-kernel.sh)";
  SimPins pins(sysfs);
  pins.pull(4, false);
  auto s = parse_scenario(std::string(R"(
period: 1ms
controller: {device: wf725-726, parameters: wf725-axis-a.txt}
machine:
  axes:
    - name: A
      drive: {transport: sim, kv: 100, feedforward: 1.0}
io_links:
  - gpio: {chip: )") + chip + R"(, consumer: hil-io-test}
    inputs:
      limit_plus_A: {line: 4, bias: pull-down}
    outputs:
      moving_A: 7
program:
  - enable: A
  - move_velocity: {axis: A, velocity: 20}
    blocking: false
  - wait: 400ms
expect:
  - {io: limit_plus_A, first_edge: true, after: 100ms, by: 105ms}
  - {axis: A, fault: "wf725-726.traversing:16"}
)",
                          "examples/controllers/test.yaml");
  ASSERT_TRUE(s) << s.error().describe();
  RunOptions o;
  o.observers = {&pins};
  const auto r = run_scenario(*s, hil::testing::sim_registry(), o);
  pins.pull(4, false);
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->ok) << (r->failures.empty() ? "" : r->failures.front());
  ASSERT_EQ(r->device_errors.size(), 1U);
  EXPECT_EQ(r->device_errors[0].code, "16");
  EXPECT_GE(pins.first_high_, Duration::zero()) << "line 7 never showed moving_A";
  EXPECT_GT(pins.last_fall_, milliseconds(100)) << "moving_A dropped when the limit switch stopped the axis";
  EXPECT_LT(pins.last_fall_, milliseconds(400));
}

}  // namespace
}  // namespace hil::runtime
