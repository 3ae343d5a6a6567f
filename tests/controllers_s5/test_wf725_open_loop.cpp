// SPDX-License-Identifier: MIT
// WF 725/726 open-loop control (AK, MD 4 = 3/4; docs/wf725.md "Open-loop control"): the speed
// stages MD 42-48 by the remaining distance, DL 4 in BCD, the cut-off point outputs, the MD 1/2
// voltage ramps, the stop model after speed 0 (MD 48), errors 21, 22, 7A and 95 on the actual
// position. Manual: seeds/wf725-726.md §1.3, §3.5 MD 1/2, MD 10, MD 11-14, MD 30, MD 42-48, §5.2.
#include "hil/controllers/s5/wf725_open_loop.hpp"
#include "wf725_fixture.hpp"

namespace hil::controllers::s5::test {
namespace {

using W = Wf725Fixture;

/// An open-loop incremental WF 726 axis (MD 4 = 3): the manual's MD 42-47 examples, creep level 5
/// and MD 48 = 60 µm so that the axis stops inside MD 33 = 30 µm (braking 35 µm from level 5, a
/// 4 ms cycle's travel 33 µm of spread); MD 1/MD 2 = 0 (step change).
std::map<int, std::string> ak_md() {
  return {{49, "1"},   {4, "3"},     {1, "0"},       {2, "0"},       {6, "0"},       {7, "1"},       {8, "0"},
          {9, "1"},    {10, "4000"}, {11, "-24537"}, {12, "-42728"}, {13, "150000"}, {14, "200000"}, {15, "1"},
          {16, "0"},   {17, "0"},    {18, "0"},      {19, "1"},      {20, "0"},      {21, "4"},      {28, "0"},
          {30, "150"}, {31, "0"},    {32, "30"},     {33, "30"},     {34, "10000"},  {40, "0"},      {41, "0"},
          {42, "87"},  {43, "52"},   {44, "5"},      {45, "50000"},  {46, "25000"},  {47, "5000"},   {48, "60"},
          {27, "0"},   {50, "0"}};
}

constexpr double speed_10v = 10000.0;  // mm/min at 10 V (the default open_loop_speed)
constexpr double drive_acc = 1000.0;   // mm/s^2 (the default open_loop_acceleration)
double level_v(int level) {
  return level * 100.0 / 10000.0 * speed_10v / 60.0;  // mm/s
}

TEST(Wf725OpenLoop, StagesOfTheManualsExample) {
  const Wf725OpenLoopStages s;  // MD 42-48 = 87, 52, 10 / 50 000, 25 000, 5 000, 55 µm
  EXPECT_EQ(wf725_open_loop_level(s, 99, 80000), 99) << "the programmed level until MD 45";
  EXPECT_EQ(wf725_open_loop_level(s, 99, 50000), 87) << "MD 42 at MD 45";
  EXPECT_EQ(wf725_open_loop_level(s, 99, 25001), 87);
  EXPECT_EQ(wf725_open_loop_level(s, 99, 25000), 52) << "MD 43 at MD 46";
  EXPECT_EQ(wf725_open_loop_level(s, 99, 5000), 10) << "MD 44 at MD 47";
  EXPECT_EQ(wf725_open_loop_level(s, 99, 56), 10);
  EXPECT_EQ(wf725_open_loop_level(s, 99, 55), 0) << "speed 0 at MD 48";
  EXPECT_EQ(wf725_open_loop_level(s, 99, -300), 0) << "past the target";
  EXPECT_EQ(wf725_open_loop_level(s, 30, 40000), 30) << "a stage never raises a lower programmed level";
  EXPECT_EQ(wf725_open_loop_level(s, 30, 20000), 30);
  EXPECT_EQ(wf725_open_loop_level(s, 30, 4000), 10);
  EXPECT_EQ(wf725_open_loop_level(s, 150, 60000), 99) << "levels are 1..99";
  EXPECT_EQ(wf725_level_bcd(87), 0x87);
  EXPECT_EQ(wf725_level_bcd(5), 0x05);
  EXPECT_EQ(wf725_level_mv(87), 8700) << "X3 = level x 100 mV";
  const Wf725OpenLoopDrive d{10000.0, 1000.0};
  EXPECT_DOUBLE_EQ(wf725_level_velocity(d, 87), 145.0) << "8.7 V of 10 V at 10 m/min";
  EXPECT_DOUBLE_EQ(wf725_ramp_acceleration(d, 1200.0), 20.0) << "MD 1 = 1200 mV/s: 1.2 V/s of 10 m/min per 10 V";
  EXPECT_DOUBLE_EQ(wf725_ramp_acceleration(d, 0.0), 1000.0) << "0 = step change: the drive's own ramp";
  EXPECT_DOUBLE_EQ(wf725_ramp_acceleration(d, 65535.0), 1000.0) << "never steeper than the drive";
}

TEST(Wf725OpenLoop, CutOffPointOutputs) {
  const Wf725OpenLoopStages s;
  const auto far = wf725_cut_off_outputs(s, 60000);
  EXPECT_TRUE(far.a && far.b && far.c);
  EXPECT_FALSE(far.last_but_one);
  const auto a = wf725_cut_off_outputs(s, 25000);
  EXPECT_FALSE(a.a) << "A drops at MD 46";
  EXPECT_TRUE(a.b && a.c);
  const auto b = wf725_cut_off_outputs(s, 5000);
  EXPECT_FALSE(b.a || b.b) << "B drops at MD 47";
  EXPECT_TRUE(b.c);
  EXPECT_TRUE(b.last_but_one) << "the last but one cut-off point is MD 47";
  const auto c = wf725_cut_off_outputs(s, 55);
  EXPECT_FALSE(c.c) << "at the last travel difference the output is switched to zero";
}

TEST_F(W, OpenLoopStagesSwitchAtTheTravelDifferences) {
  start(ak_md());
  ASSERT_TRUE(ctl->open_loop());
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 87);  // open loop: the feed is the speed level
  (void)data_code(db::code::mdi_position, 100000);
  // Observe DL 4 and the cut-off outputs X7 A1-A3 and A4 (MD 10 = 4000: last but one) per cycle.
  const auto out = [&](int n) { return ctl->io().get(BitAddress{IoArea::output, 0, static_cast<std::uint8_t>(n)}); };
  std::vector<std::pair<int, double>> seen;  // DL 4 at remaining distance (µm, actual)
  bool cut_ok = true;
  start_pulse();
  ASSERT_TRUE(run_until(
      [&] {
        const double rem = 100000.0 - actual();
        const int dl4 = word(db::dw_error) >> 8;
        if (seen.empty() || seen.back().first != dl4) seen.emplace_back(dl4, rem);
        if (dl4 != 0) {
          // A until MD 46, B until MD 47, C until MD 48; A4 from MD 47 on (one cycle of travel slack).
          const double slack = 600.0;
          if (rem > 25000 + slack && !(out(0) && out(1) && out(2) && !out(3))) cut_ok = false;
          if (rem < 25000 - slack && rem > 5000 + slack && (out(0) || !out(1) || !out(2) || out(3))) cut_ok = false;
          if (rem < 5000 - slack && (out(0) || out(1) || !out(2) || !out(3))) cut_ok = false;
        }
        return bit(db::dw_status, db::bit_peh) && ctl->speed_level() == 0;
      },
      std::chrono::seconds(10)));
  EXPECT_TRUE(cut_ok) << "cut-off point outputs A/B/C and function 4";
  // The levels the module switched to, and where (the remaining distance on the encoder when the
  // cycle saw it at or below the travel difference: within one cycle's travel of the level before).
  const auto& ch = ctl->level_changes();
  ASSERT_EQ(ch.size(), 4U);
  EXPECT_EQ(ch[0].level, 87);
  EXPECT_DOUBLE_EQ(ch[0].remaining_um, 100000.0);
  const double cycle_s = 0.004;
  const struct {
    int level;
    double at_um, prev_v;
  } want[] = {{52, 25000, level_v(87)}, {5, 5000, level_v(52)}, {0, 60, level_v(5)}};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(ch[i + 1].level, want[i].level);
    EXPECT_LE(ch[i + 1].remaining_um, want[i].at_um) << "level " << want[i].level;
    EXPECT_GT(ch[i + 1].remaining_um, want[i].at_um - want[i].prev_v * cycle_s * 1000.0 - 2.0)
        << "level " << want[i].level;
  }
  // DL 4 showed 87, 52, 05 and 00 in BCD (the DB is read after each controller cycle).
  std::vector<int> dl4;
  for (const auto& [l, r] : seen) dl4.push_back(l);
  EXPECT_EQ(dl4, (std::vector<int>{0x87, 0x52, 0x05, 0x00}));
  // The stop model: speed 0 is applied at the next drive cycle (1 ms) and the axis brakes on the
  // drive's own ramp (MD 2 = 0: step change) from level 5.
  // The stop model: speed 0 from level 5 brakes on the drive's own ramp (MD 2 = 0: step change):
  // v^2 / 2a past the point where speed 0 was output; the actual value the module measured lags
  // the drive's command by at most one drive cycle (1 ms) of travel.
  const double v = level_v(5);
  const double braking_um = v * v / (2.0 * drive_acc) * 1000.0;
  const double lag_um = v * 0.001 * 1000.0;
  const double final_rem = 100000.0 - actual();
  EXPECT_LE(final_rem, ch[3].remaining_um - braking_um + 0.5) << "final position by the overshoot model";
  EXPECT_GE(final_rem, ch[3].remaining_um - braking_um - lag_um - 0.5) << "final position by the overshoot model";
  EXPECT_LE(std::abs(100000 - actual()), 30) << "inside MD 33";
  EXPECT_TRUE(bit(db::dw_status, db::bit_peh));
  EXPECT_EQ(error(), 0);
  EXPECT_FALSE(out(0) || out(1) || out(2) || out(3)) << "all cut-off outputs off in position";
}

