// SPDX-License-Identifier: MIT
// WF 725/726 on the controller runtime: mode-change checks (S8), pre-limit and range-limit
// switches (S1, S2), reference point approach (S3), standstill/clamping checks (S9), roller feed
// (S10), set up, MDI, drive enable, data codes and teach-in. Vectors: shared/vectors/wf725-726.md
// §7.3; the manual's conditions: seeds/wf725-726.md §3.5, §5.
#include "wf725_fixture.hpp"

namespace hil::controllers::s5::test {
namespace {

using W = Wf725Fixture;

TEST_F(W, S8ModeChangeChecksKeepTheModuleOutOfTraversing) {
  start(base_md());
  select(db::bit_mode_machine_data, db::Submode::none);
  struct Case {
    std::vector<std::pair<int, std::int32_t>> writes;
    int error;
  };
  const std::vector<Case> cases = {
      {{{19, 0}, {20, 0}}, 0x19},
      {{{19, 1}, {34, 0}}, 0x1A},
      {{{34, 10000}, {12, -20000}}, 0x1B},  // MD 12 > MD 11 (-24 537)
      {{{12, -42728}, {14, 90000}}, 0x1C},  // MD 14 < MD 13 (96 417)
  };
  for (const auto& c : cases) {
    for (const auto& [n, v] : c.writes) (void)data_code(db::code::write_md, n, v);
    traverse(db::Submode::none);
    EXPECT_FALSE(ctl->traversing());
    EXPECT_EQ(error(), c.error);
    EXPECT_TRUE(bit(db::dw_status, db::bit_error)) << "D 3.5";
    (void)data_code(db::code::acknowledge);
    EXPECT_EQ(error(), 0);
    select(db::bit_mode_machine_data, db::Submode::none);
  }
  (void)data_code(db::code::write_md, 14, 137428);
  traverse(db::Submode::none);
  EXPECT_TRUE(ctl->traversing());
  EXPECT_EQ(error(), 0);
  EXPECT_EQ(ctl->pending_md(), (std::vector<int>{19})) << "MD 19 was written with another value, then back";
}

TEST_F(W, MachineDataIoErrors) {
  start(base_md());
  traverse(db::Submode::none);
  (void)data_code(db::code::write_md, 11, -1000);
  EXPECT_EQ(io_error(), 0x0201) << "MD writes only in mode MD I/O (DW 40 as the manual writes it)";
  select(db::bit_mode_machine_data, db::Submode::none);
  (void)data_code(db::code::write_md, 51, 1);
  EXPECT_EQ(io_error(), 0x0121);
  (void)data_code(db::code::read_md, 3);
  EXPECT_EQ(io_error(), 0) << "self-acknowledging: cleared by the next valid input";
  EXPECT_EQ(data_code(db::code::read_md, 3), 600000) << "MD 3 in 10^-2 mm/min";
  EXPECT_EQ(data_code(db::code::read_md, 11), -24537);
  (void)data_code(0);
  EXPECT_EQ(io_error(), 0x0112);
  (void)data_code(0x77);
  EXPECT_EQ(io_error(), 0x0113);
}

TEST_F(W, S1PreLimitNegativeStopsExactlyOnMd11) {
  start(base_md());
  synchronize();
  ASSERT_TRUE(ctl->synchronized());
  EXPECT_TRUE(bit(db::dw_status, db::bit_syn));
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 300000);      // 3000 mm/min
  (void)data_code(db::code::mdi_position, -30000);  // beyond MD 11
  start_pulse();
  ASSERT_TRUE(run_until([&] { return error() != 0; }));
  EXPECT_EQ(word(db::dw_error), 0x0095) << "DW 4 = 95";
  EXPECT_TRUE(bit(db::dw_status, db::bit_pre_limit)) << "3.3";
  EXPECT_TRUE(bit(db::dw_status, db::bit_error)) << "3.5";
  EXPECT_NEAR(command_mm(), -24.537, 1e-9) << "stops exactly on MD 11";
  EXPECT_NEAR(actual(), -24537, 1) << "the actual value, within the drive's following error";
  // Acknowledge (800C) and move away; a further negative move gives 95 again at once.
  (void)data_code(db::code::acknowledge);
  EXPECT_FALSE(bit(db::dw_status, db::bit_pre_limit));
  (void)data_code(db::code::mdi_position, -25000);
  start_pulse();
  run(milliseconds(100));
  EXPECT_EQ(error(), 0x95);
  EXPECT_NEAR(command_mm(), -24.537, 1e-9);
}

TEST_F(W, S1JogOntoThePositivePreLimit) {
  start(base_md());
  synchronize();
  traverse(db::Submode::set_up);
  (void)data_code(db::code::jog_feed, 600000);
  set_bit(db::dw_control, db::bit_plus, true);
  ASSERT_TRUE(run_until([&] { return error() != 0; }, std::chrono::seconds(30)));
  EXPECT_EQ(error(), 0x96);
  EXPECT_NEAR(command_mm(), 96.417, 1e-9);
  EXPECT_TRUE(bit(db::dw_status, db::bit_pre_limit));
}

TEST_F(W, JogWithoutSpeedIsError72) {
  start(base_md());
  traverse(db::Submode::set_up);
  drive_enable();
  set_bit(db::dw_control, db::bit_minus, true);
  run(milliseconds(20));
  EXPECT_EQ(error(), 0x72);
}

TEST_F(W, S2SetActualValueBelowMd12SwitchesPositionControlOff) {
  start(base_md());
  // The profile refuses such a file; the PLC can still write it in mode MD I/O.
  select(db::bit_mode_machine_data, db::Submode::none);
  (void)data_code(db::code::write_md, 28, -50000);
  synchronize();
  EXPECT_EQ(error(), 0x15);
  EXPECT_TRUE(bit(db::dw_status, db::bit_limit)) << "3.4";
  EXPECT_TRUE(bit(db::dw_status, db::bit_error)) << "3.5";
  run(milliseconds(20));
  EXPECT_EQ(axis->status().state, motion::AxisState::disabled) << "position control off";
}

TEST_F(W, S2RangeLimitSwitchInputIsError16) {
  start(base_md());
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 300000);
  (void)data_code(db::code::mdi_position, 50000);
  start_pulse();
  run(milliseconds(200));
  auto plus = ctl->resolve_bit("limit_plus_A");
  ASSERT_TRUE(plus);
  inputs.fn = [&](IoImage& im) { im.set(*plus, true); };
  ASSERT_TRUE(run_until([&] { return error() != 0; }, std::chrono::seconds(2)));
  EXPECT_EQ(error(), 0x16);
  EXPECT_TRUE(bit(db::dw_status, db::bit_limit));
}

