// SPDX-License-Identifier: MIT
// The example programs of the manual (§5.7 / digest clm14.md §4.4), each with exact results.
#include <gtest/gtest.h>

#include "rig.hpp"

namespace hil::controllers::clm14 {
namespace {

using testing::bit;
using testing::byte;
using testing::Rig;
using namespace std::chrono_literals;

/// Count the moves of axis 1 (standstill -> motion transitions). The CLM's actual velocity is
/// its encoder travel over 8 NC cycles: at standstill one increment (1/409.6 IU) of the Kv loop
/// settling reads as 0.15 IU/s, so motion is above 2 IU/s (the moves here run at 10..100 IU/s).
struct MoveCounter {
  int moves = 0;
  bool moving = false;
  void sample(const Rig& r) {
    const bool m = std::abs(r.clm.velocity(1)) > 2.0;
    if (m && !moving) ++moves;
    moving = m;
  }
};

bool run_program(Rig& r, MoveCounter& mc, Duration limit) {
  r.start_auto();
  return r.run_until(
      [&] {
        mc.sample(r);
        return r.clm.run_state() == RunState::stopped || r.clm.error() != 0;
      },
      limit);
}

TEST(ClmExamples, AccelerationChange) {
  Rig r;
  r.program({{0, "ACC 1 999 999"},
             {1, "POI 1 +000200.000 999"},
             {2, "AKN M2.00.0 1"},
             {3, "ACC 1 500 999"},
             {4, "WAI 00.100"},
             {5, "PSI 1 +000300.000 999"},
             {6, "WAI 02.000"},
             {7, "JST 0000"}});
  MoveCounter mc;
  ASSERT_TRUE(run_program(r, mc, 30s));
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
  EXPECT_EQ(mc.moves, 2);
  EXPECT_NEAR(r.pos(), 500.0, 0.011);
  EXPECT_EQ(r.clm.task(1).pc, 0) << "program end in instruction 0000";
}

TEST(ClmExamples, BacCountingAfterTheEventPositions10Times) {
  Rig r;
  r.program({{0, "WAI 01.000"}, {1, "PSI 1 +000050.000 250"}, {2, "BAC 0000 +0000 00010"}, {3, "JST 0000"}});
  MoveCounter mc;
  ASSERT_TRUE(run_program(r, mc, 60s));
  EXPECT_EQ(mc.moves, 10);
  EXPECT_NEAR(r.pos(), 500.0, 0.011);
  EXPECT_EQ(r.clm.counter(2)->count, 0);
}

TEST(ClmExamples, BacCountingBeforeTheEventPositions9Times) {
  Rig r;
  r.program(
      {{0, "BAC 0002 +0000 00010"}, {1, "JST 0000"}, {2, "PSI 1 +000050.000 250"}, {3, "WAI 01.000"}, {4, "JMP 0000"}});
  MoveCounter mc;
  ASSERT_TRUE(run_program(r, mc, 60s));
  EXPECT_EQ(mc.moves, 9);
  EXPECT_NEAR(r.pos(), 450.0, 0.011);
}

TEST(ClmExamples, CouPositions10TimesThenSetsTheOutput) {
  Rig r;
  r.program({{0, "CLC 0002"},
             {1, "AEA Q1.00.4 0"},
             {2, "COU +00000 Q1.00.4 000010"},
             {3, "PSI 1 +000050.000 999"},
             {4, "WAI 01.000"},
             {5, "BCE 0001 Q1.00.4 0"},
             {6, "JST 0001"}});
  MoveCounter mc;
  ASSERT_TRUE(run_program(r, mc, 60s));
  EXPECT_EQ(mc.moves, 10);
  EXPECT_TRUE(r.get(bit("Q1.00.4")));
  EXPECT_EQ(r.clm.task(1).pc, 1) << "waits for Start at 0001";
  EXPECT_NEAR(r.pos(), 500.0, 0.011);
}

TEST(ClmExamples, DecadeSwitchReadIntoV600) {
  // Fig. 5-10: select each decade with APE on Q1.01, read its BCD digit from I1.01.0-3 with CIO,
  // then CVT the BCD marker bytes into V600. The switch here is set to 4711.
  Rig r;
  std::vector<std::pair<int, std::string>> p;
  const std::array<std::string, 4> select{"22220001", "22220010", "22220100", "22221000"};
  // The 8-byte BCD field starts at M2.10 (M2.00.0 is the rig's position-reached flag, A127): the
  // fraction digits are M2.10-M2.12 (all 0), the integer digits from M2.13, units .. thousands.
  const std::array<std::string, 4> dest{"M2.13.0", "M2.13.4", "M2.14.0", "M2.14.4"};
  int line = 0;
  for (std::size_t d = 0; d < 4; ++d) {
    p.emplace_back(line++, "APE Q1.01 " + select[d]);
    p.emplace_back(line++, "WAI 00.02");
    p.emplace_back(line++, "CIO I1.01.0 " + dest[d] + " 04");
  }
  p.emplace_back(line++, "CVT V600 M2.10 0 1");
  p.emplace_back(line, "JST 0000");
  r.program(p);
  const std::array<int, 4> digits{1, 1, 7, 4};
  r.start_auto();
  r.run_until(
      [&] {
        const std::uint8_t sel = r.clm.image().byte(byte("Q1.01")) & 0x0F;
        std::uint8_t in = 0;
        for (std::size_t d = 0; d < 4; ++d)
          if (sel == (1U << d)) in = static_cast<std::uint8_t>(digits[d]);
        r.clm.image().set_byte(byte("I1.01"), in);
        return r.clm.run_state() == RunState::stopped;
      },
      5s);
  EXPECT_EQ(r.clm.variable(600), 4711 * micro_one);
}

TEST(ClmExamples, VeoProgramCReducesEveryVelocity) {
  Rig r({{"A127", "M2.02.4 0000.010"}, {"A108", "009999"}});
  r.program({{8, "VEO 1 4 1 500 0"},
             {9, "POI 1 +000100.000 999"},
             {10, "VCC 1 +000035.000 800 0 0"},
             {11, "VCC 1 +000050.000 600 0 0"},
             {12, "VCC 1 +000065.000 400 0 0"},
             {13, "VCC 1 +000080.000 200 0 0"},
             {14, "AKN M2.02.4 1"},
             {15, "JST 0008"}});
  std::vector<std::pair<double, double>> samples;
  r.start_auto();
  r.run_until(
      [&] {
        samples.emplace_back(r.pos(), r.clm.velocity(1));
        return r.clm.run_state() == RunState::stopped;
      },
      20s);
  const auto v_at = [&](double x) {
    for (const auto& s : samples)
      if (s.first >= x) return s.second;
    return -1.0;
  };
  EXPECT_NEAR(v_at(25), 49.95, 0.6);
  EXPECT_NEAR(v_at(45), 40.0, 0.6);
  EXPECT_NEAR(v_at(60), 30.0, 0.6);
  EXPECT_NEAR(v_at(75), 20.0, 0.6);
  EXPECT_NEAR(v_at(95), 10.0, 0.6);
  EXPECT_NEAR(r.pos(), 100.0, 0.011);
}

TEST(ClmExamples, RmiPunchAndCut) {
  // Task 1 punches at 50 / 75 IU pitch; task 2 cuts 15.5 IU after each raster mark.
  Rig r({{"B011", "0200 0000 0"}});
  r.program({{0, "PSI 1 +000050.000 999"},
             {1, "JSR 0005"},
             {2, "PSI 1 +000025.000 999"},
             {3, "JSR 0009"},
             {4, "JMP 0000"},
             {5, "AEA Q1.00.0 1"},
             {6, "WAI 00.200"},
             {7, "AEA Q1.00.0 0"},
             {8, "RTS"},
             {9, "AEA Q1.00.1 1"},
             {10, "WAI 00.200"},
             {11, "AEA Q1.00.1 0"},
             {12, "RTS"},
             {200, "RMI 1 0 I1.01.7"},
             {201, "PSI 1 +000015.500 500"},
             {202, "JSR 0210"},
             {203, "RMI 1 1 I1.01.7"},
             {204, "JMP 0200"},
             {210, "AEA Q1.00.2 1"},
             {211, "WAI 00.250"},
             {212, "AEA Q1.00.2 0"},
             {213, "WAI 00.250"},
             {214, "RTS"}});
  r.start_auto();
  ASSERT_TRUE(r.run_until([&] { return r.pos() > 20.0; }, 5s));
  r.set(bit("I1.01.7"), true);  // raster mark during the first feed
  r.cycle();
  const double mark = r.clm.latched_position(1);
  r.set(bit("I1.01.7"), false);
  ASSERT_TRUE(r.run_until([&] { return r.get(bit("Q1.00.2")); }, 5s)) << r.clm.error_message();
  EXPECT_NEAR(r.pos(), mark + 15.5, 0.011) << "cut 15.5 IU after the mark";
  ASSERT_TRUE(r.run_until([&] { return r.get(bit("Q1.00.0")); }, 5s));
  EXPECT_NEAR(r.pos(), 50.0, 0.011) << "the punch feed resumed to its target";
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
}

TEST(ClmExamples, MultitaskingTask2CountsTask3Supervises) {
  // B011 0200 0800 0: task 2 counts I1.00.0 pulses to Q1.00.7, task 3 mirrors I1.00.1 to Q1.00.6
  Rig r({{"B011", "0200 0800 0"}});
  r.program({{0, "JMP 0000"},
             {200, "AKN I1.00.0 1"},
             {201, "AKN I1.00.0 0"},
             {202, "COU +00000 Q1.00.7 000010"},
             {203, "JMP 0200"},
             {800, "BCE 0803 I1.00.1 1"},
             {801, "AEA Q1.00.6 0"},
             {802, "JMP 0800"},
             {803, "AEA Q1.00.6 1"},
             {804, "JMP 0800"}});
  r.cycle();
  r.set(bit("I1.00.1"), true);
  r.run_for(20ms);
  EXPECT_TRUE(r.get(bit("Q1.00.6"))) << "task 3 runs in Manual";
  r.start_auto();
  for (int i = 0; i < 9; ++i) {
    r.pulse(bit("I1.00.0"));
    r.run_for(10ms);
  }
  r.run_for(10ms);
  EXPECT_FALSE(r.get(bit("Q1.00.7")));
  r.pulse(bit("I1.00.0"));
  r.run_for(10ms);
  EXPECT_TRUE(r.get(bit("Q1.00.7")));
}

TEST(ClmExamples, RestartProgramsOneAndTwo) {
  for (const bool wait_for_input : {false, true}) {
    Rig r({{"B016", "2000"}});
    std::vector<std::pair<int, std::string>> p{{0, "AEA Q1.00.3 1"}, {1, "PSI 1 +000100.000 999"}, {2, "JMP 0002"}};
    if (wait_for_input) {
      p.insert(p.end(), {{2000, "AKN I1.00.4 1"}, {2001, "WAI 01.000"}, {2002, "RSV 1 0000 10000"}});
    } else {
      p.emplace_back(2000, "RSV 1 0000 10000");
    }
    r.program(p);
    r.start_auto();
    r.run_for(400ms);
    r.set(sys::automatic, false);
    r.cycle();
    r.clm.image().set_byte(byte("Q1.00"), 0);
    r.enter_auto();
    r.pulse(sys::restart);
    if (wait_for_input) {
      r.run_for(200ms);
      EXPECT_FALSE(r.get(bit("Q1.00.3")));
      r.set(bit("I1.00.4"), true);
    }
    ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 2; }, 10s)) << r.clm.error_message();
    EXPECT_TRUE(r.get(bit("Q1.00.3"))) << "outputs restored";
    EXPECT_NEAR(r.pos(), 100.0, 0.011);
  }
}

}  // namespace
}  // namespace hil::controllers::clm14