TEST_F(W, OpenLoopVoltageRampsMd1Md2OnTheWf726) {
  auto md = ak_md();
  md[1] = "2000";  // mV/s: 2 V/s = 33.3 mm/s^2 on a 10 m/min-at-10 V drive
  md[2] = "6000";  // mV/s: 100 mm/s^2
  md[13] = "500000";
  md[14] = "600000";
  start(md);
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 87);
  (void)data_code(db::code::mdi_position, 450000);  // level 87 (145 mm/s) is reached after 315 mm
  start_pulse();
  run(milliseconds(984));  // 1 s after the start was seen
  const double a_up = 2000.0 * speed_10v / 60.0 / 10000.0;
  EXPECT_NEAR(axis->status().command_velocity, a_up * 1.0, 0.25) << "2000 mV after 1 s of the MD 1 ramp";
  EXPECT_EQ(word(db::dw_error) >> 8, 0x87) << "DL 4 is the level output, the voltage ramps towards it";
  // Down: from level 87 at MD 46 (25 mm left) to level 52 on the MD 2 ramp (100 mm/s^2).
  ASSERT_TRUE(run_until([&] { return ctl->speed_level() == 52; }, std::chrono::seconds(20)));
  run(milliseconds(100));
  EXPECT_NEAR(axis->status().command_velocity, level_v(87) - 100.0 * 0.1, 0.5) << "MD 2 = 6000 mV/s";
}

