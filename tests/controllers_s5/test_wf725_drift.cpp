// SPDX-License-Identifier: MIT
// WF 725/726 drift (controller key `drift`, the drive's input offset on X3), its compensation MD 35
// and submode RUN with data code 10 (digest §4.3 MD 35, §5.2 errors 10/22, §6.1; docs/wf725.md
// "Drift"). The axis of examples/controllers/wf725-axis-a.txt: MD 3 = 6000 mm/min, MD 23 = 8000 mV,
// K_v = MD 22 = 1.00 (m/min)/mm: a drift of 40 mV is 30 mm/min at zero command, held by the K_v loop
// at a standstill following error of 30 µm (actual 30 µm beyond the command); MD 25 = 40, MD 33 = 11.
#include "wf725_fixture.hpp"

namespace hil::controllers::s5::test {
namespace {

/// µm: the actual position beyond the command (-following error).
double lag_um(const motion::Axis& a) {
  return -a.status().following_error / db::um;
}

class Wf725Drift : public Wf725Fixture {
 protected:
  /// MDI to `x_um` at 3000 mm/min.
  void mdi(std::int32_t x_um) {
    traverse(db::Submode::mdi);
    (void)data_code(db::code::mdi_feed, 300000);
    (void)data_code(db::code::mdi_position, x_um);
    start_pulse();
  }
};

TEST_F(Wf725Drift, DriftWithoutMd35HoldsDriftOverKvAndTheWindowIsNeverReached) {
  spec.options["drift"] = "40";
  start(base_md());
  EXPECT_NEAR(ctl->drift_offset_um(), 30.0, 1e-9) << "40 mV / 8000 mV x 6000 mm/min / (1.00 (m/min)/mm)";
  synchronize();
  run(milliseconds(300));
  EXPECT_EQ(error(), 0) << "30 µm is inside the standstill window MD 25 = 40";
  EXPECT_NEAR(lag_um(*axis), 30.0, 1.0) << "standstill following error = drift / K_v";
  EXPECT_NEAR(actual(), 30, 1) << "DD 20: the actual value 30 µm from the command position 0 (MD 28)";
  EXPECT_FALSE(bit(db::dw_status, db::bit_peh)) << "30 µm from the target, PEH window MD 33 = 11";
  // A positioning against the drift stops 30 µm short of its target: MD 30 = 150 ms runs out (22).
  mdi(-10000);
  ASSERT_TRUE(run_until([&] { return error() != 0; }, std::chrono::seconds(3)));
  EXPECT_EQ(error(), 0x22);
  EXPECT_NEAR(axis->status().position, -10.0 + 0.030, 0.001);
  EXPECT_EQ(count(0x22), 1);
}

TEST_F(Wf725Drift, DriftBeyondMd25IsError10AtStandstill) {
  spec.options["drift"] = "-60";  // -45 µm: the axis creeps negative, beyond MD 25 = 40
  start(base_md());
  synchronize();
  ASSERT_TRUE(run_until([&] { return error() != 0; }, std::chrono::seconds(1)));
  EXPECT_EQ(error(), 0x10);
  EXPECT_TRUE(bit(db::dw_status, db::bit_error));
  run(milliseconds(100));
  EXPECT_NE(axis->status().drive_state, DriveState::operation_enabled) << "10 < 60: the drive is switched off";
}

TEST_F(Wf725Drift, Md35CompensatesTheDrift) {
  spec.options["drift"] = "40";
  auto md = base_md();
  md[35] = "30";  // -(standstill following error of -30 µm in the manual's sign: command - actual)
  start(md);
  EXPECT_NEAR(ctl->drift_offset_um(), 0.0, 1e-9);
  synchronize();
  run(milliseconds(300));
  EXPECT_NEAR(lag_um(*axis), 0.0, 1.0) << "after entry the following error reads about 0";
  EXPECT_TRUE(bit(db::dw_status, db::bit_peh));
  mdi(-10000);
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_peh) && axis->status().command_position < -9.9; }));
  run(milliseconds(200));
  EXPECT_EQ(error(), 0);
  EXPECT_NEAR(actual(), -10000, 1);
}

