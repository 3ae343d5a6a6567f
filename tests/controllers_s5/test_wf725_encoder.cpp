// SPDX-License-Identifier: MIT
// WF 725/726 measuring-circuit errors raised by their conditions (manual §6.2.1): cable break 07 and
// level sensor 0B (MD 41 K), 17 in a data mode, pulse monitor 08 (WF 726, MD 41 J), missing zero mark
// 09 in the reference approach (MD 41 N), absolute board missing 30, SSI telegram / interference 31
// (MD 41 U), parity 32 (MD 21), travel difference 33 (4 or 5 jumps in a row), masking 34 (MD 5/7).
#include "wf725_fixture.hpp"

namespace hil::controllers::s5::test {
namespace {

using W = Wf725Fixture;

constexpr std::uint8_t cable = 0, level = 1, zero_mark = 2, pulse_loss = 3, parity = 4, telegram = 5, jump = 6;

/// Encoder fault inputs held by the test (input byte 2).
struct Faults {
  std::uint8_t bits = 0;
  void set(std::uint8_t b, bool on) { bits = static_cast<std::uint8_t>(on ? bits | (1U << b) : bits & ~(1U << b)); }
};

std::map<int, std::string> absolute_md(const std::string& md21 = "2") {
  auto md = base_md();
  md[4] = "2";  // closed loop, absolute encoder
  md[5] = "32768";
  md[7] = "0";
  md[21] = md21;
  md[34] = "1000";
  md[41] = (md21 == "2" || md21 == "3") ? "4" : "0";  // Gray code needs the double reading off (U)
  for (int n : {16, 28, 31, 42}) md.erase(n);         // incremental-only MD
  return md;
}

class E : public W {
 protected:
  void wire() {
    inputs.fn = [this](IoImage& im) { im.set(ByteAddress{IoArea::input, 2}, faults.bits); };
  }
  Faults faults;
};

TEST_F(E, CableBreak07AndLevelSensor0BDisableTheDriveAndLoseThePosition) {
  start(base_md());
  wire();
  synchronize();
  ASSERT_TRUE(ctl->synchronized());
  faults.set(cable, true);
  run(milliseconds(20));
  EXPECT_EQ(error(), 0x07);
  EXPECT_FALSE(ctl->synchronized()) << "position lost";
  EXPECT_EQ(axis->status().state, motion::AxisState::disabled) << "an error < 60 disables the drive";
  EXPECT_TRUE(bit(db::dw_status, db::bit_error));
  // 07 is RESET class: 800C does not clear it, RESET does (the cable repaired).
  (void)data_code(db::code::acknowledge);
  EXPECT_EQ(error(), 0x07);
  faults.set(cable, false);
  pulse(db::bit_reset);
  EXPECT_EQ(error(), 0);
  faults.set(level, true);
  run(milliseconds(20));
  EXPECT_EQ(error(), 0x0B);
}

TEST_F(E, Md41KMasksTheCableCheckAndMd40SimulationAllChecks) {
  auto md = base_md();
  md[41] = "1";
  start(md);
  wire();
  faults.set(cable, true);
  faults.set(level, true);
  run(milliseconds(50));
  EXPECT_EQ(error(), 0);
  md[41] = "0";
  md[40] = "1";
  start(md);
  wire();
  run(milliseconds(50));
  EXPECT_EQ(error(), 0);
}

TEST_F(E, AnErrorBelow60InADataModeWithTheDriveEnabledIs17Too) {
  start(base_md());
  wire();
  synchronize();
  select(db::bit_mode_machine_data, db::Submode::none);
  faults.set(cable, true);
  run(milliseconds(20));
  EXPECT_EQ(count(0x07), 1);
  EXPECT_EQ(count(0x17), 1);
}

TEST_F(E, PulseMonitor08AtTheNextZeroMarkWhilePulsesAreLost) {
  start(base_md());
  wire();
  synchronize();
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 300000);
  (void)data_code(db::code::mdi_position, 25000);  // crosses the zero marks at 10 and 20 mm
  start_pulse();
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_peh) && actual() == 25000; }));
  EXPECT_EQ(error(), 0) << "no pulses lost: no 08";
  faults.set(pulse_loss, true);
  (void)data_code(db::code::mdi_position, 5000);  // back across 20 mm
  start_pulse();
  ASSERT_TRUE(run_until([&] { return error() != 0; }));
  EXPECT_EQ(error(), 0x08);
  EXPECT_GT(actual(), 19000) << "at the first zero mark";
}

TEST_F(E, PulseMonitorIsMaskedByMd41J) {
  auto md = base_md();
  md[41] = "65536";
  start(md);
  wire();
  synchronize();
  faults.set(pulse_loss, true);
  traverse(db::Submode::mdi);
  (void)data_code(db::code::mdi_feed, 300000);
  (void)data_code(db::code::mdi_position, 25000);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_peh) && actual() == 25000; }));
  EXPECT_EQ(error(), 0);
}

