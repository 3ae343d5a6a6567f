// SPDX-License-Identifier: MIT
// StepDirDrive against mock lines whose switches follow the steps output (closed loop):
// enable/reset pulse, ready loss, limits (NO/NC, travel direction only, lock), open-loop position.
#include "drive_rig.hpp"
#include "hil/stepdir/ip247_error.hpp"

using hil::DriveState;
using hil::stepdir::Ip247Error;
using namespace std::chrono_literals;

namespace {
const char* base = R"(
transport: stepdir
fmax_hz: 20000
fss_hz: 500
accel_hz_per_s: 200000
pulse_us: 10
)";
}

TEST(StepDirDrive, CapabilitiesAreOpenLoopWithHoming) {
  DriveRig r(base);
  EXPECT_FALSE(r.drive->capabilities().closed_loop);
  EXPECT_TRUE(r.drive->capabilities().homing);
}

TEST(StepDirDrive, EnableOutputsThe100msResetPulseThenWaitsForReady) {
  DriveRig r(base);
  r.cycle(0);
  EXPECT_EQ(r.drive->feedback().state, DriveState::switch_on_disabled);
  EXPECT_TRUE(r.axis().mock_out->output_level(2));  // reset asserted while disabled
  const auto t0 = r.clock.now().time_since_epoch().count();
  r.drive->request(hil::DriveRequest::enable);
  ASSERT_TRUE(r.enable());
  // The release edge of the reset line is exactly 100 ms after the enable.
  const auto& rec = r.axis().mock_out->recorded();
  auto it = std::find_if(rec.begin(), rec.end(), [](const auto& e) { return e.line == 2 && !e.level; });
  ASSERT_NE(it, rec.end());
  EXPECT_EQ(it->t_ns - t0, 100'000'000);
  EXPECT_EQ(r.drive->feedback().state, DriveState::operation_enabled);
}

TEST(StepDirDrive, FollowsPositionCommandExactlyOpenLoop) {
  DriveRig r(base);
  ASSERT_TRUE(r.enable());
  // A smooth 1 s move of 7 321 steps, then hold.
  for (int i = 0; i <= 1000; ++i) {
    const double s = i / 1000.0;
    r.cycle(static_cast<std::int64_t>(std::llround(7321 * (3 * s * s - 2 * s * s * s))));
  }
  for (int i = 0; i < 50; ++i) r.cycle(7321);
  EXPECT_EQ(r.drive->feedback().position_inc, 7321);
  EXPECT_EQ(r.plant_position(), 7321);  // the plant counted exactly the steps output
  EXPECT_EQ(r.sd->lag_cycles(), 0U);
  r.expect_clean();
}

TEST(StepDirDrive, ReadyLossIsFault53AndLosesSynchronisation) {
  DriveRig r(base);
  ASSERT_TRUE(r.enable());
  r.sd->inject_fault("not_ready", true);
  r.cycle(0);
  const auto& fb = r.drive->feedback();
  EXPECT_EQ(fb.state, DriveState::fault);
  EXPECT_EQ(fb.fault.code, make_error_code(Ip247Error::power_section_off));
  EXPECT_STREQ(fb.fault.code.category().name(), "ip247");
  EXPECT_EQ(fb.fault.code.value(), 53);
  EXPECT_FALSE(fb.referenced);
  // Reset is refused while ready is still low, accepted once it is back.
  r.drive->request(hil::DriveRequest::fault_reset);
  r.cycle(0);
  EXPECT_EQ(r.drive->feedback().state, DriveState::fault);
  r.sd->inject_fault("not_ready", false);
  r.cycle(0);
  r.drive->request(hil::DriveRequest::fault_reset);
  r.cycle(0);
  EXPECT_EQ(r.drive->feedback().state, DriveState::operation_enabled);
}

TEST(StepDirDrive, ReadyNeverComingIsFault53) {
  DriveRig r(std::string(base) + "mock: {ready: false}\nready_timeout_ms: 50\n");
  r.drive->request(hil::DriveRequest::enable);
  ASSERT_TRUE(r.run_until(
      0, [&] { return r.drive->feedback().state == DriveState::fault; }, 1000));
  EXPECT_EQ(r.drive->feedback().fault.code.value(), 53);
  EXPECT_GE(r.clock.now().time_since_epoch(), 150ms);
}

