// SPDX-License-Identifier: MIT
// CLM1.4 modes and safety (§7): mode inputs, E-Stop, drive enable / brake, Start, Immediate
// Stop, JST, !STOP, errors and B018, task 3, tasks 2/4/5, restart vector, logic task, vectors.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "rig.hpp"

namespace hil::controllers::clm14 {
namespace {

using testing::bit;
using testing::byte;
using testing::Rig;
using namespace std::chrono_literals;

TEST(ClmModes, ModeInputsAndOutputs) {
  Rig r;
  r.cycle();
  EXPECT_EQ(r.clm.mode(), Mode::manual);
  EXPECT_TRUE(r.get(sys::out_manual));
  EXPECT_TRUE(r.get(sys::out_error)) << "active low: no error";
  r.set(sys::parameter_mode, true);
  r.cycle();
  EXPECT_EQ(r.clm.mode(), Mode::parameter);
  EXPECT_TRUE(r.get(sys::out_parameter));
  r.set(sys::automatic, true);
  r.cycle();
  EXPECT_EQ(r.clm.error(), 0x08) << "Parameter + Automatic";
  EXPECT_FALSE(r.get(sys::out_error));
  r.set(sys::parameter_mode, false);
  r.cycle();
  r.pulse(sys::external_clear);
  EXPECT_EQ(r.clm.error(), 0);
  EXPECT_EQ(r.clm.mode(), Mode::automatic);
}

TEST(ClmModes, DriveEnableThenBrakeAfter200ms) {
  Rig r;
  r.cycle();
  EXPECT_TRUE(r.get(sys::out_drive_enable[0]));
  EXPECT_FALSE(r.get(sys::out_brake[0]));
  r.run_for(196ms);
  EXPECT_FALSE(r.get(sys::out_brake[0]));
  r.run_for(4ms);
  EXPECT_TRUE(r.get(sys::out_brake[0]));
  r.set(sys::enable[0], false);
  r.cycle();
  EXPECT_FALSE(r.get(sys::out_drive_enable[0])) << "dropped at once";
  EXPECT_FALSE(r.get(sys::out_brake[0]));
}

TEST(ClmModes, AutomaticWithoutEnableIsDriveNotReady) {
  Rig r({}, 2);
  r.set(sys::enable[1], false);
  r.enter_auto();
  EXPECT_EQ(r.clm.error(), 0x70) << "axis 2: 0x40 + 0x30";
}

TEST(ClmModes, EmergencyStopDropsEverythingUntilRestoredAndCleared) {
  Rig r;
  r.program({{0, "AEA Q1.00.1 1"}, {1, "POI 1 +001000.000 999"}, {2, "JMP 0002"}});
  r.start_auto();
  r.run_for(300ms);
  EXPECT_TRUE(r.get(bit("Q1.00.1")));
  r.set(sys::emergency_stop_ok, false);
  r.cycle();
  EXPECT_EQ(r.clm.error(), 0x03);
  EXPECT_FALSE(r.get(bit("Q1.00.1")));
  EXPECT_FALSE(r.get(sys::out_error)) << "all outputs off, Error too";
  EXPECT_FALSE(r.get(sys::out_drive_enable[0]));
  EXPECT_EQ(r.clm.run_state(), RunState::idle);
  r.pulse(sys::external_clear);
  EXPECT_EQ(r.clm.error(), 0x03) << "not clearable while E-Stop is open";
  r.set(sys::emergency_stop_ok, true);
  r.pulse(sys::external_clear);
  EXPECT_EQ(r.clm.error(), 0);
  EXPECT_EQ(r.clm.task(1).pc, 0) << "restart from 0000 after clearing";
}

TEST(ClmModes, ImmediateStopKeepsTheRemainingDistance) {
  Rig r;
  r.program({{0, "PSI 1 +000100.000 999"}, {1, "JMP 0001"}});
  r.start_auto();
  r.run_for(500ms);
  r.set(sys::immediate_stop_ok, false);
  r.run_for(500ms);
  EXPECT_EQ(r.clm.run_state(), RunState::stopped);
  EXPECT_FALSE(r.get(sys::out_run));
  const double held = r.pos();
  EXPECT_LT(held, 90.0);
  EXPECT_NEAR(r.clm.velocity(1), 0.0, 0.01);
  r.set(sys::immediate_stop_ok, true);
  r.cycle();
  EXPECT_EQ(r.clm.run_state(), RunState::stopped) << "needs Start";
  r.pulse(sys::start);
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 1; }, 10s));
  EXPECT_NEAR(r.pos(), 100.0, 0.011);
}

