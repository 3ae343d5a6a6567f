// SPDX-License-Identifier: MIT
// CLM1.4 measuring-wheel mode (§7.2, digest §5.9): Ax00 modes 3/4 against mode 0 with the feed
// rolls slipping on the material, Ax31, Ax16 (4C/7C, Tolerance 2), V047/V048, the option-2 digit.
#include <gtest/gtest.h>

#include <cmath>

#include "rig.hpp"

namespace hil::controllers::clm14::testing {
namespace {

using namespace std::chrono_literals;

/// The material under the feed rolls, counted by a measuring wheel: it moves `slip` IU per IU of
/// the motor (1 = no slip, 0 = the wheel is lifted), plus whatever the test pulls it by. The
/// encoder has 250 counts per IU (C000 1250 pulses × 4 per C002 20 IU).
class SlipWheel final : public MasterEncoderPort {
 public:
  explicit SlipWheel(const motion::Axis& motor) : motor_(motor) {}
  [[nodiscard]] std::uint32_t count() const override {
    return static_cast<std::uint32_t>(static_cast<std::uint64_t>(std::llround(wheel_iu * counts_per_iu)));
  }
  /// After each cycle: the material follows the motor's travel of that cycle.
  void advance() {
    const double m = motor_.status().position;
    if (have_) wheel_iu += slip * (m - last_);
    last_ = m;
    have_ = true;
  }
  double slip = 1.0;
  double wheel_iu = 0.0;
  static constexpr double counts_per_iu = 250.0;

