// SPDX-License-Identifier: MIT
// CLM1.4 commands on master encoder 1 and the coupling layer (manual §5.7 FOL/FUN/AEO/VEO 5/
// SRP/MLO/MLT/FAK 5, §7.6, §7.12 flying cutoff LML/LMK/LMR/EOS; vector 37), on simulated drives
// in virtual time.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rig.hpp"

namespace hil::controllers::clm14 {
namespace {

using namespace std::chrono_literals;
using testing::bit;
using testing::byte;
using testing::Rig;

motion::Limits material_limits(double v) {
  motion::Limits l;
  l.velocity = std::abs(v);
  l.acceleration = 400.0;
  return l;
}

double var(const Rig& r, int n) {
  return to_double(r.clm.variable(n));
}

// ---- the gear ratio ------------------------------------------------------------------------------

TEST(ClmGearRatio, ExactFromBothScalings) {
  // 1024-line encoder on 10 IU against a 1250-line wheel on 20 IU: 409.6 / 250 inc per IU.
  EXPECT_EQ(clm_gear_ratio(micro_one, 1024, 1'000'000, 1250, 2'000'000), (motion::GearRatio{1024, 625}));
  EXPECT_EQ(clm_gear_ratio(micro_one / 2, 1024, 1'000'000, 1250, 2'000'000), (motion::GearRatio{512, 625}));
  EXPECT_EQ(clm_gear_ratio(2 * micro_one, 1024, 1'000'000, 1024, 1'000'000), (motion::GearRatio{2, 1}));
  EXPECT_EQ(clm_gear_ratio(-micro_one, 1024, 1'000'000, 1024, 1'000'000), (motion::GearRatio{-1, 1}));
  // FAK 5 multiplies the master's feed constant: 1.01 × 20 IU per wheel turn
  EXPECT_EQ(clm_gear_ratio(micro_one, 1024, 1'000'000, 1250, 2'000'000, 1'010'000), (motion::GearRatio{25856, 15625}));
}

TEST(ClmGearRatio, TooLargeTermsGiveTheNearestFittingFraction) {
  // 1.234567 × 9973 × 4999.99999 / (0.01 × 9967): the exact terms exceed 2^31.
  const auto r = clm_gear_ratio(1'234'567, 9973, 1'000, 9967, 499'999'999);
  ASSERT_TRUE(motion::valid(r));
  EXPECT_GT(r.num, std::int64_t{1} << 27) << "as many digits as the bound allows";
  const double want = 1.234567 * 9973.0 * 4999.99999 / (0.01 * 9967.0);
  EXPECT_NEAR(r.value(), want, want * 1e-12);
}

// ---- FOL -------------------------------------------------------------------------------------------

TEST(ClmFol, SlaveFollowsTheMasterAxisAtTheFactorExactly) {
  // Axis 2 is a slave of axis 1's actual position (A200 = linear, mode 2, master axis 1).
  Rig r({{"A200", "1 2 1 0 0"}}, 2);
  r.program({{0, "FOL 2 1 +2.000000"},
             {1, "PSI 1 +000030.000 500"},
             {2, "WAI 00.300"},
             {3, "PSI 1 -000012.500 400"},
             {4, "WAI 00.300"},
             {5, "JMP 0005"}});
  r.run_for(20ms);
  const auto m0 = r.motion_axes[0]->status().position_inc;
  const auto s0 = r.motion_axes[1]->status().command_inc;
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 5; }));
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
  EXPECT_TRUE(r.clm.coupled(2));
  const auto m1 = r.motion_axes[0]->status().position_inc;
  const auto s1 = r.motion_axes[1]->status().command_inc;
  EXPECT_NE(m1, m0);
  EXPECT_EQ(s1 - s0, 2 * (m1 - m0)) << "slave increments = 2 x master increments, exactly";
  EXPECT_NEAR(r.pos(2), 2.0 * r.pos(1), 0.006);
  EXPECT_NEAR(r.pos(1), 17.5, 0.011);
}