TEST(ClmModes, JstStopsAndStartResumesAtItsTarget) {
  Rig r;
  r.program({{0, "AEA Q1.00.0 1"}, {1, "JST 0005"}, {5, "AEA Q1.00.1 1"}, {6, "JMP 0006"}});
  r.start_auto();
  r.run_for(20ms);
  EXPECT_EQ(r.clm.run_state(), RunState::stopped);
  EXPECT_EQ(r.clm.task(1).pc, 5);
  EXPECT_TRUE(r.get(bit("Q1.00.0"))) << "outputs unchanged";
  EXPECT_FALSE(r.get(bit("Q1.00.1")));
  r.pulse(sys::start);
  r.run_for(10ms);
  EXPECT_TRUE(r.get(bit("Q1.00.1")));
}

TEST(ClmModes, StopCommandNeedsStartCommand) {
  Rig r;
  r.program({{0, "JMP 0000"}});
  r.start_auto();
  r.clm.command_stop();
  r.pulse(sys::start);
  EXPECT_EQ(r.clm.run_state(), RunState::stopped) << "after !STOP only !START resumes";
  EXPECT_TRUE(r.clm.command_start());
  EXPECT_EQ(r.clm.run_state(), RunState::running);
}

TEST(ClmModes, TasksRunInOrderAndTask3InManualAndThroughFaults) {
  // B011: task 2 at 0200, task 3 at 0300; B012: task 4 at 0400, task 5 at 0500
  Rig r({{"B011", "0200 0300 0"}, {"B012", "0400 0500"}});
  r.program({{0, "AEA M2.00.7 1"},
             {1, "JMP 0001"},
             {200, "JMP 0200"},
             {300, "MAT V600 = V600 + +1"},
             {301, "JMP 0300"},
             {400, "AKN M2.00.7 1"},
             {401, "AEA M2.01.0 1"},
             {402, "JMP 0402"},
             {500, "JMP 0500"}});
  r.cycle();
  r.run_for(20ms);
  EXPECT_GT(r.clm.variable(600), 0) << "task 3 runs in Manual";
  EXPECT_FALSE(r.clm.task(1).active);
  r.enter_auto();
  r.set(sys::start, true);
  r.cycle();  // start cycle: task 1 sets M2.00.7, task 4 sees it in the same cycle
  EXPECT_EQ(r.clm.task(4).pc, 401);
  EXPECT_TRUE(r.clm.task(2).active);
  EXPECT_TRUE(r.clm.task(5).active);
  EXPECT_EQ(r.clm.task(2).pc, 200);
  // a fault stops tasks 1, 2, 4, 5; task 3 keeps counting
  r.set(sys::enable[0], false);
  r.cycle();
  EXPECT_EQ(r.clm.error(), 0x40);
  EXPECT_FALSE(r.clm.task(1).active);
  EXPECT_FALSE(r.clm.task(4).active);
  const Micro before = r.clm.variable(600);
  r.run_for(20ms);
  EXPECT_GT(r.clm.variable(600), before);
}

TEST(ClmModes, Task3MustNotMoveAxes) {
  Rig r({{"B011", "0000 0300 0"}});
  r.program({{300, "POI 1 +000010.000 999"}});
  r.run_for(10ms);
  EXPECT_EQ(r.clm.error(), 0x0A);
  EXPECT_EQ(r.clm.error_item(1), "0300");
}

TEST(ClmModes, ErrorClearsOutputsPerB018AndShowsTheCode) {
  // vector #39: B018 = 3 ...: the code goes to Q1.02; position lag of axis 2 = 0x73
  Rig r({{"B018", "3 2000000"}, {"A206", "000100.000"}}, 2);
  r.program({{0, "AEA Q1.00.0 1"}, {1, "AEA Q1.01.0 1"}, {2, "POI 2 +000500.000 999"}, {3, "JMP 0003"}});
  r.start_auto();
  r.run_for(100ms);
  ASSERT_TRUE(r.get(bit("Q1.00.0")));
  // the drive of axis 2 runs away from its command: a plant fault
  auto* fi = dynamic_cast<FaultInjectable*>(&r.motion_axes[1]->drive());
  ASSERT_NE(fi, nullptr);
  ASSERT_TRUE(fi->inject_fault("following_blowup", true));
  ASSERT_TRUE(r.run_until([&] { return r.clm.error() != 0; }, 5s));
  EXPECT_EQ(r.clm.error(), 0x73) << r.clm.error_message();
  EXPECT_EQ(r.clm.image().byte(byte("Q1.02")), 0x73);
  EXPECT_TRUE(r.get(bit("Q1.00.0"))) << "B018 g = 2: Q1.00 never cleared";
  EXPECT_FALSE(r.get(bit("Q1.01.0"))) << "g = 0: cleared on the fault";
  EXPECT_FALSE(r.clm.homed(2));
}