TEST_F(W, S3ReferencePointApproachOnTheCamOfE1) {
  auto md = base_md();
  md[15] = "2";
  md[7] = "1";
  md[17] = "-25";
  md[16] = "-824967";
  md[11] = "-1000000";
  md[12] = "-2000000";
  for (int n : {27, 29, 38, 39, 46, 47}) md.erase(n);  // WF 726 only
  spec.options = {{"module", "WF725A"}, {"reference_speeds", "3000,600,60"}};
  start(md);
  // The cam lies on the axis from 23.4 to 31.2 mm; zero marks every MD 34 = 10 000 increments (10 mm).
  inputs.fn = [&](IoImage& im) {
    const double p = axis->status().position;
    im.set(BitAddress{IoArea::input, 0, 0}, p >= 23.4 && p <= 31.2);
  };
  traverse(db::Submode::reference);
  drive_enable();
  set_bit(db::dw_control, db::bit_plus, true);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return ctl->synchronized() && bit(db::dw_status, db::bit_peh); }));
  EXPECT_EQ(actual(), -824967);
  EXPECT_TRUE(bit(db::dw_status, db::bit_syn)) << "3.6";
  EXPECT_TRUE(bit(db::dw_status, db::bit_peh)) << "3.0";
  EXPECT_NEAR(command_mm(), 40.0 - 0.025, 1e-9) << "the zero mark after the cam (40 mm), then MD 17 = -25 µm";
  EXPECT_EQ(error(), 0);
  // Limits armed: a move beyond MD 11 stops on it.
  set_bit(db::dw_control, db::bit_plus, false);
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 600000);
  (void)data_code(db::code::mdi_position, -1000000 - 5000);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return error() != 0; }, std::chrono::seconds(60)));
  EXPECT_EQ(error(), 0x95);
  EXPECT_NEAR(actual(), -1000000, 1);
}