TEST(ClmFol, SlaveOfMasterEncoderWithARampedEngageAndASuperimposedMove) {
  // Axis 2 slave of master encoder 1 (wheel 1250 lines on 20 IU), factor 0.5, mode 2 (ramps):
  // engaged while the material runs at 20 IU/s, it reaches 10 IU/s without a coupling fault.
  Rig r({{"A200", "1 2 5 0 0"}, {"C000", "01250 0000"}, {"C002", "0020.00000"}}, 2);
  auto& material = r.add_master_encoder();
  r.program({{0, "FOL 2 2 +0.500000"}, {1, "WAI 01.000"}, {2, "PSI 2 +000005.000 500"}, {3, "JMP 0003"}});
  r.run_for(20ms);
  ASSERT_FALSE(material.move_velocity(20.0, material_limits(20.0)));
  r.run_for(200ms);
  r.start_auto();
  r.run_for(500ms);
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
  // the measured velocity resolves one increment per 16 ms: 0.15 IU/s
  EXPECT_NEAR(r.clm.velocity(2), 10.0, 0.16) << "half the material speed";
  // The superimposed PSI adds 5 IU to the following slave; then the material stops. The slave's
  // set-point moved 512/625 increments per wheel count (0.5 × 409.6 / 250) plus 2048 (5 IU).
  std::int64_t m_used = material.status().position_inc;  // the count the next CLM cycle reads
  const auto step = [&] {
    m_used = material.status().position_inc;
    r.cycle();
  };
  while (r.clm.task(1).pc != 2) step();
  const std::int64_t m0 = m_used;
  const std::int64_t s0 = r.motion_axes[1]->status().command_inc;
  while (r.clm.task(1).pc != 3) step();
  ASSERT_FALSE(material.move_velocity(0.0, material_limits(20.0)));
  for (int i = 0; i < 500; ++i) step();
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
  const std::int64_t ds = r.motion_axes[1]->status().command_inc - s0;
  const double want = 512.0 * static_cast<double>(m_used - m0) / 625.0 + 2048.0;
  EXPECT_LE(std::abs(static_cast<double>(ds) - want), 1.0) << ds << " vs " << want;
  EXPECT_NEAR(var(r, 11), 0.0, 1e-9) << "V011 master encoder velocity at rest";
}

TEST(ClmFol, Mode2RampsDownAtImmediateStopAndResynchronisesOnStart) {
  Rig r({{"A200", "1 2 5 0 0"}, {"C000", "01250 0000"}, {"C002", "0020.00000"}}, 2);
  auto& material = r.add_master_encoder();
  r.program({{0, "FOL 2 2 +0.500000"}, {1, "WAI 09.000"}, {2, "JMP 0002"}});
  r.run_for(20ms);
  ASSERT_FALSE(material.move_velocity(20.0, material_limits(20.0)));
  r.run_for(200ms);
  r.start_auto();
  r.run_for(300ms);
  EXPECT_NEAR(r.clm.velocity(2), 10.0, 0.16);
  r.set(sys::immediate_stop_ok, false);  // Immediate Stop: the material runs on, the slave ramps out
  r.run_for(300ms);
  EXPECT_EQ(r.clm.run_state(), RunState::stopped);
  EXPECT_NEAR(r.clm.velocity(2), 0.0, 0.16);
  EXPECT_TRUE(r.clm.coupled(2));
  r.set(sys::immediate_stop_ok, true);
  r.pulse(sys::start);
  r.run_for(300ms);
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
  EXPECT_NEAR(r.clm.velocity(2), 10.0, 0.16) << "re-synchronised";
}

/// FOL mode 2 at the B015 interrupt vector (p = `p`): axis 2 follows the material at 0.5; the
/// vector's program waits 0.5 s, then gives FOL again. The slave's velocity 300 ms after the
/// vector and 400 ms after that FOL.
std::pair<double, double> fol2_at_interrupt_vector(char p) {
  Rig r({{"A200", "1 2 5 0 0"},
         {"C000", "01250 0000"},
         {"C002", "0020.00000"},
         {"B015", std::string("I1.00.3 1 ") + p + " 0100"}},
        2);
  auto& material = r.add_master_encoder();
  r.program({{0, "FOL 2 2 +0.500000"},
             {1, "WAI 09.000"},
             {2, "JMP 0002"},
             {100, "WAI 00.500"},
             {101, "FOL 2 2 +0.500000"},
             {102, "JMP 0102"}});
  r.run_for(20ms);
  EXPECT_FALSE(material.move_velocity(20.0, material_limits(20.0)));
  r.run_for(200ms);
  r.start_auto();
  r.run_for(300ms);
  EXPECT_NEAR(r.clm.velocity(2), 10.0, 0.16);
  r.pulse(bit("I1.00.3"));
  EXPECT_EQ(r.clm.task(1).pc, 100);
  r.run_for(300ms);
  const double during = r.clm.velocity(2);
  EXPECT_TRUE(r.clm.coupled(2));
  EXPECT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 102; }, 1s));
  r.run_for(400ms);
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
  return {during, r.clm.velocity(2)};
}