TEST(ClmModes, RestartResumesWhereAutomaticWasLeft) {
  Rig r;
  r.program({{0, "AEA Q1.00.3 1"}, {1, "PSI 1 +000200.000 999"}, {2, "AEA Q1.00.5 1"}, {3, "JMP 0003"}});
  r.start_auto();
  r.run_for(800ms);
  r.set(sys::automatic, false);
  r.cycle();
  EXPECT_TRUE(r.clm.restart_possible());
  EXPECT_TRUE(r.get(sys::out_restart_possible));
  r.run_for(500ms);
  const double left_at = r.pos();
  EXPECT_LT(left_at, 190.0);
  r.enter_auto();
  r.pulse(sys::restart);
  EXPECT_EQ(r.clm.run_state(), RunState::running);
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 3; }, 10s));
  EXPECT_NEAR(r.pos(), 200.0, 0.011) << "the remaining distance was kept";
  EXPECT_FALSE(r.clm.restart_possible());
}

TEST(ClmModes, RestartProgramWithRsv) {
  // §4.4 restart program 3: restore outputs, wait for I1.00.4, then terminate without outputs
  Rig r({{"B016", "2000"}});
  r.program({{0, "AEA Q1.00.2 1"},
             {1, "WAI 05.000"},
             {2, "AEA Q1.00.6 1"},
             {3, "JMP 0003"},
             {2000, "RSV 0 0000 10000"},
             {2001, "AKN I1.00.4 1"},
             {2002, "WAI 01.000"},
             {2003, "RSV 1 0000 00000"}});
  r.start_auto();
  r.run_for(100ms);
  r.set(sys::automatic, false);
  r.cycle();
  r.clm.image().set_byte(byte("Q1.00"), 0);  // outputs lost meanwhile
  r.enter_auto();
  r.pulse(sys::restart);
  r.run_for(20ms);
  EXPECT_EQ(r.clm.task(1).pc, 2001);
  EXPECT_TRUE(r.get(bit("Q1.00.2"))) << "RSV 0 ... 1xxxx restored the outputs";
  r.set(bit("I1.00.4"), true);
  r.run_for(1100ms);
  EXPECT_EQ(r.clm.task(1).pc, 1) << "back in the interrupted WAI";
  ASSERT_TRUE(r.run_until([&] { return r.get(bit("Q1.00.6")); }, 6s));
}

TEST(ClmModes, ByteWritesOfNcKeepTheLogicTasksOutputBits) {
  Rig r;
  r.clm.store_logic_line(0, "LD I1.00.0");
  r.clm.store_logic_line(1, "SETC Q1.00.7");  // the LT owns Q1.00.7 but leaves it alone while I1.00.0 = 0
  r.clm.store_logic_line(2, "END");
  // CVT writes whole bytes Q1.00..Q1.07 (V600 = 0: all 00), APE single bits of Q1.01.
  r.program({{0, "CVT V600 Q1.00 0 0"}, {1, "APE Q1.01 11111111"}, {2, "JMP 0000"}});
  r.run_for(10ms);
  r.set(bit("I1.00.0"), true);
  r.run_for(10ms);
  r.set(bit("I1.00.0"), false);
  r.set(bit("Q1.00.3"), true);
  ASSERT_TRUE(r.get(bit("Q1.00.7")));
  r.start_auto();
  r.run_for(20ms);
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
  EXPECT_TRUE(r.get(bit("Q1.00.7"))) << "the LT's bit of the byte CVT cleared";
  EXPECT_FALSE(r.get(bit("Q1.00.3"))) << "the other bits of that byte follow NC";
  EXPECT_TRUE(r.get(bit("Q1.01.5")));
}