TEST_F(E, MissingZeroMarkInTheReferenceApproachIs09UnlessMd41N) {
  for (const bool masked : {false, true}) {
    auto md = base_md();
    md[15] = "2";
    md[41] = masked ? "131072" : "0";
    for (int n : {27, 29, 38, 39, 46, 47}) md.erase(n);
    spec.options = {{"module", "WF725A"}, {"reference_speeds", "3000,600,60"}};
    start(md);
    faults.set(zero_mark, true);
    inputs.fn = [&](IoImage& im) {
      const double p = axis->status().position;
      im.set(BitAddress{IoArea::input, 0, 0}, p >= 23.4 && p <= 31.2);
      im.set(ByteAddress{IoArea::input, 2}, faults.bits);
    };
    traverse(db::Submode::reference);
    drive_enable();
    set_bit(db::dw_control, db::bit_plus, true);
    start_pulse();
    if (masked) {
      ASSERT_TRUE(run_until([&] { return ctl->synchronized() && bit(db::dw_status, db::bit_peh); }));
      EXPECT_EQ(error(), 0);
    } else {
      ASSERT_TRUE(run_until([&] { return error() != 0; }));
      EXPECT_EQ(error(), 0x09);
      EXPECT_FALSE(ctl->synchronized());
      EXPECT_NEAR(command_mm(), 50.0 - 0.0, 0.001) << "one encoder revolution past the missing mark (40 mm)";
    }
  }
}

TEST_F(E, AbsoluteEncoderOnAVariantAModuleIs30) {
  // The profile's rule refuses the MD list at power-up with the module's number 30.
  std::string text;
  for (const auto& [n, v] : absolute_md()) text += "MD " + std::to_string(n) + " = " + v + "\n";
  spec.parameters = write("md.txt", text);
  ControllerRegistry r;
  register_wf725(r);
  auto c = r.create(spec);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().describe().find("error 30"), std::string::npos) << c.error().describe();
  spec.options = {{"module", "WF726B"}};
  start(absolute_md());
  run(milliseconds(20));
  EXPECT_EQ(error(), 0);
}

TEST_F(E, ParallelAbsoluteParity32InterferenceAnd31) {
  spec.options = {{"module", "WF726B"}};
  start(absolute_md("2"));  // Gray without parity: no parity check
  wire();
  faults.set(parity, true);
  run(milliseconds(30));
  EXPECT_EQ(error(), 0);
  start(absolute_md("3"));  // Gray with parity
  wire();
  run(milliseconds(30));
  EXPECT_EQ(error(), 0x32);
  faults.set(parity, false);
  start(absolute_md("1"));
  wire();
  faults.set(telegram, true);
  run(milliseconds(30));
  EXPECT_EQ(error(), 0x31) << "the double reading sees the interference";
  auto md = absolute_md("1");
  md[41] = "4";  // U: no double reading, no 31 on a parallel encoder
  start(md);
  wire();
  run(milliseconds(30));
  EXPECT_EQ(error(), 0);
}

TEST_F(E, SsiTelegram31) {
  spec.options = {{"module", "WF726C"}};
  auto md = absolute_md("4");
  md[7] = "32";  // SSI: steps per revolution
  md[37] = "1";  // < 50 m, 1 Mbit/s
  start(md);
  wire();
  faults.set(telegram, true);
  run(milliseconds(30));
  EXPECT_EQ(error(), 0x31);
}

TEST_F(E, TravelDifference33AfterFourJumpsInARowOrFive) {
  for (const char* n : {"4", "5"}) {
    spec.options = {{"module", "WF726B"}, {"difference_cycles", n}};
    start(absolute_md());
    wire();
    const int cycles = n[0] - '0';
    // cycles - 1 jumps, then a good reading: extrapolated, no error.
    faults.set(jump, true);
    const Duration cycle = ctl->cycle_period();
    run(cycle * (cycles - 1));
    faults.set(jump, false);
    run(cycle * 2);
    EXPECT_EQ(error(), 0) << n;
    faults.set(jump, true);
    run(cycle * (cycles - 1));
    EXPECT_EQ(error(), 0) << n << ": one jump short";
    run(cycle);
    EXPECT_EQ(error(), 0x33) << n;
  }
}

TEST_F(E, MaskingError34OutsideTheUsedRange) {
  spec.options = {{"module", "WF726B"}};
  auto md = absolute_md();
  md[5] = "512";
  md[7] = "76";
  start(md);
  run(milliseconds(20));
  EXPECT_EQ(error(), 0x34) << "reading 0 lies in the masked range 0..76";
  EXPECT_EQ(ctl->machine_data().integer(7), 76);
}

}  // namespace
}  // namespace hil::controllers::s5::test