TEST_F(W, OpenLoopOvershootBeyondTheWindowIsError22AfterMd30) {
  auto md = ak_md();
  md[48] = "0";  // speed 0 only at the target: the axis coasts past it
  md[44] = "10";
  start(md);
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 50);
  (void)data_code(db::code::mdi_position, 20000);
  start_pulse();
  TimePoint zero_at{};
  ASSERT_TRUE(run_until(
      [&] {
        if (zero_at == TimePoint{} && ctl->speed_level() == 0) zero_at = now;
        return error() != 0;
      },
      std::chrono::seconds(10)));
  EXPECT_EQ(error(), 0x22);
  const auto after = std::chrono::duration_cast<milliseconds>(now - zero_at).count();
  EXPECT_GT(after, 150) << "MD 30 runs from the output of speed 0";
  EXPECT_LE(after, 150 + 4 + 4);
  EXPECT_GT(actual() - 20000, 20) << "past the window: coasting from level 10 is 139 µm";
  EXPECT_FALSE(bit(db::dw_status, db::bit_peh));
  run(milliseconds(20));
  EXPECT_EQ(axis->status().state, motion::AxisState::disabled) << "22 switches the drive off";
}

TEST_F(W, OpenLoopLeavingTheReachedWindowIsError21) {
  start(ak_md());
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 20);
  (void)data_code(db::code::mdi_position, 10000);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_peh) && ctl->speed_level() == 0; }));
  run(milliseconds(200));
  EXPECT_EQ(error(), 0) << "standing in the window";
  // The axis is pushed out of position (a force on the machine): 21.
  ASSERT_FALSE(axis->move_relative(0.1));
  ASSERT_TRUE(run_until([&] { return error() != 0; }, std::chrono::seconds(1)));
  EXPECT_EQ(error(), 0x21);
  EXPECT_TRUE(bit(db::dw_status, db::bit_error));
  EXPECT_GT(actual() - 10000, 20);
}

