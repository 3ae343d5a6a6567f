// SPDX-License-Identifier: MIT
// The IP247 reference-point run (manual §4.2.3) against a mock cam and limit switches that
// change with the steps output: the normal sequence, special cases 1-3, the cam watchdog
// (error 59) and the synchronous reference point.
#include "drive_rig.hpp"

using hil::DriveState;

namespace {
// Reference direction backward; cam [-2000, -1500]; end limit at +3000.
std::string axis(std::int64_t start, const std::string& homing_extra = "") {
  return std::string(R"(
transport: stepdir
fmax_hz: 20000
fss_hz: 500
accel_hz_per_s: 200000
pulse_us: 10
homing: {direction: backward, speed_hz: 8000, coordinate: 100000)") +
         homing_extra + "}\n" +
         "mock: {limit_end_at: 3000, limit_start_at: -6000, cam: [-2000, -1500], initial_position: " +
         std::to_string(start) + "}\n";
}

struct Track {
  std::int64_t min = INT64_MAX, max = INT64_MIN;
};

bool home(DriveRig& r, Track& t) {
  if (!r.drive->request(hil::DriveRequest::home)) return false;
  // The motion core holds the command at the actual position while the drive homes.
  for (int i = 0; i < 200'000; ++i) {
    hil::CycleTime c{r.clock.now(), r.period};
    r.drive->read(c);
    r.drive->write(c, hil::DriveCommand{hil::CommandMode::position, r.drive->feedback().position_inc, 0, 0});
    r.clock.advance(r.period);
    const auto p = r.plant_position();
    t.min = std::min(t.min, p);
    t.max = std::max(t.max, p);
    if (!r.sd->planner().moving() && (r.sd->homing_phase() == hil::drives::stepdir::HomingPhase::idle ||
                                      r.drive->feedback().state == DriveState::fault)) {
      r.drive->read(hil::CycleTime{r.clock.now(), r.period});
      return true;
    }
  }
  return false;
}
}  // namespace

TEST(ReferenceRun, NormalSequenceReversesAtLimitAndReferencesAtCamEdge) {
  DriveRig r(axis(0));
  ASSERT_TRUE(r.enable());
  EXPECT_FALSE(r.drive->feedback().referenced);
  Track t;
  ASSERT_TRUE(home(r, t));
  ASSERT_EQ(r.drive->feedback().state, DriveState::operation_enabled) << r.drive->feedback().fault.describe();
  EXPECT_TRUE(r.drive->feedback().referenced);
  EXPECT_GE(t.max, 3000);                // went against the reference direction to the end limit
  EXPECT_LT(t.min, -2000);               // passed the cam in the reference direction
  EXPECT_EQ(r.plant_position(), -2001);  // first position off the cam, reached in single steps
  EXPECT_EQ(r.drive->feedback().position_inc, 100000);
  r.cycle(100000);
  EXPECT_EQ(r.drive->feedback().position_inc, 100000);
  r.expect_clean();
}

TEST(ReferenceRun, SpecialCase1CamBeforeLimitReversesAtCamEnd) {
  DriveRig r(axis(-2500));
  ASSERT_TRUE(r.enable());
  Track t;
  ASSERT_TRUE(home(r, t));
  ASSERT_TRUE(r.drive->feedback().referenced) << r.drive->feedback().fault.describe();
  EXPECT_LT(t.max, 3000);  // never touched the limit switch
  EXPECT_GT(t.max, -1500);
  EXPECT_EQ(r.plant_position(), -2001);
}

TEST(ReferenceRun, SpecialCase2StartOnReversalLimit) {
  DriveRig r(axis(3500));
  ASSERT_TRUE(r.enable());
  Track t;
  ASSERT_TRUE(home(r, t));
  ASSERT_TRUE(r.drive->feedback().referenced) << r.drive->feedback().fault.describe();
  EXPECT_EQ(t.max, 3500);  // moved off immediately in the reference direction
  EXPECT_EQ(r.plant_position(), -2001);
}

TEST(ReferenceRun, SpecialCase3StartOnCamLeavesInSingleSteps) {
  DriveRig r(axis(-1800));
  ASSERT_TRUE(r.enable());
  Track t;
  ASSERT_TRUE(home(r, t));
  ASSERT_TRUE(r.drive->feedback().referenced);
  EXPECT_EQ(t.max, -1800);
  EXPECT_EQ(r.plant_position(), -2001);
  EXPECT_EQ(r.sd->planner().steps_total(), 201U);  // 201 single steps, nothing else
}

TEST(ReferenceRun, CamNotLeftWithin2500StepsIsError59) {
  DriveRig r(axis(-1800));
  ASSERT_TRUE(r.enable());
  r.sd->inject_fault("cam_stuck", true);
  Track t;
  ASSERT_TRUE(home(r, t));
  EXPECT_EQ(r.drive->feedback().state, DriveState::fault);
  EXPECT_EQ(r.drive->feedback().fault.code.value(), 59);
  EXPECT_FALSE(r.drive->feedback().referenced);  // an aborted run leaves no reference point
  EXPECT_EQ(r.sd->planner().steps_total(), 2500U);
}

TEST(ReferenceRun, SynchronousReferenceEndsOnPatternCounterZero) {
  DriveRig r(axis(-1800, ", sync: true, patterns: 8"));
  ASSERT_TRUE(r.enable());
  const auto before = r.axis().mock_out->recorded().size();
  Track t;
  ASSERT_TRUE(home(r, t));
  ASSERT_TRUE(r.drive->feedback().referenced);
  EXPECT_EQ(r.sd->pattern_counter(), 0);
  EXPECT_LE(r.plant_position(), -2001);
  EXPECT_GT(r.plant_position(), -2001 - 8);
  // A 100 ms reset pulse was output at the start of the run.
  const auto& rec = r.axis().mock_out->recorded();
  std::int64_t rise = -1, fall = -1;
  for (std::size_t i = before; i < rec.size(); ++i) {
    if (rec[i].line == 2 && rec[i].level && rise < 0) rise = rec[i].t_ns;
    if (rec[i].line == 2 && !rec[i].level && rise >= 0 && fall < 0) fall = rec[i].t_ns;
  }
  ASSERT_GE(rise, 0);
  EXPECT_EQ(fall - rise, 100'000'000);
}

TEST(ReferenceRun, HomeRefusedWhenNotEnabled) {
  DriveRig r(axis(0));
  EXPECT_FALSE(r.drive->request(hil::DriveRequest::home));
}