TEST(ClmFol, Mode2RampsOutAtTheInterruptVectorAndTheNextFolResynchronises) {
  const auto [during, after] = fol2_at_interrupt_vector('1');
  EXPECT_NEAR(during, 0.0, 0.16) << "B015 p = 1: the slave ramped out";
  EXPECT_NEAR(after, 10.0, 0.16) << "FOL re-synchronised it";
  const auto [during0, after0] = fol2_at_interrupt_vector('0');
  EXPECT_NEAR(during0, 10.0, 0.16) << "B015 p = 0: the slave keeps following";
  EXPECT_NEAR(after0, 10.0, 0.16);
}

TEST(ClmFol, FactorOnANormalAxisOnlySetsTheVeoMultiplier) {
  Rig r({{"C002", "0020.00000"}});
  auto& material = r.add_master_encoder();
  r.program({{0, "FOL 1 1 +0.500000"}, {1, "VEO 1 5 0 999 0"}, {2, "POI 1 +000050.000 999"}, {3, "JMP 0003"}});
  r.run_for(20ms);
  ASSERT_FALSE(material.move_velocity(80.0, material_limits(80.0)));
  r.run_for(300ms);
  r.start_auto();
  r.run_for(300ms);
  EXPECT_FALSE(r.clm.coupled(1));
  // override = 80 / 100 × 0.5 = 0.4: the feed runs at 0.999 × 100 × 0.4
  EXPECT_NEAR(r.clm.velocity(1), 39.96, 0.16);
}

TEST(ClmVeo, MasterEncoderOverrideFollowsTheMaterialAndFaults4DAbove125Percent) {
  Rig r({{"C002", "0020.00000"}});
  auto& material = r.add_master_encoder();
  r.program({{0, "VEO 1 5 0 999 0"}, {1, "POI 1 +001000.000 999"}, {2, "JMP 0002"}});
  r.run_for(20ms);
  ASSERT_FALSE(material.move_velocity(50.0, material_limits(50.0)));
  r.run_for(300ms);
  r.start_auto();
  r.run_for(500ms);
  EXPECT_NEAR(r.clm.velocity(1), 49.95, 0.16) << "programmed 99.9 % × override 0.5";
  ASSERT_FALSE(material.move_velocity(80.0, material_limits(80.0)));
  r.run_for(500ms);
  EXPECT_NEAR(r.clm.velocity(1), 79.92, 0.16) << "the running feed follows the material";
  ASSERT_FALSE(material.move_velocity(130.0, material_limits(130.0)));
  r.run_for(500ms);
  EXPECT_EQ(r.clm.error(), 0x4D) << "Max. Override axis 1";
}

TEST(ClmAeo, AccelerationFromTheMaterialSpeed) {
  Rig r({{"C002", "0020.00000"}});
  auto& material = r.add_master_encoder();
  r.program({{0, "AEO 1 1 1 999 100"}, {1, "POI 1 +000020.000 999"}, {2, "JMP 0002"}});
  r.run_for(20ms);
  ASSERT_FALSE(material.move_velocity(50.0, material_limits(50.0)));
  r.run_for(300ms);
  r.start_auto();
  double peak = 0.0;
  for (int i = 0; i < 200; ++i) {
    r.cycle();
    peak = std::max(peak, std::abs(r.motion_axes[0]->status().command_acceleration));
  }
  // 1000 × (50 / 100)² × 0.999 = 249.75 IU/s² (above the 100 ‰ minimum)
  EXPECT_NEAR(peak, 249.75, 0.5);
}

// ---- FUN, MLT, MLO ------------------------------------------------------------------------------------