TEST_F(W, ReferenceApproachDirectionAndSpeedErrors) {
  start(base_md());
  traverse(db::Submode::reference);
  drive_enable();
  const auto expect_start_error = [&](int code, const char* what) {
    start_pulse();
    EXPECT_EQ(error(), code) << what;
    (void)data_code(db::code::acknowledge);  // 74..79: acknowledged with data code 800C
  };
  expect_start_error(0x78, "no direction");
  set_bit(db::dw_control, db::bit_plus, true);
  set_bit(db::dw_control, db::bit_minus, true);
  expect_start_error(0x77, "both directions");
  set_bit(db::dw_control, db::bit_minus, false);
  expect_start_error(0x74, "V_rapid = 0 (data code 8)");
  (void)data_code(db::code::ref_rapid, 300000);
  expect_start_error(0x75, "V_reduced = 0 (data code 9)");
  (void)data_code(db::code::ref_reduced, 60000);
  expect_start_error(0x76, "V_slow = 0 (data code A)");
  (void)data_code(db::code::ref_slow, 6000);
  start_pulse();
  EXPECT_EQ(error(), 0);
  run(milliseconds(100));
  EXPECT_TRUE(axis->status().busy);
  set_bit(db::dw_control, db::bit_plus, false);
  set_bit(db::dw_control, db::bit_minus, true);
  run(milliseconds(20));
  EXPECT_EQ(error(), 0x79) << "direction changed during the approach";
  EXPECT_FALSE(ctl->synchronized());
}

TEST_F(W, S9StandstillWindowBelowThePehWindowGivesError10EachTime) {
  start(base_md());
  // The profile refuses MD 33 > MD 25 in a file; the PLC writes it in mode MD I/O.
  select(db::bit_mode_machine_data, db::Submode::none);
  (void)data_code(db::code::write_md, 33, 45);  // MD 33 > MD 25 = 40
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 300000);
  for (int k = 1; k <= 2; ++k) {
    (void)data_code(db::code::mdi_position, 1000 * k);
    start_pulse();
    ASSERT_TRUE(run_until([&] { return error() != 0; }, std::chrono::seconds(3)));
    EXPECT_EQ(error(), 0x10);
    EXPECT_NEAR(actual(), 1000 * k, 11) << "raised where the PEH window (MD 33) is reached";
    (void)data_code(db::code::acknowledge);
    run(milliseconds(60));
  }
  EXPECT_EQ(count(0x10), 2);
}

TEST_F(W, S9ClampingWithMd25BelowMd32IsError10AndTheToleranceIs23) {
  start(base_md());
  select(db::bit_mode_machine_data, db::Submode::none);
  (void)data_code(db::code::write_md, 32, 50);  // MD 32 > MD 25 = 40
  synchronize();
  traverse(db::Submode::clamping);
  start_pulse();
  EXPECT_EQ(error(), 0x10);
}

TEST_F(W, S10RollerFeed) {
  auto md = base_md();
  md[42] = "1";
  start(md);
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 600000);
  (void)data_code(db::code::mdi_position, 12345);
  start_pulse();
  EXPECT_EQ(error(), 0x70) << "G90 with roller feed";
  (void)data_code(db::code::acknowledge);
  (void)data_code(db::code::mdi_position, 12345, 1);  // G91
  start_pulse();
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_peh) && !axis->status().busy; }));
  EXPECT_EQ(actual(), 12345);
  (void)data_code(db::code::mdi_position, 5000, 1);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_peh) && !axis->status().busy; }));
  EXPECT_EQ(actual(), 5000);
  EXPECT_NEAR(command_mm(), 17.345, 1e-9) << "the axis went on";
}