TEST_F(W, OpenLoopPreLimitOnTheActualPositionIs95) {
  start(ak_md());
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 87);
  (void)data_code(db::code::mdi_position, -40000);  // beyond MD 11 = -24 537
  start_pulse();
  ASSERT_TRUE(run_until([&] { return error() != 0; }));
  EXPECT_EQ(error(), 0x95);
  EXPECT_LE(actual(), -24537) << "open loop checks the actual position: 95 when it reaches MD 11";
  EXPECT_EQ(ctl->speed_level(), 0);
  EXPECT_TRUE(bit(db::dw_status, db::bit_pre_limit));
  // The stage was MD 43 (15.5 mm left to the target at MD 11): the axis brakes on the drive's ramp.
  ASSERT_TRUE(run_until([&] { return axis->status().state == motion::AxisState::standstill; }));
  const double v = level_v(52);
  EXPECT_NEAR(actual(), -24537 - (v * 0.001 + v * v / (2 * drive_acc)) * 1000.0, 600.0);
}

TEST_F(W, OpenLoopJogRunsAtTheLevelOfDataCode1C) {
  start(ak_md());
  synchronize();
  traverse(db::Submode::set_up);
  (void)data_code(db::code::jog_feed, 30);
  set_bit(db::dw_control, db::bit_plus, true);
  run(milliseconds(400));
  EXPECT_NEAR(axis->status().command_velocity, level_v(30), 1e-9) << "3 V";
  EXPECT_EQ(word(db::dw_error) >> 8, 0x30);
  set_bit(db::dw_control, db::bit_plus, false);
  run(milliseconds(200));
  EXPECT_EQ(ctl->speed_level(), 0);
  EXPECT_EQ(axis->status().state, motion::AxisState::standstill);
}

TEST_F(W, OpenLoopRefusesThe4thGGroupWith7A) {
  start(ak_md(), "%3\nN1 G90 G23 X 10000 F 50\n");
  synchronize();
  traverse(db::Submode::automatic);
  ctl->write_db_word(db::dw_program, 3);
  start_pulse();
  run(milliseconds(40));
  EXPECT_EQ(error(), 0x7A);
  EXPECT_EQ(ctl->speed_level(), 0);
}

TEST_F(W, OpenLoopProgramPositionsBlockByBlock) {
  start(ak_md(), "%4\nN1 G90 X 30000 F 87\nN2 G91 X -10000 F 40\n");
  synchronize();
  traverse(db::Submode::automatic);
  ctl->write_db_word(db::dw_program, 4);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return !bit(db::dw_flags, 1) && bit(db::dw_status, db::bit_peh); }));
  EXPECT_EQ(error(), 0);
  EXPECT_NEAR(actual(), 20000, 20) << "each block ends inside MD 33";
  int zeros = 0;
  for (const auto& c : ctl->level_changes()) zeros += c.level == 0 ? 1 : 0;
  EXPECT_EQ(zeros, 2) << "no flying block change in open loop: speed 0 at each block end";
}

}  // namespace
}  // namespace hil::controllers::s5::test