TEST(ClmFun, FeedLengthsBufferedAndRestarted) {
  Rig r({{"C002", "0020.00000"}});
  auto& material = r.add_master_encoder();
  r.program({{0, "FUN 1222121"},
             {1, "PSI 1 +000030.000 999"},
             {2, "MLT 1 000010.000 Q1.00.1"},
             {3, "FUN 0222022"},
             {4, "JMP 0004"}});
  r.run_for(20ms);
  r.start_auto();
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 4; }));
  EXPECT_NEAR(var(r, 112), 30.0, 0.011) << "axis 1 feed length buffered";
  EXPECT_NEAR(var(r, 111), 0.0, 0.011) << "and restarted";
  EXPECT_GT(var(r, 41), 10.0) << "master encoder 1 feed length buffered";
  EXPECT_TRUE(r.get(bit("Q1.00.1"))) << "MLT: more than 10 IU of material since the FUN restart";
}

TEST(ClmMlo, BitTogglesEveryProgrammedLength) {
  Rig r({{"C002", "0020.00000"}});
  auto& material = r.add_master_encoder();
  r.program({{0, "MLO 1 000010.000 Q1.00.2"}, {1, "JMP 0001"}});
  r.run_for(20ms);
  r.start_auto();
  r.cycle();
  ASSERT_FALSE(material.move_velocity(50.0, material_limits(50.0)));
  int edges = 0;
  bool last = false;
  while (r.clm.master_position() < 45.0) {
    r.cycle();
    const bool q = r.get(bit("Q1.00.2"));
    edges += q != last;
    last = q;
  }
  EXPECT_EQ(edges, 4) << "10, 20, 30, 40 IU";
  r.set(sys::automatic, false);
  r.run_for(500ms);
  EXPECT_EQ(r.get(bit("Q1.00.2")), last) << "leaving Automatic disables it";
}

// ---- flying cutoff ------------------------------------------------------------------------------------

// Axis 1 a flying cutoff (A100 mode 5) on master encoder 1: a 1250-line wheel on 20 IU.
#define CUTOFF_PARAMETERS                                                    \
  {"A100", "1 5 0 0 0"}, {"C000", "01250 0000"}, {"C001", "5 0 00 0 0 0"}, { \
    "C002", "0020.00000"                                                     \
  }

struct Cut {
  double exact;     ///< the CLM's cut point: wheel counts under the commanded tool (IU)
  double actual;    ///< material - carriage, actual positions (IU), when the knife goes down
  double measured;  ///< V025 after the FUN of the tool program
  double speed;     ///< material speed of this part (IU/s)
};

TEST(ClmFlyingCutoff, CutsAtTheProgrammedLengthWhileTheMaterialSpeedChanges) {
  Rig r({CUTOFF_PARAMETERS});
  auto& material = r.add_master_encoder();
  r.program({{0, "NOP"},
             {1, "LML 1 000100.000"},
             {2, "AEA Q1.00.0 1"},
             {3, "FUN 2222220"},
             {4, "WAI 00.100"},
             {5, "AEA Q1.00.0 0"},
             {6, "EOS"},
             {7, "JMP 0001"}});
  r.run_for(20ms);
  r.enter_auto();  // flying cutoff: task 1 starts on Manual -> Automatic, no Start
  EXPECT_EQ(r.clm.run_state(), RunState::running);
  double speed = 40.0;
  ASSERT_FALSE(material.move_velocity(speed, material_limits(speed)));
  std::vector<Cut> cuts;
  bool knife = false;
  while ((cuts.size() < 6 || knife) && r.now < TimePoint{} + 30s) {
    r.cycle();
    const bool q = r.get(bit("Q1.00.0"));
    if (q && !knife) cuts.push_back({r.clm.last_cut_point(), material.status().position - r.pos(1), 0.0, speed});
    if (!q && knife) {
      cuts.back().measured = var(r, 25);
      // the material changes speed after parts 2 and 4
      if (cuts.size() == 2 || cuts.size() == 4) {
        speed = cuts.size() == 2 ? 25.0 : 60.0;
        ASSERT_FALSE(material.move_velocity(speed, material_limits(speed)));
      }
    }
    knife = q;
    ASSERT_EQ(r.clm.error(), 0) << r.clm.error_message();
  }
  ASSERT_EQ(cuts.size(), 6u);
  EXPECT_EQ(r.clm.cuts(), 6u);
  // The CLM's own cut points (the material stood at 0 under the tool when the program started):
  // every part exactly 100 IU, to one count of the wheel (0.004 IU), at any speed.
  for (std::size_t i = 0; i < cuts.size(); ++i)
    EXPECT_NEAR(cuts[i].exact - (i == 0 ? 0.0 : cuts[i - 1].exact), 100.0, 0.0045) << "part " << i + 1;
  // The physical cut (actual positions) trails by the one-cycle encoder sampling and the
  // carriage drive's lag, both proportional to the speed: a part cut at the same speed as the
  // one before is 100 IU to 0.01 IU (actual and V025); a speed change shifts that one part.
  for (std::size_t i = 1; i < cuts.size(); ++i) {
    const double len = cuts[i].actual - cuts[i - 1].actual;
    if (cuts[i].speed == cuts[i - 1].speed) {
      EXPECT_NEAR(len, 100.0, 0.01) << "part " << i + 1;
      EXPECT_NEAR(cuts[i].measured, 100.0, 0.01) << "V025 of part " << i + 1;
    } else {
      EXPECT_NEAR(len, 100.0, 0.006 * std::abs(cuts[i].speed - cuts[i - 1].speed)) << "part " << i + 1;
    }
  }
}

