// SPDX-License-Identifier: MIT
// WF 725/726 submode control (errors 77/78, the voltage with its polarity), the read-out data codes
// 3 (encoder speed) and 4 (pulse-check difference), delete block and the listings page by page
// (errors 125-129, 145), and the voltage checks 40-46 masked by MD 41 S (docs/wf725.md).
#include "wf725_fixture.hpp"

namespace hil::controllers::s5::test {
namespace {

using W = Wf725Fixture;

void set_input(IoImage& im, std::uint8_t byte, std::uint8_t b, bool on) {
  im.set(BitAddress{IoArea::input, byte, b}, on);
}

TEST_F(W, ControlRunsAtTheVoltageWithItsPolarity) {
  start(base_md());
  synchronize();
  traverse(db::Submode::control);
  (void)data_code(db::code::control_voltage, 4000);  // 4 V of MD 23 = 8 V at MD 3 = 6000 mm/min
  start_pulse();
  EXPECT_EQ(error(), 0x78) << "no polarity";
  (void)data_code(db::code::acknowledge);
  set_bit(db::dw_control, db::bit_plus, true);
  set_bit(db::dw_control, db::bit_minus, true);
  start_pulse();
  EXPECT_EQ(error(), 0x77) << "both polarities";
  (void)data_code(db::code::acknowledge);
  EXPECT_EQ(error(), 0) << "77/78 are acknowledged with 800C";
  set_bit(db::dw_control, db::bit_plus, false);
  start_pulse();  // negative: 3000 mm/min = 50 mm/s
  run(milliseconds(400));
  EXPECT_NEAR(axis->status().command_velocity, -50.0, 1e-9);
  EXPECT_TRUE(bit(db::dw_status, db::bit_moving_minus));
  pulse(db::bit_stop);
  run(milliseconds(300));
  EXPECT_EQ(axis->status().state, motion::AxisState::standstill) << "D 1.2 ends the output";
  // Into the pre-limit MD 11: control runs until the pre-limit as every motion (95).
  start_pulse();
  ASSERT_TRUE(run_until([&] { return error() != 0; }));
  EXPECT_EQ(error(), 0x95);
  EXPECT_NEAR(command_mm(), -24.537, 1e-9);
}

TEST_F(W, ControlWithoutVoltageIs73) {
  start(base_md());
  synchronize();
  traverse(db::Submode::control);
  set_bit(db::dw_control, db::bit_plus, true);
  start_pulse();
  EXPECT_EQ(error(), 0x73);
}

TEST_F(W, DataCode3ReadsTheEncoderSpeed) {
  start(base_md());
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 600000);  // 6000 mm/min on a 10 mm screw: 600 1/min
  (void)data_code(db::code::mdi_position, 90000);
  start_pulse();
  run(milliseconds(500));
  ASSERT_NEAR(axis->status().velocity, 100.0, 0.01);
  EXPECT_EQ(data_code(db::code::encoder_speed), 600) << "MD 34 = 10 000 pulses per revolution";
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_peh); }));
  EXPECT_EQ(data_code(db::code::encoder_speed), 0);
}

TEST_F(W, DataCode4CountsTheLostPulses) {
  auto md = base_md();
  md[41] = "65536";  // MD 41 J: the pulse check (08) masked; the difference is still counted
  start(md);
  synchronize();
  traverse(db::Submode::mdi);
  EXPECT_EQ(data_code(db::code::pulse_difference), 0);
  (void)data_code(db::code::mdi_feed, 300000);
  (void)data_code(db::code::mdi_position, 20000);
  start_pulse();
  run(milliseconds(100));
  int cycles = 0;
  inputs.fn = [&](IoImage& im) { set_input(im, 2, 3, true); };  // encoder_pulse_loss_A
  run(milliseconds(40), [&] { return ++cycles < 0; });
  inputs.fn = [&](IoImage& im) { set_input(im, 2, 3, false); };
  run(milliseconds(8));
  EXPECT_EQ(data_code(db::code::pulse_difference), -cycles) << "one pulse per moving cycle";
  EXPECT_EQ(error(), 0) << "masked by MD 41 J";
}