TEST(StepDirDrive, LimitEndStopsLocksAndUnlocksMovingAway) {
  DriveRig r(std::string(base) + "mock: {limit_end_at: 500, limit_start_at: -500}\n");
  ASSERT_TRUE(r.enable());
  std::int64_t cmd = 0;
  ASSERT_TRUE(r.run_until(
      0,
      [&] {
        cmd = std::min<std::int64_t>(cmd + 5, 2000);  // 5 kHz toward the end switch
        r.drive->write(hil::CycleTime{r.clock.now(), r.period},
                       hil::DriveCommand{hil::CommandMode::position, cmd, 0, 0});
        return r.drive->feedback().state == DriveState::fault;
      },
      1000));
  const auto& fb = r.drive->feedback();
  EXPECT_EQ(fb.fault.code, make_error_code(Ip247Error::limit_end_overrun));
  EXPECT_GE(fb.position_inc, 500);
  EXPECT_LE(fb.position_inc, 520);  // stopped within about one cycle of steps
  EXPECT_EQ(r.sd->locked_direction(), 1);
  EXPECT_TRUE(r.drive->capabilities().digital_inputs);
  EXPECT_EQ(fb.digital_inputs, hil::digital_input::positive_limit) << "the end limit as 0x60FD bit 1";
  const auto stop = fb.position_inc;
  r.drive->request(hil::DriveRequest::fault_reset);
  for (int i = 0; i < 50; ++i) r.cycle(stop + 100);  // forward stays locked
  EXPECT_EQ(r.drive->feedback().position_inc, stop);
  EXPECT_EQ(r.drive->feedback().state, DriveState::operation_enabled);
  for (int i = 0; i < 200; ++i) r.cycle(stop - 100);  // backward is allowed and releases the switch
  EXPECT_EQ(r.drive->feedback().position_inc, stop - 100);
  EXPECT_EQ(r.sd->locked_direction(), 0);
  EXPECT_EQ(r.drive->feedback().digital_inputs, 0U);
  r.expect_clean();
}

TEST(StepDirDrive, LimitSeenOnlyInTravelDirection) {
  DriveRig r(base);
  ASSERT_TRUE(r.enable());
  r.sd->inject_fault("limit_start", true);  // actuated by hand, behind us
  for (int i = 0; i < 100; ++i) r.cycle(i * 3);
  r.refresh();
  EXPECT_EQ(r.drive->feedback().state, DriveState::operation_enabled);
  EXPECT_EQ(r.drive->feedback().position_inc, 297);
  r.cycle(290);  // about to move toward it: refused with error 25
  r.refresh();
  EXPECT_EQ(r.drive->feedback().fault.code.value(), 25);
  EXPECT_EQ(r.drive->feedback().position_inc, 297);
}

TEST(StepDirDrive, NormallyClosedBrokenWireIsOverrunInTravelDirection) {
  DriveRig r(std::string(base) + "limit_switches: normally_closed\n");
  ASSERT_TRUE(r.enable());
  r.sd->inject_fault("broken_wire_end", true);
  for (int i = 0; i < 20; ++i) r.cycle(-i);  // moving away from it: fine
  EXPECT_EQ(r.drive->feedback().state, DriveState::operation_enabled);
  r.cycle(100);
  r.refresh();
  EXPECT_EQ(r.drive->feedback().fault.code.value(), 26);
}

TEST(StepDirDrive, Ip247ProfileHitsAbsoluteTargetWithFirstIntervalOneOverFss) {
  DriveRig r(std::string(base) + "profile: ip247\nbacklash: 7\n");
  ASSERT_TRUE(r.enable());
  ASSERT_TRUE(r.run_until(4000, [&] { return !r.sd->planner().moving() && r.drive->feedback().position_inc == 4000; }));
  ASSERT_TRUE(
      r.run_until(-1234, [&] { return !r.sd->planner().moving() && r.drive->feedback().position_inc == -1234; }));
  EXPECT_EQ(r.plant_position(), -1234 - 7);  // backlash taken up on the reversal, position unchanged by it
  EXPECT_EQ(r.axis().sink.verifier.stats().first_interval_ns, 2'000'000);  // 1/500 Hz
  r.expect_clean();
}

namespace {
/// Shortest interval between rising step edges (line 0) recorded on the mock output bank.
std::int64_t min_step_interval_ns(const DriveRig& r) {
  std::int64_t last = -1, best = INT64_MAX;
  for (const auto& e : r.factory.axes().front()->mock_out->recorded()) {
    if (e.line != 0 || !e.level) continue;
    if (last >= 0) best = std::min(best, e.t_ns - last);
    last = e.t_ns;
  }
  return best;
}
}  // namespace