TEST(ClmFlyingCutoff, ToolWidthIsAddedToTheLength) {
  Rig r({CUTOFF_PARAMETERS, {"A141", "02.50"}});
  auto& material = r.add_master_encoder();
  r.program({{0, "NOP"}, {1, "LML 1 000050.000"}, {2, "EOS"}, {3, "JMP 0001"}});
  r.run_for(20ms);
  r.enter_auto();
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  ASSERT_TRUE(r.run_until([&] { return r.clm.cuts() == 2; }, 10s));
  EXPECT_NEAR(r.clm.last_cut_point(), 105.0, 0.005);
}

TEST(ClmFlyingCutoff, LmrVector37RasterAndOffsetDistance) {
  // Vector 37: light-barrier offset 100, mark distance 1000, offset 300.
  constexpr LmrGeometry before = lmr_geometry(1000.0, 300.0, 100.0);
  constexpr LmrGeometry after = lmr_geometry(1000.0, 300.0, -100.0);
  EXPECT_EQ(before.raster, 900.0);
  EXPECT_EQ(before.offset, 400.0);
  EXPECT_EQ(after.raster, 1100.0);
  EXPECT_EQ(after.offset, 200.0);
}

/// LMR on the running model: the material runs at 40 IU/s; a mark reaches the light barrier at
/// material 500 (Raster 1 pulse); returns the cut point.
double lmr_cut(std::string_view barrier, std::optional<double> mark_at) {
  Rig r({CUTOFF_PARAMETERS});
  auto& material = r.add_master_encoder();
  r.program({{0, "NOP"},
             {1, std::string("LMR 1 001000.000 000300.000 ") + std::string(barrier)},
             {2, "EOS"},
             {3, "JMP 0003"}});
  r.run_for(20ms);
  r.enter_auto();
  EXPECT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  bool pulsed = false;
  while (r.clm.cuts() == 0 && r.now < TimePoint{} + 60s) {
    const bool pulse = mark_at && !pulsed && r.clm.master_position() >= *mark_at;
    r.set(sys::raster1, pulse);
    pulsed = pulsed || pulse;
    r.cycle();
  }
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
  return r.clm.last_cut_point();
}

TEST(ClmFlyingCutoff, LmrCutsTheOffsetDistanceAfterTheMark) {
  // The mark reaches the barrier at material 500; the CLM samples Raster 1 once per NC cycle and
  // this rig raises it one cycle after the material passed 500, so the raster position is
  // 500.08..500.16 (40 IU/s × 2 ms per cycle). The cut follows at the offset distance: 400 with
  // the barrier before the material entry, 200 after it.
  const double before = lmr_cut("+00100.000", 500.0);
  EXPECT_GE(before, 900.0 + 0.08 - 0.005);
  EXPECT_LE(before, 900.0 + 0.16 + 0.005);
  const double after = lmr_cut("-00100.000", 500.0);
  EXPECT_GE(after, 700.0 + 0.08 - 0.005);
  EXPECT_LE(after, 700.0 + 0.16 + 0.005);
  // No mark: the expected one (previous cut - offset + raster distance) gives mark distance.
  EXPECT_NEAR(lmr_cut("+00100.000", std::nullopt), 1000.0, 0.005);
}