TEST(ClmModes, LogicTaskCompiledOnLeavingParameterMode) {
  Rig r;
  r.clm.store_logic_line(0, "LD I1.00.0");
  r.clm.store_logic_line(1, "ST Q1.00.7");
  r.clm.store_logic_line(2, "END");
  r.program({{0, "AEA Q1.00.7 0"}, {1, "JMP 0000"}});
  r.run_for(10ms);
  r.set(bit("I1.00.0"), true);
  r.run_for(10ms);
  EXPECT_TRUE(r.get(bit("Q1.00.7")));
  r.start_auto();
  r.run_for(20ms);
  EXPECT_TRUE(r.get(bit("Q1.00.7"))) << "an LT output is no longer driven by NC";
  // a bad logic program: error 38 on leaving Parameter mode, with the line
  r.set(sys::automatic, false);
  r.set(sys::parameter_mode, true);
  r.cycle();
  r.clm.store_logic_line(1, "ST I1.00.1");
  r.set(sys::parameter_mode, false);
  r.cycle();
  EXPECT_EQ(r.clm.error(), 0x38);
  EXPECT_EQ(r.clm.error_item(2), "0001");
  r.pulse(sys::external_clear);
  EXPECT_EQ(r.clm.error(), 0x38) << "cleared only by a program that compiles";
  // changing it outside Parameter mode is 39
  Rig q;
  q.cycle();
  q.clm.store_logic_line(5, "NOP ");
  EXPECT_EQ(q.clm.error(), 0x39);
}

TEST(ClmModes, ParameterErrorOnLeavingParameterMode) {
  Rig r;
  r.cycle();
  r.set(sys::parameter_mode, true);
  r.cycle();
  r.params["A106"] = "abc";
  r.set(sys::parameter_mode, false);
  r.cycle();
  EXPECT_EQ(r.clm.error(), 0x02);
  EXPECT_EQ(r.clm.error_item(0), "A106");
  r.set(sys::parameter_mode, true);
  r.cycle();
  r.params["A106"] = "000100.000";
  r.set(sys::parameter_mode, false);
  r.cycle();
  EXPECT_EQ(r.clm.error(), 0);
}

TEST(ClmModes, ManualVectorRunsInManual) {
  // §4.4: B014 I1.01.0 0 0400; 0400 AEA Q1.00.0 0 / 0401 AEA Q1.00.1 0 / 0402 RTS
  Rig r({{"B014", "I1.01.0 0 0400"}});
  r.program({{400, "AEA Q1.00.0 0"}, {401, "AEA Q1.00.1 0"}, {402, "RTS"}});
  r.cycle();
  r.clm.image().set_byte(byte("Q1.00"), 0x03);
  r.pulse(bit("I1.01.0"));
  r.run_for(10ms);
  EXPECT_EQ(r.clm.image().byte(byte("Q1.00")), 0);
  EXPECT_FALSE(r.clm.task(1).active);
  EXPECT_FALSE(r.get(sys::out_run)) << "a manual vector does not set Run Task";
}

TEST(ClmModes, InterruptVectorRedirectsTask1) {
  Rig r({{"B015", "I1.02.0 1 1 0700"}});
  r.program(
      {{0, "JSR 0010"}, {10, "POI 1 +001000.000 999"}, {11, "JMP 0011"}, {700, "AEA Q1.00.0 1"}, {701, "JMP 0701"}});
  r.start_auto();
  r.run_for(100ms);
  r.pulse(bit("I1.02.0"));
  r.run_for(10ms);
  EXPECT_TRUE(r.get(bit("Q1.00.0")));
  EXPECT_EQ(r.clm.task(1).depth, 0) << "stack cleared";
  r.run_for(2s);
  EXPECT_LT(r.pos(), 100.0) << "p = 1: the move was aborted";
}

TEST(ClmModes, StateSurvivesAPowerLossAndRestarts) {
  Rig r;
  r.program({{0, "COU +00000 Q1.00.4 000100"}, {1, "PSI 1 +000050.000 999"}, {2, "JMP 0000"}});
  ASSERT_TRUE(r.clm.set_variable(700, 42 * micro_one));
  r.start_auto();
  r.run_for(1500ms);
  const int count = r.clm.counter(0)->count;
  EXPECT_GE(count, 2);
  const auto saved = r.clm.to_json();
  Rig q;  // the same controller after a power cycle
  ASSERT_TRUE(q.clm.from_json(saved));
  q.cycle();
  EXPECT_EQ(q.clm.counter(0)->count, count);
  EXPECT_EQ(q.clm.variable(700), 42 * micro_one);
  EXPECT_TRUE(q.clm.restart_possible());
  EXPECT_EQ(q.clm.line_text(1), "PSI 1 +000050.000 999");
}

}  // namespace
}  // namespace hil::controllers::clm14