 private:
  const motion::Axis& motor_;
  double last_ = 0.0;
  bool have_ = false;
};

constexpr double count_iu = 1.0 / SlipWheel::counts_per_iu;  // one wheel count, 0.004 IU

struct WheelRig {
  /// Axis 1 (and axis 2 with `axes` = 2) in Ax00 mode `mode` with the wheel(s) attached.
  explicit WheelRig(int mode, std::map<std::string, std::string> extra = {}, int axes = 1, Options o = {})
      : r({}, axes, o) {
    const std::string ax00 = fmt_mode(mode);
    r.params["A100"] = ax00;
    r.params["C000"] = "01250 0000";
    r.params["C001"] = "5 0 00 0 0 0";
    r.params["C002"] = "0020.00000";
    if (axes == 2) {
      r.params["A200"] = ax00;
      r.params["C004"] = "01250 0000";
      r.params["C005"] = "5 0 00 0 0 0";
      r.params["C006"] = "0020.00000";
    }
    for (auto& [k, v] : extra) r.params[k] = v;
    for (int ax = 1; ax <= axes; ++ax)
      wheels.push_back(std::make_unique<SlipWheel>(*r.motion_axes[static_cast<std::size_t>(ax - 1)]));
    r.clm.attach_master_encoder(wheels[0].get());
    if (axes == 2) r.clm.attach_master_encoder2(wheels[1].get());
  }
  static std::string fmt_mode(int mode) { return "1 " + std::to_string(mode) + " 0 0 0"; }
  void cycle() {
    r.cycle();
    for (auto& w : wheels) w->advance();
  }
  void run_for(Duration d) {
    const TimePoint end = r.now + d;
    while (r.now < end) cycle();
  }
  template <class F>
  bool run_until(F done, Duration limit = 20s) {
    const TimePoint end = r.now + limit;
    while (r.now < end) {
      cycle();
      if (done()) return true;
    }
    return false;
  }
  void start() {
    run_for(20ms);
    r.set(sys::automatic, true);
    cycle();
    cycle();
    r.set(sys::start, true);
    cycle();
    r.set(sys::start, false);
    cycle();
  }
  /// Run the program to line `line` and then until the motor stands (1 s).
  void run_to(int line) {
    ASSERT_TRUE(run_until([&] { return r.clm.task(1).pc == line; })) << "task 1 at " << r.clm.task(1).pc;
    run_for(1s);
  }
  Rig r;
  std::vector<std::unique_ptr<SlipWheel>> wheels;
};

/// Two feeds of 100 IU; the second after I1.00.6.
const std::vector<std::pair<int, std::string>> two_feeds{
    {0, "PSI 1 +000100.000 999"}, {1, "AKN I1.00.6 1"}, {2, "PSI 1 +000100.000 999"}, {3, "JMP 0003"}};

TEST(ClmMeasuringWheel, Mode0FeedsOnTheMotorAndTheMaterialFallsShort) {
  WheelRig w(0);
  w.wheels[0]->slip = 0.98;
  w.r.program(two_feeds);
  w.r.set(bit("I1.00.6"), true);
  w.start();
  w.run_to(3);
  EXPECT_EQ(w.r.clm.error(), 0);
  EXPECT_NEAR(w.r.pos(1), 200.0, 0.002);
  EXPECT_NEAR(w.wheels[0]->wheel_iu, 196.0, 0.002);  // 2 % slip: 4 IU of material missing
  EXPECT_FALSE(w.r.clm.wheel_active(1));
}

TEST(ClmMeasuringWheel, Mode3ClosesTheLoopOnTheWheel) {
  WheelRig w(3);
  w.wheels[0]->slip = 0.98;
  w.r.program(two_feeds);
  w.start();
  EXPECT_TRUE(w.r.clm.wheel_active(1));
  w.run_to(1);
  EXPECT_NEAR(w.wheels[0]->wheel_iu, 100.0, count_iu + 0.0013);  // one wheel count + half a motor increment
  EXPECT_NEAR(w.r.pos(1), 100.0, count_iu + 0.0013);             // the axis position is the wheel's
  EXPECT_NEAR(w.r.clm.motor_position(1), 100.0 / 0.98, 0.006);   // the motor ran the slip out
  EXPECT_NEAR(to_double(w.r.clm.variable(47)), w.r.clm.motor_position(1), 1e-6);  // V047
  w.r.set(bit("I1.00.6"), true);
  w.run_to(3);
  EXPECT_EQ(w.r.clm.error(), 0);
  EXPECT_NEAR(w.wheels[0]->wheel_iu, 200.0, count_iu + 0.0013);
  EXPECT_NEAR(w.r.clm.motor_position(1), 200.0 / 0.98, 0.006);
  EXPECT_NEAR(to_double(w.r.clm.variable(100)), w.r.pos(1), 1e-6);  // V100: the wheel's position
}

TEST(ClmMeasuringWheel, Mode3HoldsTheWheelOnTheTargetAfterTheMove) {
  WheelRig w(3);
  w.r.program({{0, "PSI 1 +000050.000 500"}, {1, "JMP 0001"}});
  w.start();
  w.run_to(1);
  EXPECT_NEAR(w.wheels[0]->wheel_iu, 50.0, count_iu + 0.0013);
  w.wheels[0]->wheel_iu -= 2.0;  // the material is pulled back 2 IU under the standing rolls
  w.run_for(1s);
  EXPECT_NEAR(w.wheels[0]->wheel_iu, 50.0, count_iu + 0.0013);  // the motor fed it forward again
  EXPECT_NEAR(w.r.clm.motor_position(1), 52.0, count_iu + 0.0013);
}

TEST(ClmMeasuringWheel, Mode4CorrectsUntilAx27AndCarriesTheRestToTheNextMove) {
  WheelRig w(4, {{"A127", "M2.00.0 0000.500"}});
  w.wheels[0]->slip = 0.98;
  w.r.program(two_feeds);
  w.start();
  w.run_to(1);
  // The correction ends 0.5 IU before the target; the last 0.5 IU of the motor move slip by 2 %.
  const double first = w.wheels[0]->wheel_iu;
  EXPECT_LT(first, 100.0 - 0.008);
  EXPECT_GT(first, 100.0 - 0.010 - count_iu);
  w.r.set(bit("I1.00.6"), true);
  w.run_to(3);
  EXPECT_EQ(w.r.clm.error(), 0);
  // The first move's residual went into the second: 200 less one residual, not two.
  const double second = w.wheels[0]->wheel_iu;
  EXPECT_LT(second, 200.0 - 0.008);
  EXPECT_GT(second, 200.0 - 0.010 - count_iu);
  EXPECT_NEAR(w.r.pos(1), second, count_iu);
}

TEST(ClmMeasuringWheel, Mode4LeavesTheSlipOfTheLastWindowUncorrected) {
  WheelRig w(4, {{"A127", "M2.00.0 0005.000"}});
  w.wheels[0]->slip = 0.98;
  w.r.program(two_feeds);
  w.start();
  w.run_to(1);
  EXPECT_NEAR(w.wheels[0]->wheel_iu, 100.0 - 0.1, 0.01);  // 2 % of the last 5 IU
  w.r.set(bit("I1.00.6"), true);
  w.run_to(3);
  EXPECT_NEAR(w.wheels[0]->wheel_iu, 200.0 - 0.1, 0.01);  // not 0.2: the residual went into the second feed
}

TEST(ClmMeasuringWheel, Mode3WithTheOption2DigitIsOption2) {
  WheelRig w(3, {{"A100", "1 3 0 0 1"}, {"A127", "M2.00.0 0000.500"}});
  w.wheels[0]->slip = 0.98;
  w.r.program(two_feeds);
  w.start();
  w.run_to(1);
  EXPECT_LT(w.wheels[0]->wheel_iu, 100.0 - 0.008);
}

TEST(ClmMeasuringWheel, Ax31SwitchesTheWheelInAutomaticOnly) {
  WheelRig w(3, {{"A131", "I1.00.7"}});
  w.wheels[0]->slip = 0.98;
  w.r.program({{0, "PSI 1 +000100.000 999"}, {1, "AKN I1.00.6 1"}, {2, "PSI 1 +000100.000 999"}, {3, "JMP 0003"}});
  w.start();
  EXPECT_FALSE(w.r.clm.wheel_active(1));  // Ax31 input off: the motor closes the loop
  w.run_to(1);
  EXPECT_NEAR(w.wheels[0]->wheel_iu, 98.0, 0.002);
  EXPECT_NEAR(w.r.pos(1), 100.0, 0.002);
  w.r.set(bit("I1.00.7"), true);
  w.r.set(bit("I1.00.6"), true);
  w.run_to(3);
  EXPECT_TRUE(w.r.clm.wheel_active(1));
  // the second feed is measured on the wheel: 100 IU more material
  EXPECT_NEAR(w.wheels[0]->wheel_iu, 198.0, count_iu + 0.0013);
  EXPECT_NEAR(w.r.pos(1), 200.0, count_iu + 0.0013);
  w.r.set(sys::automatic, false);  // Manual: always the motor encoder
  w.cycle();
  w.cycle();
  EXPECT_FALSE(w.r.clm.wheel_active(1));
  EXPECT_NEAR(w.r.pos(1), 200.0, count_iu + 0.0013);  // the position stays where it was
}

TEST(ClmMeasuringWheel, LiftedWheelIsError4CAfterAx16Window1) {
  WheelRig w(3, {{"A116", "05 02 Q1.00.5"}});
  w.r.program({{0, "CON 1 1 +500"}, {1, "JMP 0001"}});
  w.start();
  ASSERT_TRUE(w.run_until([&] { return w.r.clm.motor_position(1) > 7.0; }));
  EXPECT_EQ(w.r.clm.error(), 0);
  const double lifted_at = w.r.clm.motor_position(1);
  w.wheels[0]->slip = 0.0;
  double at_error = 0.0;
  ASSERT_TRUE(w.run_until([&] {
    at_error = w.r.clm.motor_position(1);
    return w.r.clm.error() != 0;
  }));
  EXPECT_EQ(w.r.clm.error(), 0x4C);
  // 5 IU of motor travel without the wheel, seen in the cycle after (50 IU/s: 0.1 IU per cycle)
  EXPECT_GT(at_error - lifted_at, 5.0);
  EXPECT_LT(at_error - lifted_at, 5.0 + 0.25);
}

TEST(ClmMeasuringWheel, Tolerance2OutputAndPercentWindows) {
  Options o;
  o.wheel_window = WheelWindowUnit::percent;
  // window 1: 25 % of 20 IU = 5 IU; window 2: 10 % = 2 IU per wheel revolution
  WheelRig w(3, {{"A116", "25 10 Q1.00.5"}}, 1, o);
  w.wheels[0]->slip = 0.98;  // 20.41 IU of motor per 20 IU of wheel: 0.41 IU
  w.r.program({{0, "CON 1 1 +500"}, {1, "JMP 0001"}});
  w.start();
  w.run_for(2s);
  EXPECT_EQ(w.r.clm.error(), 0);
  EXPECT_FALSE(w.r.get(bit("Q1.00.5")));
  w.wheels[0]->slip = 0.85;  // 23.53 IU of motor per revolution: 3.53 IU > 2, < 5
  w.run_for(2s);
  EXPECT_EQ(w.r.clm.error(), 0);
  EXPECT_TRUE(w.r.get(bit("Q1.00.5")));
  w.wheels[0]->slip = 0.98;  // one whole revolution within the window clears it again
  w.run_for(2s);
  EXPECT_FALSE(w.r.get(bit("Q1.00.5")));
  w.wheels[0]->slip = 0.5;  // 40 IU of motor per revolution: 20 IU > 5
  ASSERT_TRUE(w.run_until([&] { return w.r.clm.error() != 0; }, 2s));
  EXPECT_EQ(w.r.clm.error(), 0x4C);
}

TEST(ClmMeasuringWheel, Axis2OnMasterEncoder2IsError7C) {
  WheelRig w(3, {{"A216", "03 00 00.00.0"}, {"A227", "00.00.0 0000.010"}}, 2);
  w.r.program({{0, "PSI 2 +000100.000 500"}, {1, "JMP 0001"}});
  w.wheels[1]->slip = 0.98;
  w.start();
  EXPECT_TRUE(w.r.clm.wheel_active(2));
  ASSERT_TRUE(w.run_until([&] { return w.r.clm.motor_position(2) > 30.0; }));
  EXPECT_EQ(w.r.clm.error(), 0);
  w.wheels[1]->slip = 0.0;
  ASSERT_TRUE(w.run_until([&] { return w.r.clm.error() != 0; }, 2s));
  EXPECT_EQ(w.r.clm.error(), 0x7C);
}

TEST(ClmMeasuringWheel, Axis2ReachesItsLengthOnMasterEncoder2) {
  WheelRig w(3, {{"A227", "00.00.0 0000.010"}}, 2);
  w.r.program({{0, "PSI 2 +000100.000 500"}, {1, "JMP 0001"}});
  w.wheels[1]->slip = 0.95;
  w.start();
  w.run_to(1);
  EXPECT_EQ(w.r.clm.error(), 0);
  EXPECT_NEAR(w.wheels[1]->wheel_iu, 100.0, count_iu + 0.0013);
  EXPECT_NEAR(to_double(w.r.clm.variable(48)), 100.0 / 0.95, 0.006);  // V048: axis 2's motor
}

TEST(ClmMeasuringWheel, LiftedWheelWithAx16OffStopsAtTheMovesBound) {
  WheelRig w(3);  // Ax16 00 00: no window; the correction bound still holds
  w.r.program({{0, "PSI 1 +000100.000 999"}, {1, "JMP 0001"}});
  w.wheels[0]->slip = 0.0;
  w.start();
  ASSERT_TRUE(w.run_until([&] { return w.r.clm.error() != 0; }, 10s));
  EXPECT_EQ(w.r.clm.error(), 0x4C);
  // the wheel-motor difference of the move reached its length: the motor stops there
  EXPECT_GT(w.r.clm.motor_position(1), 100.0);
  EXPECT_LT(w.r.clm.motor_position(1), 100.0 + 0.25);
}

TEST(ClmMeasuringWheel, NoEncoderAttachedIs4CInAutomatic) {
  Rig r({{"A100", "1 3 0 0 0"}, {"C000", "01250 0000"}, {"C002", "0020.00000"}});
  r.start_auto();
  EXPECT_EQ(r.clm.error(), 0x4C);
}

TEST(ClmMeasuringWheel, WithoutItsMasterEncoderTheParameterSetIsError02) {
  Rig r({{"A100", "1 3 0 0 0"}});
  r.params["C002"] = "0000.00000";  // master encoder 1 not used (read at power-up)
  r.run_for(10ms);
  EXPECT_EQ(r.clm.error(), 0x02);
  EXPECT_NE(r.clm.error_message().find("A100"), std::string::npos) << r.clm.error_message();
}

TEST(ClmMeasuringWheel, SetV047MovesTheMotorPositionWhileNotHomed) {
  WheelRig w(3, {{"A124", "M2.01.0 +100 1"}});  // homing option 2, "homed" on M2.01.0
  w.r.program({{0, "SET V047 = +00000005.000000"},
               {1, "HOM 1"},
               {2, "AKN M2.01.0 1"},
               {3, "SET V047 = +00000001.000000"},
               {4, "JMP 0004"}});
  w.start();
  w.cycle();
  EXPECT_NEAR(w.r.clm.motor_position(1), 5.0, 1e-9);
  EXPECT_NEAR(w.r.pos(1), 0.0, 1e-9);  // the axis position stays
  ASSERT_TRUE(w.run_until([&] { return w.r.clm.error() != 0; }, 20s));
  EXPECT_EQ(w.r.clm.error(), 0x31);  // homed: V047 is read-only
  EXPECT_TRUE(w.r.clm.homed(1));
}

}  // namespace
}  // namespace hil::controllers::clm14::testing