TEST(ClmFlyingCutoff, LmkRasterSetsTheOffsetDistanceOncePerInstruction) {
  Rig r({CUTOFF_PARAMETERS});
  auto& material = r.add_master_encoder();
  r.program({{0, "NOP"}, {1, "LMK 1 000200.000 000030.000"}, {2, "EOS"}, {3, "JMP 0001"}});
  r.run_for(20ms);
  r.enter_auto();
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  std::vector<double> marks{60.0, 90.0};  // the second is ignored: once per instruction
  std::size_t next = 0;
  while (r.clm.cuts() == 0 && r.now < TimePoint{} + 30s) {
    const bool pulse = next < marks.size() && r.clm.master_position() >= marks[next];
    if (pulse) ++next;
    r.set(sys::raster1, pulse);
    r.cycle();
  }
  const double first = r.clm.last_cut_point();
  EXPECT_NEAR(first, 90.0 + 0.12, 0.045) << "60 (+ 1..2 sampling cycles) + 30";
  // the next part without a mark: 200 from that cut, to one count of the wheel
  ASSERT_TRUE(r.run_until([&] { return r.clm.cuts() == 2; }, 10s));
  EXPECT_NEAR(r.clm.last_cut_point() - first, 200.0, 0.0045);
}

TEST(ClmFlyingCutoff, MissingEosIsError35) {
  Rig r({CUTOFF_PARAMETERS});
  auto& material = r.add_master_encoder();
  r.program({{0, "NOP"}, {1, "LML 1 000020.000"}, {2, "LML 1 000020.000"}, {3, "EOS"}});
  r.run_for(20ms);
  r.enter_auto();
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  ASSERT_TRUE(r.run_until([&] { return r.clm.error() != 0; }, 5s));
  EXPECT_EQ(r.clm.error(), 0x35) << r.clm.error_message();
  EXPECT_FALSE(r.clm.coupled(1)) << "the error ends the coupling";
}

/// Manual: jog 1 forward for 200 ms and let the carriage stop, away from its origin (not homed).
void jog_carriage_away(Rig& r) {
  r.run_for(20ms);
  r.set(sys::jog_forward[0], true);
  r.run_for(200ms);
  r.set(sys::jog_forward[0], false);
  r.run_for(300ms);
}

TEST(ClmFlyingCutoff, CarriageAwayFromItsOriginIsError36) {
  Rig r({CUTOFF_PARAMETERS});
  r.add_master_encoder();
  r.program({{0, "NOP"}, {1, "LML 1 000020.000"}, {2, "EOS"}});
  jog_carriage_away(r);
  r.enter_auto();
  EXPECT_EQ(r.clm.error(), 0x36);
}

TEST(ClmFlyingCutoff, PassiveHomingOption5EntersAutomaticOnTheSwitch) {
  // §7.9 option 5 (Ax24 type 4, home switch I1.00.1): the carriage, jogged away from 0 and not
  // homed, stands on its switch: Manual -> Automatic is allowed (no 36), and the carriage is homed
  // (Ax25 = +2) where, synchronised with the material, it leaves the switch.
  Rig r({CUTOFF_PARAMETERS, {"A123", "00.00.0 I1.00.1"}, {"A124", "M2.01.0 +100 4"}, {"A125", "+00002.000"}});
  auto& material = r.add_master_encoder();
  const auto raw = [&] { return r.motion_axes[0]->status().position; };  // machine position, IU
  r.program({{0, "NOP"}, {1, "LML 1 000050.000"}, {2, "WAI 00.200"}, {3, "EOS"}, {4, "JMP 0001"}});
  jog_carriage_away(r);
  const double parked = raw();
  ASSERT_GT(parked, 0.5) << "away from the origin";
  r.set(bit("I1.00.1"), true);  // on the home switch
  r.enter_auto();
  ASSERT_EQ(r.clm.error(), 0) << r.clm.error_message();
  EXPECT_EQ(r.clm.run_state(), RunState::running);
  EXPECT_FALSE(r.clm.homed(1));
  ASSERT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  // The switch ends 1 IU ahead of where the carriage stands: it drops when the carriage passes.
  const double switch_end = parked + 1.0;
  while (!r.clm.homed(1) && r.now < TimePoint{} + 10s) {
    r.set(bit("I1.00.1"), raw() < switch_end);
    r.cycle();
    ASSERT_EQ(r.clm.error(), 0) << r.clm.error_message();
  }
  ASSERT_TRUE(r.clm.homed(1));
  EXPECT_TRUE(r.clm.coupled(1)) << "homed by the synchronous carriage";
  EXPECT_TRUE(r.get(bit("M2.01.0"))) << "the Ax24 homed output";
  // After EOS the carriage returns to its origin (CLM position 0) and waits there for the next
  // part: Ax25 (+2) behind the position sampled in the cycle that saw the switch drop (at 40 IU/s
  // the carriage moves 0.08 IU per NC cycle).
  ASSERT_TRUE(r.run_until([&] { return !r.clm.coupled(1); }, 10s));
  ASSERT_TRUE(r.run_until([&] { return std::abs(r.clm.position(1)) < 0.011; }, 2s));
  r.run_for(20ms);
  ASSERT_EQ(r.clm.error(), 0) << r.clm.error_message();
  EXPECT_NEAR(r.clm.position(1), 0.0, 0.011);
  const double home_raw = raw() - r.clm.position(1) + 2.0;
  EXPECT_GE(home_raw, switch_end - 0.011);
  EXPECT_LT(home_raw, switch_end + 0.08 + 0.011);
}

