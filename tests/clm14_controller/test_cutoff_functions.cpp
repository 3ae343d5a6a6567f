// SPDX-License-Identifier: MIT
// CLM1.4 flying cutoff functions (manual §7.12, Ax33-Ax42, C008; digest §5.11): immediate cut and
// the manual cut vector with indexing (A134, error 3A), cut inhibit (A133), rapid stop (A136, 3B),
// maximum stroke (A137, 3C) and the travel limit, crop cut (A142), reverse optimisation
// (A139/A140), test mode (A100), No Material (C008) and the length counters of status 54. Each
// behaviour is raised by its condition on simulated drives in virtual time.
#include <gtest/gtest.h>

#include <cmath>

#include "rig.hpp"

namespace hil::controllers::clm14 {
namespace {

using namespace std::chrono_literals;
using testing::bit;
using testing::Rig;

motion::Limits material_limits(double v) {
  motion::Limits l;
  l.velocity = std::abs(v);
  l.acceleration = 400.0;
  return l;
}

// Axis 1 a flying cutoff (A100 mode 5) on master encoder 1: a 1250-line wheel on 20 IU.
#define CUTOFF_PARAMETERS                                                    \
  {"A100", "1 5 0 0 0"}, {"C000", "01250 0000"}, {"C001", "5 0 00 0 0 0"}, { \
    "C002", "0020.00000"                                                     \
  }

/// The cutting program: parts of `length` IU, `sync` seconds in sync, EOS, loop.
std::vector<std::pair<int, std::string>> cutting(const std::string& length = "000100.000",
                                                 const std::string& sync = "00.100") {
  return {{0, "NOP"}, {1, "LML 1 " + length}, {2, "WAI " + sync}, {3, "EOS"}, {4, "JMP 0001"}};
}

/// Runs cycles until `done` (or `limit`), setting `input` for the one cycle in which `when` first holds.
template <class When, class Done>
void pulse_when(Rig& r, const BitAddress& input, When when, Done done, Duration limit = 30s) {
  bool pulsed = false;
  const TimePoint end = r.now + limit;
  while (!done() && r.now < end) {
    const bool p = !pulsed && when();
    pulsed = pulsed || p;
    r.set(input, p);
    r.cycle();
  }
  r.set(input, false);
}

TEST(ClmCutoffFunctions, CutInhibitHoldsTheSyncUntilImmediateCutWhichSyncsAtOnce) {
  Rig r({CUTOFF_PARAMETERS, {"A133", "I1.00.0 Q1.00.5"}, {"A134", "I1.00.1 0100 0"}});
  auto& material = r.add_master_encoder();
  r.program(cutting());
  r.run_for(20ms);
  r.enter_auto();
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  // A pulse at material 10 (the first part is armed, its ramp has not begun): no sync.
  pulse_when(
      r, bit("I1.00.0"), [&] { return r.clm.master_position() >= 10.0; },
      [&] { return r.clm.master_position() >= 250.0; });
  EXPECT_EQ(r.clm.cuts(), 0u) << "the cut is inhibited";
  EXPECT_TRUE(r.clm.cut_inhibited());
  EXPECT_TRUE(r.get(bit("Q1.00.5"))) << "A133 output";
  EXPECT_NEAR(r.pos(1), 0.0, 0.01) << "the carriage stays home";
  EXPECT_GT(r.clm.length_counter(1), 249.0) << "material counter";
  EXPECT_LT(r.clm.length_counter(2), 11.0) << "the product counter stops while the cut is inhibited";
  // Immediate cut at material ~250: sync now; the cut falls half the ramp (v²/2a = 0.8 IU) later.
  const double at = r.clm.master_position();
  pulse_when(
      r, bit("I1.00.1"), [] { return true; }, [&] { return r.clm.cuts() == 1; }, 2s);
  ASSERT_EQ(r.clm.cuts(), 1u) << r.clm.error_message();
  EXPECT_NEAR(r.clm.last_cut_point(), at + 0.8, 0.2);
  EXPECT_FALSE(r.clm.cut_inhibited());
  r.cycle();
  EXPECT_FALSE(r.get(bit("Q1.00.5")));
  // The next part: the programmed length from that cut, to one count of the wheel.
  const double first = r.clm.last_cut_point();
  ASSERT_TRUE(r.run_until([&] { return r.clm.cuts() == 2; }, 10s));
  EXPECT_NEAR(r.clm.last_cut_point() - first, 100.0, 0.0045);
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
}

TEST(ClmCutoffFunctions, ImmediateCutWithTheCarriageAwayFromHomeIsIgnored) {
  Rig r({CUTOFF_PARAMETERS, {"A134", "I1.00.1 0100 0"}});
  auto& material = r.add_master_encoder();
  r.program(cutting("000100.000", "01.000"));
  r.run_for(20ms);
  r.enter_auto();
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  ASSERT_TRUE(r.run_until([&] { return r.clm.cuts() == 1; }, 10s));
  const double first = r.clm.last_cut_point();
  r.run_for(200ms);  // in sync, 8 IU from home
  pulse_when(
      r, bit("I1.00.1"), [] { return true; }, [&] { return r.clm.cuts() == 2; }, 10s);
  EXPECT_NEAR(r.clm.last_cut_point() - first, 100.0, 0.0045) << "the part is cut at its length";
}

TEST(ClmCutoffFunctions, ManualCutRunsItsProgramAndIndexingCountsFromIt) {
  const auto program = [] {
    auto p = cutting();
    p.push_back({100, "AEA M3.00.3 1"});
    p.push_back({101, "RTS"});
    return p;
  };
  for (const double enter_at : {60.0, 150.0}) {
    Rig r({CUTOFF_PARAMETERS, {"A134", "I1.00.1 0100 1"}});
    auto& material = r.add_master_encoder();
    r.program(program());
    r.run_for(20ms);
    ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
    // Manual: the manual cut vector at material 30 runs the program at 0100 (up to its RTS).
    ASSERT_TRUE(r.run_until([&] { return material.status().position >= 30.0; }, 5s));
    const double manual_cut = material.status().position;  // the encoder the next cycle reads
    r.set(bit("I1.00.1"), true);
    r.cycle();
    r.set(bit("I1.00.1"), false);
    r.run_for(20ms);
    EXPECT_TRUE(r.get(bit("M3.00.3"))) << "the manual cut program ran";
    EXPECT_FALSE(r.clm.task(1).active) << "and ended with its RTS";
    ASSERT_TRUE(r.run_until([&] { return r.clm.master_position() >= enter_at; }, 10s));
    r.set(sys::automatic, true);
    if (enter_at < 100.0) {
      // Indexing: the material fed since the manual cut is subtracted from the first length.
      ASSERT_TRUE(r.run_until([&] { return r.clm.cuts() == 1; }, 10s)) << r.clm.error_message();
      EXPECT_NEAR(r.clm.last_cut_point(), manual_cut + 100.0, 0.01);
    } else {
      // More material than the length since the manual cut: error 3A.
      ASSERT_TRUE(r.run_until([&] { return r.clm.error() != 0; }, 1s));
      EXPECT_EQ(r.clm.error(), 0x3A) << r.clm.error_message();
      EXPECT_EQ(r.clm.cuts(), 0u);
    }
  }
}

TEST(ClmCutoffFunctions, RapidStopInSyncRunsItsProgramThenStopsWith3B) {
  for (const bool in_sync : {true, false}) {
    Rig r({CUTOFF_PARAMETERS, {"A136", "I1.00.2 0200"}});
    auto& material = r.add_master_encoder();
    auto p = cutting("000100.000", "01.000");
    p.push_back({200, "AEA M3.00.0 1"});
    p.push_back({201, "EOS"});
    r.program(p);
    r.run_for(20ms);
    r.enter_auto();
    ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
    if (in_sync) {
      ASSERT_TRUE(r.run_until([&] { return r.clm.cuts() == 1; }, 10s));
    }
    r.run_for(100ms);
    pulse_when(
        r, bit("I1.00.2"), [] { return true; }, [&] { return r.clm.error() != 0; }, 1s);
    EXPECT_EQ(r.clm.error(), 0x3B) << r.clm.error_message();
    EXPECT_EQ(r.get(bit("M3.00.0")), in_sync) << "the rapid-stop program runs only in sync";
    EXPECT_FALSE(r.clm.coupled(1));
    const double stopped = r.pos(1);
    r.run_for(200ms);
    EXPECT_NEAR(r.pos(1), stopped, 0.2) << "0 V: the carriage stands";
  }
}

TEST(ClmCutoffFunctions, MaximumStrokeRunsItsProgramThenStopsWith3C) {
  for (const std::string line : {"0200", "0000"}) {
    Rig r({CUTOFF_PARAMETERS, {"A104", "+000050.000"}, {"A137", "00030 " + line}});
    auto& material = r.add_master_encoder();
    auto p = cutting("000100.000", "05.000");
    p.push_back({200, "AEA M3.00.1 1"});
    p.push_back({201, "EOS"});
    r.program(p);
    r.run_for(20ms);
    r.enter_auto();
    ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
    ASSERT_TRUE(r.run_until([&] { return r.clm.error() != 0; }, 10s));
    EXPECT_EQ(r.clm.error(), 0x3C) << r.clm.error_message();
    EXPECT_EQ(r.get(bit("M3.00.1")), line != "0000") << line;
    // 50 - 30: the stroke ran out at 20 IU (one more cycle with a program)
    EXPECT_GT(r.pos(1), 20.0);
    EXPECT_LT(r.pos(1), 20.5);
  }
}

TEST(ClmCutoffFunctions, TravelLimitReachedFirstIs47) {
  Rig r({CUTOFF_PARAMETERS, {"A104", "+000050.000"}});
  auto& material = r.add_master_encoder();
  r.program(cutting("000100.000", "05.000"));
  r.run_for(20ms);
  r.enter_auto();
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  ASSERT_TRUE(r.run_until([&] { return r.clm.error() != 0; }, 10s));
  EXPECT_EQ(r.clm.error(), 0x47) << r.clm.error_message();
  EXPECT_NEAR(r.pos(1), 50.0, 0.2);
}

TEST(ClmCutoffFunctions, CropCutMakesThisPartTheCropLength) {
  Rig r({CUTOFF_PARAMETERS, {"A142", "0025.00 I1.00.3"}});
  auto& material = r.add_master_encoder();
  r.program(cutting());
  r.run_for(20ms);
  r.enter_auto();
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  r.run_for(10ms);  // the first part is armed, the carriage home
  pulse_when(
      r, bit("I1.00.3"), [] { return true; }, [&] { return r.clm.cuts() == 1; }, 5s);
  EXPECT_NEAR(r.clm.last_cut_point(), 25.0, 0.0045) << "the crop length from where the material stood";
  const double crop = r.clm.last_cut_point();
  ASSERT_TRUE(r.run_until([&] { return r.clm.cuts() == 2; }, 10s));
  EXPECT_NEAR(r.clm.last_cut_point() - crop, 100.0, 0.0045) << "then the programmed length";
}

/// Seconds the carriage stands at its origin before the second part's ramp, with A139's input
/// set or not; `speed_up` raises the material speed to 60 IU/s during the first return.
struct ReturnRun {
  double standstill_s = 0.0;
  bool output_seen = false;
  double second_part = 0.0;
};
ReturnRun return_run(bool optimise, bool speed_up = false) {
  Rig r({CUTOFF_PARAMETERS, {"A139", "I1.00.4 Q1.00.6"}, {"A140", "0.10 001 100"}});
  auto& material = r.add_master_encoder();
  r.program(cutting());
  r.set(bit("I1.00.4"), optimise);
  r.run_for(20ms);
  r.enter_auto();
  EXPECT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  ReturnRun out;
  EXPECT_TRUE(r.run_until([&] { return r.clm.cuts() == 1; }, 10s));
  const double first = r.clm.last_cut_point();
  if (speed_up) {
    // during the optimised return (the carriage moves back)
    EXPECT_TRUE(r.run_until([&] { return r.get(bit("Q1.00.6")) && r.clm.velocity(1) < -0.5; }, 2s));
    EXPECT_FALSE(material.move_velocity(60.0, material_limits(60.0)));
    const TimePoint t0 = r.now;
    EXPECT_TRUE(r.run_until([&] { return !r.get(bit("Q1.00.6")); }, 1s));
    EXPECT_LT(r.now - t0, 100ms) << "above the velocity window the return goes back to A108";
  }
  bool home = false;
  TimePoint home_since{};
  while (r.clm.cuts() < 2 && r.now < TimePoint{} + 30s) {
    r.cycle();
    out.output_seen = out.output_seen || r.get(bit("Q1.00.6"));
    const bool at = std::abs(r.pos(1)) < 0.02;
    if (at && !home) home_since = r.now;
    if (at) home = true;
    if (!at && home && !r.clm.coupled(1)) home = false;
    if (r.pos(1) > 0.05 && home && r.clm.coupled(1) && out.standstill_s == 0.0)
      out.standstill_s = std::chrono::duration<double>(r.now - home_since).count();
  }
  out.second_part = r.clm.last_cut_point() - first;
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
  return out;
}

TEST(ClmCutoffFunctions, ReverseOptimisationReturnsJustInTimeForTheNextSync) {
  const ReturnRun plain = return_run(false);
  const ReturnRun optimised = return_run(true);
  // 100 IU parts at 40 IU/s: the plain return (A108) waits ~2 s at the origin; the optimised one
  // arrives A140's 0.1 s before the ramp.
  EXPECT_GT(plain.standstill_s, 1.5);
  EXPECT_FALSE(plain.output_seen);
  EXPECT_GT(optimised.standstill_s, 0.05);
  EXPECT_LT(optimised.standstill_s, 0.25);
  EXPECT_TRUE(optimised.output_seen) << "A139 output during the optimised return";
  EXPECT_NEAR(plain.second_part, 100.0, 0.0045);
  EXPECT_NEAR(optimised.second_part, 100.0, 0.0045);
  const ReturnRun faster = return_run(true, true);
  EXPECT_GT(faster.standstill_s, 0.5) << "re-planned at A108, the carriage is home early again";
}

TEST(ClmCutoffFunctions, TestModeRunsOnTheInternalMaterialClock) {
  // No master encoder attached: test mode's clock is the material (32 key steps, 0..A106).
  Rig r({CUTOFF_PARAMETERS, {"A100", "1 5 0 1 0"}});
  r.program(cutting());
  r.run_for(20ms);
  r.enter_auto();
  r.clm.set_test_speed_step(31);
  r.run_for(100ms);
  EXPECT_NEAR(r.clm.master_velocity(), 100.0, 1e-9) << "step 31 = A106";
  r.clm.set_test_speed_step(12);
  r.cycle();
  EXPECT_NEAR(r.clm.master_velocity(), 100.0 * 12 / 31, 1e-9);
  ASSERT_TRUE(r.run_until([&] { return r.clm.cuts() == 3; }, 20s)) << r.clm.error_message();
  const double c3 = r.clm.last_cut_point();
  ASSERT_TRUE(r.run_until([&] { return r.clm.cuts() == 4; }, 20s));
  EXPECT_NEAR(r.clm.last_cut_point() - c3, 100.0, 0.0045);
  r.set(sys::automatic, false);
  r.cycle();
  EXPECT_EQ(r.clm.test_speed_step(), 0) << "Automatic -> Manual stops the clock";
  r.cycle();
  EXPECT_EQ(r.clm.master_velocity(), 0.0);
}

TEST(ClmCutoffFunctions, NoMaterialTakesTheSpeedFromItsVariable) {
  Rig r({CUTOFF_PARAMETERS, {"C008", "I1.00.5 600"}});
  auto& material = r.add_master_encoder();
  r.program(cutting());
  ASSERT_TRUE(r.clm.set_variable(600, 30 * micro_one));
  r.run_for(20ms);
  r.enter_auto();
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  r.run_for(500ms);
  EXPECT_NEAR(r.clm.master_velocity(), 40.0, 0.1);
  r.set(bit("I1.00.5"), true);
  double last = r.clm.master_position();
  r.cycle();
  EXPECT_EQ(r.clm.master_velocity(), 30.0) << "the switch is instantaneous";
  EXPECT_NEAR(r.clm.master_position() - last, 0.06, 0.005);
  r.run_for(1s);
  r.set(bit("I1.00.5"), false);
  last = r.clm.master_position();
  r.cycle();
  EXPECT_NEAR(r.clm.master_position() - last, 0.08, 0.005) << "back on the encoder without a jump";
  // A speed above A106 is error 32 naming the variable.
  ASSERT_TRUE(r.clm.set_variable(600, 150 * micro_one));
  r.set(bit("I1.00.5"), true);
  r.cycle();
  EXPECT_EQ(r.clm.error(), 0x32);
  EXPECT_EQ(r.clm.error_item(3), "0600");
}

TEST(ClmCutoffFunctions, LengthCountersOfStatus54) {
  Rig r({CUTOFF_PARAMETERS});
  auto& material = r.add_master_encoder();
  r.program(cutting());
  r.run_for(20ms);
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  ASSERT_TRUE(r.run_until([&] { return r.clm.master_position() >= 50.0; }, 5s));
  EXPECT_NEAR(r.clm.length_counter(1), r.clm.master_position(), 0.005) << "Manual: the material counter counts";
  EXPECT_EQ(r.clm.length_counter(2), 0.0) << "the product counter counts in Automatic only";
  r.enter_auto();
  const double m0 = r.clm.master_position();
  ASSERT_TRUE(r.run_until([&] { return r.clm.master_position() >= m0 + 100.0; }, 5s));
  EXPECT_NEAR(r.clm.length_counter(2), r.clm.master_position() - m0, 0.1);
  r.clm.clear_length_counter(2);
  EXPECT_EQ(r.clm.length_counter(2), 0.0);
  EXPECT_GT(r.clm.length_counter(1), 150.0);
  r.clm.clear_length_counter(1);
  EXPECT_EQ(r.clm.length_counter(1), 0.0);
}

}  // namespace
}  // namespace hil::controllers::clm14