TEST_F(W, DeleteBlockAndListPageByPage) {
  std::string progs;
  for (int p = 1; p <= 10; ++p) progs += "%" + std::to_string(p) + "\nN1 G90 X 1000 F 1000\nN2 X 2000\n";
  progs += "%20\n";
  for (int n = 1; n <= 11; ++n) progs += "N" + std::to_string(n) + " G91 X 10 F 1000\n";
  start(base_md(), progs);
  traverse(db::Submode::none);
  EXPECT_EQ(data_code(db::code::list_programs, 1), 11) << "11 programs";
  EXPECT_EQ(word(db::dw_list), 8);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(word(static_cast<std::uint16_t>(db::dw_list + 1 + i)), i + 1);
  (void)data_code(db::code::list_programs, 2);
  EXPECT_EQ(word(db::dw_list), 3);
  EXPECT_EQ(word(db::dw_list + 3), 20);
  EXPECT_EQ(word(db::dw_list + 4), 0);
  (void)data_code(db::code::list_programs, 0);
  EXPECT_EQ(io_error(), 0x0145) << "page number 0";
  EXPECT_EQ(data_code(db::code::list_blocks, 20, 2), 11);
  EXPECT_EQ(word(db::dw_list), 3);
  EXPECT_EQ(word(db::dw_list + 1), 9);
  (void)data_code(db::code::list_blocks, 0, 1);
  EXPECT_EQ(io_error(), 0x0125);
  (void)data_code(db::code::list_blocks, 7, 0);
  EXPECT_EQ(io_error(), 0x0145);
  (void)data_code(db::code::list_blocks, 33, 1);
  EXPECT_EQ(io_error(), 0x0127);
  // Delete block: 126 block 0, 128 no such block, 127 no such program; deleting both blocks of
  // program 3 leaves it without blocks: listing it is 129.
  (void)data_code(db::code::delete_block, 3, 0);
  EXPECT_EQ(io_error(), 0x0126);
  (void)data_code(db::code::delete_block, 3, 5);
  EXPECT_EQ(io_error(), 0x0128);
  (void)data_code(db::code::delete_block, 44, 1);
  EXPECT_EQ(io_error(), 0x0127);
  (void)data_code(db::code::delete_block, 3, 1);
  EXPECT_EQ(io_error(), 0);
  ASSERT_NE(ctl->programs().find(3), nullptr);
  EXPECT_EQ(ctl->programs().find(3)->blocks.size(), 1U);
  (void)data_code(db::code::delete_block, 3, 2);
  (void)data_code(db::code::list_blocks, 3, 1);
  EXPECT_EQ(io_error(), 0x0129) << "valid, no blocks";
}

TEST_F(W, VoltageChecksRaise40To45AndMask) {
  const std::pair<std::uint8_t, int> cases[] = {{0, 0x40}, {1, 0x41}, {2, 0x42}, {3, 0x43}, {4, 0x44}, {5, 0x45}};
  for (const auto& [b, code] : cases) {
    start(base_md());
    traverse(db::Submode::none);
    drive_enable();
    inputs.fn = [b = b](IoImage& im) { set_input(im, 3, b, true); };
    run(milliseconds(8));
    EXPECT_EQ(error(), code);
    run(milliseconds(20));
    EXPECT_EQ(axis->status().state, motion::AxisState::disabled) << "an error < 60 switches the drive off";
    inputs.fn = [b = b](IoImage& im) { set_input(im, 3, b, false); };
    (void)data_code(db::code::acknowledge);
    EXPECT_EQ(error(), code) << "RESET class: 800C does not clear it";
    pulse(db::bit_reset);
    EXPECT_EQ(error(), 0);
  }
  // MD 41 S masks the voltage check.
  auto md = base_md();
  md[41] = "2";
  start(md);
  traverse(db::Submode::none);
  inputs.fn = [](IoImage& im) { set_input(im, 3, 4, true); };
  run(milliseconds(40));
  EXPECT_EQ(error(), 0);
}

TEST_F(W, DacShortIs46OnlyAboveOneVolt) {
  start(base_md());
  synchronize();
  traverse(db::Submode::mdi);
  inputs.fn = [](IoImage& im) { set_input(im, 3, 6, true); };  // dac_short_A: the readback is 0 V
  // 600 mm/min of MD 3 = 6000 mm/min at MD 23 = 8 V: 0.8 V: no check.
  (void)data_code(db::code::mdi_feed, 60000);
  (void)data_code(db::code::mdi_position, 5000);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_peh); }));
  EXPECT_EQ(error(), 0) << "0.8 V";
  // 1200 mm/min: 1.6 V -> 46 once the ramp passes 1 V (750 mm/min).
  (void)data_code(db::code::mdi_feed, 120000);
  (void)data_code(db::code::mdi_position, 15000);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return error() != 0; }, std::chrono::seconds(2)));
  EXPECT_EQ(error(), 0x46);
  EXPECT_GT(std::abs(axis->status().command_velocity) * 60.0, 750.0 - 0.5 * 500.0 * 60.0 * 0.004);
  run(milliseconds(40));
  EXPECT_EQ(axis->status().state, motion::AxisState::disabled);
  EXPECT_TRUE(ctl->resolve_bit("dac_short_A").has_value());
  EXPECT_TRUE(ctl->resolve_bit("fuse_24v_blown").has_value());
}

}  // namespace
}  // namespace hil::controllers::s5::test