TEST_F(Wf725Drift, Md35WithoutDriftIsAnErrorOfItsOwn) {
  auto md = base_md();
  md[35] = "-20";
  start(md);
  synchronize();
  run(milliseconds(300));
  EXPECT_NEAR(lag_um(*axis), 20.0, 1.0) << "the compensation drives the axis off its command by -MD 35";
}

TEST_F(Wf725Drift, SubmodeRunDataCode10StoresTheCompensationInMd35) {
  spec.options["drift"] = "40";
  start(base_md());
  synchronize();
  run(milliseconds(300));
  // Outside RUN: 900 (wrong mode/submode), MD 35 unchanged.
  traverse(db::Submode::set_actual);
  EXPECT_EQ(data_code(db::code::drift), 0);
  EXPECT_EQ(io_error(), 0x0900);
  EXPECT_EQ(ctl->read_machine_data(35), 0);
  traverse(db::Submode::run);
  start_pulse();  // a start in RUN does nothing
  EXPECT_EQ(io_error(), 0) << "the next valid input clears 900";
  EXPECT_EQ(error(), 0);
  const auto md35 = data_code(db::code::drift);
  EXPECT_NEAR(md35, 30, 1) << "-(standstill following error)";
  EXPECT_EQ(io_error(), 0);
  EXPECT_EQ(data_code(db::code::read_md, 35), md35) << "stored in the module's MD 35 (data code 51)";
  run(milliseconds(300));
  EXPECT_NEAR(lag_um(*axis), 0.0, 1.5) << "compensated during operation";
  EXPECT_TRUE(bit(db::dw_status, db::bit_peh));
  // Again: the error is about 0 now, so MD 35 stays about the same (the measurement adds to it).
  EXPECT_NEAR(data_code(db::code::drift), md35, 1);
  mdi(-10000);
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_peh) && axis->status().command_position < -9.9; }));
  EXPECT_EQ(error(), 0) << "no 22: the window MD 33 is reached";
}

TEST_F(Wf725Drift, Md35WrittenByDataCode50TakesEffectAtOnce) {
  spec.options["drift"] = "40";
  start(base_md());
  synchronize();
  run(milliseconds(300));
  ASSERT_NEAR(lag_um(*axis), 30.0, 1.0);
  select(db::bit_mode_machine_data, db::Submode::none);
  (void)data_code(db::code::write_md, 35, 30);
  EXPECT_EQ(io_error(), 0);
  run(milliseconds(300));
  EXPECT_NEAR(lag_um(*axis), 0.0, 1.0);
  EXPECT_TRUE(ctl->pending_md().empty()) << "MD 35 is the module's own: no power-up needed";
}

TEST_F(Wf725Drift, DataCode10NeedsTheAxisAtRestUnderPositionControl) {
  spec.options["drift"] = "40";
  start(base_md());
  traverse(db::Submode::run);
  (void)data_code(db::code::drift);
  EXPECT_EQ(io_error(), 0x0202) << "no drive enable D 2.0: WF not ready";
  EXPECT_EQ(ctl->read_machine_data(35), 0);
  drive_enable();
  run(milliseconds(200));
  EXPECT_NEAR(data_code(db::code::drift), 30, 1);
}

TEST_F(Wf725Drift, DataCode10IsLimitedTo255ResolutionSteps) {
  spec.options["drift"] = "400";  // 300 µm: beyond the limit +-255 µm at 1 µm resolution
  auto md = base_md();
  md[25] = "400";  // a standstill window wide enough to stand with it
  start(md);
  traverse(db::Submode::run);
  drive_enable();
  run(milliseconds(300));
  EXPECT_NEAR(lag_um(*axis), 300.0, 1.0);
  EXPECT_EQ(data_code(db::code::drift), 255) << "\"so that the drive fault is not masked\"";
  run(milliseconds(300));
  EXPECT_NEAR(lag_um(*axis), 45.0, 1.0) << "the rest of the drift stays visible";
}