TEST(ClmFlyingCutoff, PassiveHomingOffTheSwitchIsStillError36) {
  Rig r({CUTOFF_PARAMETERS, {"A123", "00.00.0 I1.00.1"}, {"A124", "M2.01.0 +100 4"}});
  r.add_master_encoder();
  r.program({{0, "NOP"}, {1, "LML 1 000020.000"}, {2, "EOS"}});
  jog_carriage_away(r);
  r.enter_auto();
  EXPECT_EQ(r.clm.error(), 0x36) << "not homed, off the switch, away from 0";
}

TEST(ClmFlyingCutoff, ForbiddenCommandsAndOtherTasks) {
  for (const std::string line :
       {"POA 1 +000010.000 999", "HOM 1", "FOL 1 1 +1.000000", "JST 0001", "SRP 1 1 0 V600 M2.02"}) {
    Rig r({CUTOFF_PARAMETERS});
    r.add_master_encoder();
    r.program({{0, "NOP"}, {1, line}});
    r.run_for(20ms);
    r.enter_auto();
    r.run_for(10ms);
    EXPECT_EQ(r.clm.error(), 0x0A) << line;
  }
}

// ---- SRP -----------------------------------------------------------------------------------------------

TEST(ClmSrp, Mode2CorrectsTheRunningFeedFromThePrintMark) {
  Rig r;
  r.program({{0, "SET V601 = +20.0"},
             {1, "SET V602 = +5.0"},
             {2, "SRP 1 2 0 V600 M2.02"},
             {3, "PSI 1 +000100.000 999"},
             {4, "JMP 0004"}});
  r.run_for(20ms);
  r.start_auto();
  bool pulsed = false;
  while (r.clm.task(1).pc != 4 && r.now < TimePoint{} + 10s) {
    const bool pulse = !pulsed && r.pos(1) >= 70.0;
    pulsed = pulsed || pulse;
    r.set(sys::raster1, pulse);
    r.cycle();
  }
  r.run_for(300ms);
  // mark at 70.x: 29.x to go, desired 20: corrected by the limit -5 to end at 95
  EXPECT_NEAR(var(r, 600), 29.8, 0.25);
  EXPECT_NEAR(r.pos(1), 95.0, 0.011);
  EXPECT_TRUE(r.get(bit("M2.02.4"))) << "raster detected";
}

TEST(ClmSrp, NoMarkInTheWindowJumpsToTheLineInVbasePlus5) {
  Rig r;
  r.program({{0, "SET V603 = +10.0"},
             {1, "SET V604 = +30.0"},
             {2, "SET V605 = +900"},
             {3, "SRP 1 3 0 V600 M2.02"},
             {4, "PSI 1 +000050.000 999"},
             {5, "JMP 0005"},
             {900, "JMP 0900"}});
  r.run_for(20ms);
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 900 || r.clm.task(1).pc == 5; }, 10s));
  EXPECT_EQ(r.clm.task(1).pc, 900);
  EXPECT_FALSE(r.get(bit("M2.02.4")));
}

TEST(ClmSrp, VariableBlockOutsideV600ToV990IsError1F) {
  Rig r;
  r.program({{0, "SRP 1 1 0 V995 M2.02"}});
  r.start_auto();
  EXPECT_EQ(r.clm.error(), 0x1F);
}

}  // namespace
}  // namespace hil::controllers::clm14