TEST(StepDirDrive, Ip247ProfileRunsEachMoveAtItsProgrammedSpeed) {
  // The ip247 profile is a drive-profile drive: the motion core's move carries the programmed
  // speed, which becomes the pulse frequency (1 increment = 1 step), not fmax.
  DriveRig r(std::string(base) + "profile: ip247\n");
  EXPECT_TRUE(r.drive->capabilities().drive_profile);
  ASSERT_TRUE(r.enable());
  hil::DriveCommand c;
  c.move = {hil::DriveMove::Kind::position, 1, 3000, 2000.0, 0.0, 0.0};  // 2 kHz
  const auto run = [&](const hil::DriveCommand& cmd, std::int64_t end) {
    for (int i = 0; i < 100'000; ++i) {
      hil::CycleTime t{r.clock.now(), r.period};
      r.drive->read(t);
      r.drive->write(t, cmd);
      r.clock.advance(r.period);
      if (!r.sd->planner().moving() && r.drive->feedback().position_inc == end) return true;
    }
    return false;
  };
  ASSERT_TRUE(run(c, 3000));
  EXPECT_EQ(min_step_interval_ns(r), 500'000);  // 1 / 2 kHz
  // Above fmax: clamped to fmax (20 kHz = 50 us), the move still runs.
  c.move = {hil::DriveMove::Kind::position, 2, 60'000, 1e6, 0.0, 0.0};
  ASSERT_TRUE(run(c, 60'000));
  EXPECT_EQ(min_step_interval_ns(r), 50'000);
  // A velocity move at -5 kHz, then hold: brakes along the ramp and stands.
  c.move = {hil::DriveMove::Kind::velocity, 3, 0, -5000.0, 0.0, 0.0};
  for (int i = 0; i < 200; ++i) {
    hil::CycleTime t{r.clock.now(), r.period};
    r.drive->read(t);
    r.drive->write(t, c);
    r.clock.advance(r.period);
  }
  EXPECT_LT(r.drive->feedback().position_inc, 60'000 - 500);
  c.move = {hil::DriveMove::Kind::hold, 4, 0, 0.0, 0.0, 0.0};
  for (int i = 0; i < 500 && r.sd->planner().moving(); ++i) {
    hil::CycleTime t{r.clock.now(), r.period};
    r.drive->read(t);
    r.drive->write(t, c);
    r.clock.advance(r.period);
  }
  EXPECT_FALSE(r.sd->planner().moving());
  const auto at = r.sd->planner().position();
  for (int i = 0; i < 20; ++i) {
    hil::CycleTime t{r.clock.now(), r.period};
    r.drive->read(t);
    r.drive->write(t, c);
    r.clock.advance(r.period);
  }
  EXPECT_EQ(r.sd->planner().position(), at);  // the hold stays: nothing re-starts the old move
  r.expect_clean();
}

TEST(StepDirConfig, ErrorsNameKeyAndMdError) {
  hil::VirtualClock clock;
  hil::RunEnvironment env{clock, true, nullptr, "", std::chrono::milliseconds(1), false, {}};
  env.source_file = "s.yaml";
  hil::drives::stepdir::StepDirTransportFactory f;
  auto bad = [&](const std::string& y) {
    auto d = f.make_drive("x", YAML::Load(y), env);
    EXPECT_FALSE(d);
    return d ? std::string() : d.error().describe();
  };
  EXPECT_NE(bad("transport: stepdir\nfmax_hz: 200000\n").find("IP247 MD error 3"), std::string::npos);
  EXPECT_NE(bad("transport: stepdir\nfmax_hz: 100000\npulse_us: 6\n").find("MD error 2"), std::string::npos);
  EXPECT_NE(bad("transport: stepdir\nfss_hz: 20000\n").find("MD error 22"), std::string::npos);
  EXPECT_NE(bad("transport: stepdir\nbacklash: 70000\n").find("MD error 20"), std::string::npos);
  EXPECT_NE(bad("transport: stepdir\nfmax_hx: 1\n").find("fmax_hx"), std::string::npos);
  EXPECT_NE(bad("transport: stepdir\nprofile: trapez\n").find("unknown profile"), std::string::npos);
  EXPECT_NE(bad("transport: stepdir\nchip: gpiochip0\n").find("lines"), std::string::npos);
  EXPECT_NE(bad("transport: stepdir\nhoming: {speed_hz: 100}\n").find("MD error 17"), std::string::npos);
  EXPECT_NE(bad("transport: stepdir\nlines: {step: -3}\n").find("neither"), std::string::npos);
  // A chip that does not exist: clear error, no crash.
  EXPECT_NE(bad("transport: stepdir\nchip: gpiochip-none\nlines: {step: 0, dir: 1}\n").find("cannot open"),
            std::string::npos);
}

TEST(StepDirTransport, FinishReportFailsTheRunOnATimingViolation) {
  DriveRig r(base);
  ASSERT_TRUE(r.enable());
  for (int i = 0; i < 10; ++i) r.cycle(i);
  for (int i = 0; i < 5; ++i) r.cycle(9);
  auto good = r.factory.finish(hil::CycleTime{r.clock.now(), r.period});
  EXPECT_TRUE(good.ok);
  ASSERT_FALSE(good.lines.empty());
  EXPECT_NE(good.lines[0].find("timing rules held"), std::string::npos) << good.lines[0];
  // A pulse far too short on the recorded stream (as a broken writer would produce).
  const std::int64_t t = r.clock.now().time_since_epoch().count() + 10'000'000;
  const std::vector<hil::gpio::Edge> bad = {{t, 0, true}, {t + 1'000, 0, false}};
  r.axis().sink.output(bad);
  auto rep = r.factory.finish(hil::CycleTime{r.clock.now(), r.period});
  EXPECT_FALSE(rep.ok);
  EXPECT_NE(rep.lines[0].find("pulse_width"), std::string::npos) << rep.lines[0];
}