TEST_F(Wf725Drift, TheKeyIsAVoltage) {
  const auto create = [&](const char* drift) {
    spec.options["drift"] = drift;
    std::string text;
    for (const auto& [n, v] : base_md()) text += "MD " + std::to_string(n) + " = " + v + "\n";
    spec.parameters = write("md.txt", text);
    ControllerRegistry r;
    register_wf725(r);
    return r.create(spec);
  };
  for (const char* bad : {"12000", "x", "40mV", "-10001"}) {
    auto b = create(bad);
    ASSERT_FALSE(b) << bad;
    EXPECT_NE(b.error().describe().find("offset voltage in mV"), std::string::npos) << b.error().describe();
  }
  ASSERT_TRUE(create("-10000"));
  ASSERT_TRUE(create("0.5"));
}

/// The open-loop axis of test_wf725_open_loop.cpp (MD 4 = 3, MD 33 = 30 µm, MD 30 = 150 ms).
std::map<int, std::string> ak_md() {
  return {{49, "1"},   {4, "3"},     {1, "0"},       {2, "0"},       {6, "0"},       {7, "1"},       {8, "0"},
          {9, "1"},    {10, "4000"}, {11, "-24537"}, {12, "-42728"}, {13, "150000"}, {14, "200000"}, {15, "1"},
          {16, "0"},   {17, "0"},    {18, "0"},      {19, "1"},      {20, "0"},      {21, "4"},      {28, "0"},
          {30, "150"}, {31, "0"},    {32, "30"},     {33, "30"},     {34, "10000"},  {40, "0"},      {41, "0"},
          {42, "87"},  {43, "52"},   {44, "5"},      {45, "50000"},  {46, "25000"},  {47, "5000"},   {48, "60"},
          {27, "0"},   {50, "0"}};
}

TEST_F(Wf725Drift, OpenLoopTheDriveCreepsAndLeavesThePehWindow) {
  // Open loop has no position loop: 50 mV of the drive's 10 V = 10 000 mm/min is 50 mm/min at speed
  // level 0, as long as the drive is powered (docs/wf725.md "Drift").
  spec.options["drift"] = "50";
  start(ak_md());
  ASSERT_TRUE(ctl->open_loop());
  synchronize();
  const auto a0 = actual();
  run(milliseconds(1200));
  EXPECT_NEAR(actual() - a0, 1000, 20) << "50 mm/min for 1.2 s: 1 mm at speed level 0";
  EXPECT_EQ(ctl->speed_level(), 0);
  traverse(db::Submode::run);
  (void)data_code(db::code::drift);
  EXPECT_EQ(io_error(), 0x0113) << "no MD 35 in open loop";
  // A positioning reaches PEH (speed 0 at MD 48, inside MD 33), then the creep carries the axis out
  // of the window: 21 (drive off), and the drive stands (no creep unpowered).
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 20);
  (void)data_code(db::code::mdi_position, 10000);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_peh) && ctl->speed_level() == 0; }));
  ASSERT_TRUE(run_until([&] { return error() != 0; }, std::chrono::seconds(1)));
  EXPECT_EQ(error(), 0x21);
  EXPECT_GT(actual() - 10000, 30) << "left the window MD 33 = 30 µm";
  run(milliseconds(100));
  const auto stopped = axis->status().position;
  run(milliseconds(500));
  EXPECT_NEAR(axis->status().position, stopped, 1e-3) << "unpowered, the drive does not creep";
  EXPECT_EQ(ctl->drift_offset_um(), 0.0);
  // Re-enabled after 800C: no jump, the creep starts again from where the axis stands.
  (void)data_code(db::code::acknowledge);
  ASSERT_TRUE(run_until([&] { return axis->status().drive_state == DriveState::operation_enabled; }));
  const double back = axis->status().position;
  EXPECT_NEAR(back, stopped, 0.006) << "at most one controller cycle of creep, no jump";
  run(milliseconds(600));
  EXPECT_NEAR(axis->status().position - back, 0.5, 0.01) << "50 mm/min again";
}

}  // namespace
}  // namespace hil::controllers::s5::test