TEST_F(W, MdiErrorsAndDriveEnable) {
  start(base_md());
  traverse(db::Submode::mdi);
  start_pulse();
  EXPECT_EQ(error(), 0x13) << "start without D 2.0";
  (void)data_code(db::code::acknowledge);
  drive_enable();
  start_pulse();
  EXPECT_EQ(error(), 0x65);
  (void)data_code(db::code::mdi_position, 1000);
  start_pulse();
  EXPECT_EQ(error(), 0x66);
  (void)data_code(db::code::mdi_feed, 0);
  EXPECT_EQ(io_error(), 0x0145);
  (void)data_code(db::code::mdi_feed, 60000);
  start_pulse();
  EXPECT_EQ(error(), 0);
  run(milliseconds(100));
  ASSERT_TRUE(axis->status().busy);
  set_bit(db::dw_enable, db::bit_drive_enable, false);
  run(milliseconds(20));
  EXPECT_EQ(error(), 0x13) << "D 2.0 dropped while traversing";
  EXPECT_FALSE(ctl->io().get(*ctl->resolve_bit("drive_enable_A")));
}

TEST_F(W, TeachInStoresTheActualValue) {
  start(base_md());
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 300000);
  (void)data_code(db::code::mdi_position, 4321);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return !axis->status().busy && bit(db::dw_status, db::bit_peh); }));
  (void)data_code(db::code::teach_in, 7, 3);
  EXPECT_EQ(io_error(), 0);
  const auto* p = ctl->programs().find(7);
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->blocks.size(), 1U);
  EXPECT_EQ(p->blocks[0].number, 3);
  EXPECT_EQ(p->blocks[0].x, 4321);
  EXPECT_EQ(p->blocks[0].f, 300000);
  (void)data_code(db::code::teach_in, 0, 3);
  EXPECT_EQ(io_error(), 0x0135);
  (void)data_code(db::code::teach_in, 7, 0);
  EXPECT_EQ(io_error(), 0x0136);
}

}  // namespace
}  // namespace hil::controllers::s5::test

namespace hil::controllers::s5::test {
namespace {

TEST_F(Wf725Fixture, TheDbAxisIsPlainWordsInTheImage) {
  spec.options = {{"db", "12"}};
  start(base_md());
  ASSERT_EQ(ctl->data_blocks().size(), 1U);
  EXPECT_EQ(ctl->data_blocks()[0].number, 12);
  EXPECT_EQ(ctl->data_blocks()[0].words, db::words);
  ctl->write_db_word(db::dw_enable, 0x0701);  // DL 2 = block 7, D 2.0 drive enable
  const auto rf = ctl->resolve_bit("DB12 D 2.0");
  ASSERT_TRUE(rf) << rf.error();
  EXPECT_EQ(*rf, *ctl->resolve_bit("rf_A"));
  EXPECT_TRUE(ctl->io().get(*rf));
  EXPECT_EQ(ctl->io().get(ByteAddress{IoArea::data, 4}), 7) << "DL 2 is byte 2w of the data area";
  EXPECT_TRUE(ctl->resolve_bit("D 3.6")) << "the DB number defaults to the DB axis";
  EXPECT_FALSE(ctl->resolve_bit("DB11 D 2.0"));
  EXPECT_FALSE(ctl->resolve_bit("DB12 D 48.0")) << "beyond DW 47";
  traverse(db::Submode::set_actual);
  run(milliseconds(40));
  EXPECT_EQ(word(db::dw_state), (1U << 8) | 3U) << "DW 23: active mode bits / submode";
  EXPECT_EQ(axis->status().state, motion::AxisState::standstill) << "D 2.0 enabled the axis";
}

}  // namespace
}  // namespace hil::controllers::s5::test
