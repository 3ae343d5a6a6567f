// SPDX-License-Identifier: MIT
// WF 725/726 traversing programs: the block parser (errors of the memory administration), the
// program memory (10/64 programs, 50/350 + 50 blocks), and programs on the controller: flying
// measurement / flying setting of the actual value (S4, S5), read-in enable G99 (S6), block
// change points MD 46/47 (S7), M output MD 8/9, program errors 61-93.
#include "hil/profiles/loader.hpp"
#include "wf725_fixture.hpp"

namespace hil::controllers::s5::test {
namespace {

using W = Wf725Fixture;

int parse_error(std::string_view text) {
  auto p = parse_wf725_programs(text);
  return p ? 0 : p.error().code;
}

TEST(Wf725Program, TheManualsExamplesParse) {
  auto p = parse_wf725_programs(
      "%1\n"
      "N1 G90          X 1000 000  F 12 000\n"
      "N2 G90 G92 G68  X 2000 000  F 10 000  M0\n"
      "N3 G90          X 3000 000  F 15 000\n"
      "%2 A RAM ; G99\n"
      "N5  G90      X 10 000  F 4000\n"
      "N10 G90 G99  X 20 000  F 4000\n"
      "N15 G90      X 30 000  F 4000\n"
      "%3\n"
      "N1 A G90 G23 X 10 000 F1000\n"
      "N2 B G90 G24 X 10 000 F1000\n"
      "/N3 A G90 G73 X -20 000 F1000 M21 T3\n"
      "N4 G04 F 1500\n"
      "N5 L2 P3\n");
  ASSERT_TRUE(p) << p.error().message;
  ASSERT_EQ(p->size(), 3U);
  const auto& a = (*p)[0];
  ASSERT_EQ(a.blocks.size(), 3U);
  EXPECT_EQ(a.blocks[0].x, 1'000'000);
  EXPECT_EQ(a.blocks[0].f, 12'000);
  EXPECT_EQ(a.blocks[1].group(3), 92);
  EXPECT_EQ(a.blocks[1].group(2), 68);
  EXPECT_EQ(a.blocks[1].m, 0);
  EXPECT_EQ((*p)[1].valid_axes, "A");
  EXPECT_TRUE((*p)[1].ram);
  EXPECT_TRUE((*p)[1].blocks[1].has_g(99));
  const auto& c = (*p)[2];
  EXPECT_EQ(c.blocks[1].axis, 'B');
  EXPECT_TRUE(c.blocks[2].skippable);
  EXPECT_EQ(c.blocks[2].x, -20'000);
  EXPECT_EQ(c.blocks[2].group(4), 73);
  EXPECT_EQ(c.blocks[2].tool, 3);
  EXPECT_EQ(c.blocks[3].f, 1500);
  EXPECT_EQ(c.blocks[4].call, 2);
  EXPECT_EQ(c.blocks[4].passes, 3);
  for (const auto& prog : *p) {
    auto back = parse_wf725_programs(make_wf725_program_text(prog));
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(back->front(), prog);
  }
}

TEST(Wf725Program, SyntaxErrorsCarryTheMemoryAdministrationsNumbers) {
  EXPECT_EQ(parse_error("N1 G90 X1 F1\n"), 230) << "block before the header";
  EXPECT_EQ(parse_error("%0\nN1 X1 F1\n"), 230);
  EXPECT_EQ(parse_error("%1\nN0 X1 F1\n"), 231);
  EXPECT_EQ(parse_error("%1\nG90 X1 F1\n"), 231) << "no N";
  EXPECT_EQ(parse_error("%1\nN1 G90 G91 X1 F1\n"), 232) << "two G of group 1";
  EXPECT_EQ(parse_error("%1\nN1 G68 G99 X1 F1\n"), 233);
  EXPECT_EQ(parse_error("%1\nN1 G92 G54 X1 F1 T1\n"), 234);
  EXPECT_EQ(parse_error("%1\nN1 G23 G73 X1 F1\n"), 235);
  EXPECT_EQ(parse_error("%1\nN1 G04\n"), 236);
  EXPECT_EQ(parse_error("%1\nN1 L2\n"), 237);
  EXPECT_EQ(parse_error("%1\nN1 G90 L2 P1\n"), 238);
  EXPECT_EQ(parse_error("%1\nN1 X1 F1 T21\n"), 239);
  EXPECT_EQ(parse_error("%1\nN1 L2 P0\n"), 240);
  EXPECT_EQ(parse_error("%1\nN1 G05 X1 F1\n"), 220) << "no such G";
  EXPECT_EQ(parse_error("%1\nN1 X1 Y2\n"), 220);
  EXPECT_EQ(parse_error("%1\nN2 X1 F1\nN1 X2 F1\n"), 220) << "block numbers ascend";
  EXPECT_EQ(parse_error("%1\nN1 X 80 000 000 F1\n"), 220);
  EXPECT_EQ(parse_error("%1\nN1 X1 F1\n%1\nN1 X1 F1\n"), 220);
  auto e = parse_wf725_programs("%4\nN1 X1 F1\nN7 G90 G91\n");
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().program, 4);
  EXPECT_EQ(e.error().block, 7);
  EXPECT_EQ(e.error().line, 3);
}

Wf725Program program(int number, int blocks, bool ram = false) {
  Wf725Program p;
  p.number = number;
  p.ram = ram;
  for (int i = 1; i <= blocks; ++i) {
    Wf725Block b;
    b.number = i;
    b.x = i;
    b.f = 100;
    p.blocks.push_back(b);
  }
  return p;
}

TEST(Wf725ProgramStore, MemoryLimitsOfBothModules) {
  Wf725ProgramStore wf725(wf725_memory_limits(725));
  for (int n = 1; n <= 10; ++n) EXPECT_EQ(wf725.store(program(n, n <= 5 ? 10 : 0)), 0);
  EXPECT_EQ(wf725.store(program(11, 1)), 124) << "11th program";
  EXPECT_EQ(wf725.store(program(6, 1)), 123) << "EEPROM: 50 blocks stored already";
  EXPECT_EQ(wf725.store(program(6, 50, true)), 0) << "RAM: 50 blocks";
  EXPECT_EQ(wf725.teach(7, 1, Wf725Block{}, true), 138);
  EXPECT_EQ(wf725.teach(12, 1, Wf725Block{}, false), 137);
  EXPECT_EQ(wf725.teach(0, 1, Wf725Block{}, false), 135);
  EXPECT_EQ(wf725.teach(1, 0, Wf725Block{}, false), 136);
  EXPECT_EQ(wf725.teach(1, 5, Wf725Block{}, false), 0) << "replacing a block needs no room";
  EXPECT_EQ(wf725.store(program(0, 1)), 125);
  EXPECT_EQ(wf725.remove(0), 125);
  EXPECT_EQ(wf725.remove(42), 127);
  EXPECT_EQ(wf725.remove(10), 0);
  Wf725ProgramStore wf726(wf725_memory_limits(726));
  for (int n = 1; n <= 64; ++n) ASSERT_EQ(wf726.store(program(n, n <= 7 ? 50 : 0)), 0);
  EXPECT_EQ(wf726.store(program(65, 0)), 124);
  EXPECT_EQ(wf726.store(program(8, 1)), 123) << "EEPROM: 350 blocks";
  EXPECT_EQ(wf726.store(program(8, 50, true)), 0);
  EXPECT_EQ(wf726.blocks_used(false), 350);
  EXPECT_EQ(wf726.blocks_used(true), 50);
}

/// MD 15 = 3047: E1 start, E2 read-in enable (4), E4 flying measurement (3); wide limits.
std::map<int, std::string> program_md() {
  auto md = base_md();
  md[15] = "3047";
  md[11] = "-5000000";
  md[12] = "-6000000";
  md[13] = "5000000";
  md[14] = "6000000";
  return md;
}

class WfProgram : public Wf725Fixture {
 protected:
  void run_program(int number, db::Submode sub = db::Submode::automatic) {
    synchronize();
    traverse(sub);
    ctl->write_db_word(db::dw_program, static_cast<std::uint16_t>(number));
    start_pulse();
  }
  bool program_active() const { return bit(db::dw_flags, 1); }
};

TEST_F(WfProgram, S5FlyingSettingOfTheActualValue) {
  start(program_md(),
        "%1\n"
        "N1 G90          X 10 000  F 300 000\n"
        "N2 G90 G92 G68  X 20 000  F 120 000\n"
        "N3 G90          X 30 000  F 300 000\n");
  const BitAddress e4{IoArea::input, 0, 3};
  inputs.fn = [&](IoImage& im) { im.set(e4, axis->status().position < 4.0); };
  run_program(1);
  bool rested_after_edge = false;
  ASSERT_TRUE(run_until([&] {
    if (ctl->measured_um() && !program_active()) return true;
    // N3 lies behind (G68 ran negative): the axis reverses within one motion, no standstill.
    if (ctl->measured_um() && (!axis->status().busy || bit(db::dw_flags, 0))) rested_after_edge = true;
    return false;
  }));
  EXPECT_FALSE(rested_after_edge) << "N2 -> N3 without a stop or a new start";
  ASSERT_TRUE(ctl->measured_um());
  // E4 is sampled at the controller cycle: the latch lies within one cycle's travel (20 mm/s x 4 ms).
  EXPECT_LE(*ctl->measured_um(), 4000);
  EXPECT_GE(*ctl->measured_um(), 4000 - 80);
  EXPECT_EQ(error(), 0);
  run(milliseconds(100));
  EXPECT_NEAR(actual(), 30000, 1) << "N3 in the coordinates set at the edge (actual := 20 000)";
  // The axis went from the edge (4 mm, now 20 mm) to 30 mm: 10 mm further.
  EXPECT_NEAR(command_mm(), 4.0 + 10.0, 0.5);
}

TEST_F(WfProgram, S4FlyingMeasurementWithM0StopsAndDataCode32ReadsTheLatch) {
  start(program_md(),
        "%1\n"
        "N1 G90          X 10 000  F 300 000\n"
        "N2 G90 G92 G68  X 20 000  F 120 000  M0\n"
        "N3 G90          X 30 000  F 300 000\n");
  const BitAddress e4{IoArea::input, 0, 3};
  inputs.fn = [&](IoImage& im) { im.set(e4, axis->status().position < 4.0); };
  run_program(1);
  ASSERT_TRUE(run_until([&] { return bit(db::dw_flags, 0); })) << "waits for start after the ramp stop";
  EXPECT_FALSE(axis->status().busy);
  const auto latched = data_code(db::code::measured);
  EXPECT_LE(latched, 4000);
  EXPECT_GE(latched, 4000 - 80);
  EXPECT_EQ(latched, std::llround(*ctl->measured_um()));
  EXPECT_LT(command_mm(), 4.0) << "stopped on the braking ramp after the edge";
  EXPECT_NEAR(actual(), command_mm() * 1000, 1) << "no actual value was set";
  start_pulse();
  ASSERT_TRUE(run_until([&] { return !program_active(); }));
  run(milliseconds(60));
  EXPECT_NEAR(actual(), 30000, 1) << "the new start runs N3";
}

TEST_F(WfProgram, FlyingMeasurementWithoutAFastInputIsB9) {
  auto md = program_md();
  md[15] = "47";
  start(md, "%1\nN1 G90 G68 X 1000 F 120 000\n");
  run_program(1);
  EXPECT_EQ(error(), 0xB9);
}

const char* g99_program =
    "%2\n"
    "N5  G90      X 10 000  F 300 000\n"
    "N10 G90 G99  X 20 000  F 300 000\n"
    "N15 G90      X 30 000  F 300 000\n";

TEST_F(WfProgram, S6aReadInEnableAlreadyPresentFlyingBlockChange) {
  start(program_md(), g99_program);
  const BitAddress e2{IoArea::input, 0, 1};
  inputs.fn = [&](IoImage& im) { im.set(e2, true); };
  run_program(2);
  double min_v = 1e9;
  ASSERT_TRUE(run_until([&] {
    // At F between N5's acceleration (up to 2.5 mm) and N15's braking (from 27.5 mm).
    if (axis->status().command_position > 3.0 && axis->status().command_position < 27.0)
      min_v = std::min(min_v, std::abs(axis->status().command_velocity));
    return !program_active();
  }));
  EXPECT_GT(min_v, 49.0) << "N5 -> N10 -> N15 without slowing down (F = 50 mm/s)";
  ASSERT_EQ(ctl->block_changes_um().size(), 2U);
  run(milliseconds(60));
  EXPECT_NEAR(actual(), 30000, 1);
}

TEST_F(WfProgram, S6bReadInEnableDuringTheDecelerationStartsN10AtOnce) {
  start(program_md(), g99_program);
  const BitAddress e2{IoArea::input, 0, 1};
  bool enable = false;
  inputs.fn = [&](IoImage& im) { im.set(e2, enable); };
  run_program(2);
  // The enable comes while N5 brakes (braking distance 2.5 mm from 50 mm/s at 500 mm/s²).
  ASSERT_TRUE(run_until([&] { return axis->status().command_position > 8.5; }));
  enable = true;
  double min_v = 1e9;
  ASSERT_TRUE(run_until([&] {
    if (axis->status().command_position < 19.0) min_v = std::min(min_v, std::abs(axis->status().command_velocity));
    return !program_active();
  }));
  EXPECT_GT(min_v, 1.0) << "no stop at N5's end: N10 started from the braking axis";
  ASSERT_GE(ctl->block_changes_um().size(), 1U);
  EXPECT_GT(ctl->block_changes_um()[0], 8500);
  EXPECT_LT(ctl->block_changes_um()[0], 10000);
  run(milliseconds(60));
  EXPECT_NEAR(actual(), 30000, 1);
}

TEST_F(WfProgram, S6cReadInEnableAfterN5WaitsAtN5sEnd) {
  start(program_md(), g99_program);
  const BitAddress e2{IoArea::input, 0, 1};
  bool enable = false;
  inputs.fn = [&](IoImage& im) { im.set(e2, enable); };
  run_program(2);
  ASSERT_TRUE(run_until([&] { return bit(db::dw_flags, 2); })) << "waits for the read-in enable";
  run(milliseconds(500));
  EXPECT_NEAR(actual(), 10000, 1) << "N5 finished, N10 not started";
  EXPECT_FALSE(axis->status().busy);
  enable = true;
  ASSERT_TRUE(run_until([&] { return !program_active(); }));
  run(milliseconds(60));
  EXPECT_NEAR(actual(), 30000, 1);
}

TEST_F(WfProgram, S7BlockChangePointsMd46AndMd47) {
  auto md = program_md();
  md[46] = "100";
  md[47] = "700";
  start(md,
        "%3\n"
        "N1 G90 G23 X 10 000 F 300 000\n"
        "N2 G90 G73 X 20 000 F 300 000\n"
        "N3 G90     X 30 000 F 300 000\n");
  run_program(3);
  ASSERT_TRUE(run_until([&] { return !program_active(); }));
  ASSERT_EQ(ctl->block_changes_um().size(), 2U);
  // MD 46/47 below the braking distance (2.5 mm): the change is that far before the end, to
  // within one controller cycle of travel at the speed there.
  EXPECT_NEAR(ctl->block_changes_um()[0], 10000 - 100, 45);
  EXPECT_NEAR(ctl->block_changes_um()[1], 20000 - 700, 80);
}

TEST_F(WfProgram, S7ToleranceAboveTheBrakingDistanceChangesAtTheBrakingStart) {
  auto md = program_md();
  md[46] = "5000";
  start(md,
        "%3\n"
        "N1 G90 G23 X 10 000 F 300 000\n"
        "N2 G90     X 20 000 F 300 000\n");
  run_program(3);
  ASSERT_TRUE(run_until([&] { return !program_active(); }));
  ASSERT_EQ(ctl->block_changes_um().size(), 1U);
  EXPECT_NEAR(ctl->block_changes_um()[0], 10000 - 2500, 205) << "the braking start (2.5 mm, one cycle = 0.2 mm)";
}

TEST_F(WfProgram, MFunctionsHandshakeBeforeTheMotion) {
  auto md = program_md();
  md[9] = "2";  // before the block: the axis waits for the acknowledgement
  start(md,
        "%4\n"
        "N1 G90 X 5 000 F 300 000 M21\n"
        "N2 M22\n");
  run_program(4);
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_m_strobe); }));
  EXPECT_EQ(word(db::dw_status) >> 8, 21) << "DL 3 = M21";
  run(milliseconds(200));
  EXPECT_FALSE(axis->status().busy) << "no motion before the acknowledgement";
  set_bit(db::dw_enable, db::bit_m_ack, true);
  run(milliseconds(20));
  EXPECT_FALSE(bit(db::dw_status, db::bit_m_strobe));
  EXPECT_TRUE(axis->status().busy);
  set_bit(db::dw_enable, db::bit_m_ack, false);
  ASSERT_TRUE(run_until([&] { return bit(db::dw_status, db::bit_m_strobe); }));
  EXPECT_EQ(word(db::dw_status) >> 8, 22);
  EXPECT_NEAR(actual(), 5000, 1);
  set_bit(db::dw_enable, db::bit_m_ack, true);
  run(milliseconds(20));
  set_bit(db::dw_enable, db::bit_m_ack, false);
  ASSERT_TRUE(run_until([&] { return !program_active(); }));
  EXPECT_EQ(ctl->m_history(), (std::vector<int>{21, 22}));
}

TEST_F(WfProgram, TimedMOutputAndSubprogramsAndDwell) {
  auto md = program_md();
  md[8] = "100";  // timed output, 100 ms
  start(md,
        "%5\n"
        "N1 G91 F 300 000\n"
        "N2 L6 P3\n"
        "N3 G04 F 250 M30\n"
        "%6\n"
        "N1 X 1 000 M7\n");
  run_program(5);
  ASSERT_TRUE(run_until([&] { return !program_active(); }));
  EXPECT_EQ(ctl->m_history(), (std::vector<int>{7, 7, 7, 30}));
  run(milliseconds(60));
  EXPECT_NEAR(actual(), 3000, 1) << "three passes of the incremental subprogram";
}

TEST_F(WfProgram, SingleStepAndAutomaticSingleStep) {
  start(program_md(),
        "%7\n"
        "N1 G90 X 1 000 F 300 000\n"
        "N2 G90 X 2 000\n"
        "N3 G90 X 3 000\n");
  synchronize();
  traverse(db::Submode::single_step);
  ctl->write_db_word(db::dw_program, 7);
  start_pulse();
  EXPECT_EQ(error(), 0x64) << "block number 0 in DL 2";
  ctl->write_db_word(db::dw_enable, static_cast<std::uint16_t>(9 << 8 | 1));
  start_pulse();
  EXPECT_EQ(error(), 0x67) << "N9 does not exist";
  ctl->write_db_word(db::dw_enable, static_cast<std::uint16_t>(2 << 8 | 1));
  start_pulse();
  ASSERT_TRUE(run_until([&] { return !program_active(); }));
  EXPECT_EQ(error(), 0x73) << "N2 alone has no feed";
  (void)data_code(db::code::acknowledge);
  ctl->write_db_word(db::dw_enable, static_cast<std::uint16_t>(1 << 8 | 1));
  start_pulse();
  ASSERT_TRUE(run_until([&] { return !program_active(); }));
  run(milliseconds(60));
  EXPECT_NEAR(actual(), 1000, 1);
  traverse(db::Submode::automatic_step);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return bit(db::dw_flags, 0); }));
  EXPECT_NEAR(actual(), 1000, 1);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return bit(db::dw_flags, 0); }));
  EXPECT_NEAR(actual(), 2000, 1);
  EXPECT_EQ(word(db::dw_block), (7 << 8) | 2);
  start_pulse();
  ASSERT_TRUE(run_until([&] { return bit(db::dw_flags, 0); }));
  start_pulse();
  ASSERT_TRUE(run_until([&] { return !program_active(); }));
  EXPECT_NEAR(actual(), 3000, 1);
}

TEST_F(WfProgram, ProgramStartErrors) {
  auto md = program_md();
  for (int n : {27, 29, 38, 39, 46, 47}) md.erase(n);
  spec.options = {{"module", "WF725A"}};
  md[15] = "2";
  std::string big = "%9\n";
  for (int i = 1; i <= 41; ++i) big += "N" + std::to_string(i) + " G91 X 1 F 1000\n";
  start(md, big + "%8 B\nN1 X 1 F 1000\n%10\nN1 G90\n");
  synchronize();
  traverse(db::Submode::automatic);
  const auto expect = [&](int program, int code) {
    ctl->write_db_word(db::dw_program, static_cast<std::uint16_t>(program));
    start_pulse();
    EXPECT_EQ(error(), code) << "program " << program;
    (void)data_code(db::code::acknowledge);
  };
  expect(0, 0x80);
  expect(3, 0x81);
  expect(8, 0x90);
  expect(9, 0x68);  // 41 blocks on a WF 725 (40 per program)
  expect(10, 0x62);
}

TEST_F(WfProgram, ProgramRuleErrors) {
  start(program_md(),
        "%1\nN1 G91 X 10 F 1000\n/N2 G91 X 10\n"
        "%2\nN1 G93\n"
        "%3\nN1 G92 X 0\nN2 G92 X 5\n"
        "%4\nN1 T0\n"
        "%5\nN1 G53\n"
        "%6\nN1 L7 P1\n%7\nN1 L8 P1\n%8\nN1 L9 P1\n%9\nN1 G91 X 1 F 1000\n"
        "%11\nN1 G91 X 10 F 1000 T2\nN2 A G17 X 5\nN3 B X 5\n");
  synchronize();
  traverse(db::Submode::automatic);
  set_bit(db::dw_control, db::bit_skip, true);
  const auto expect = [&](int program, int code) {
    ctl->write_db_word(db::dw_program, static_cast<std::uint16_t>(program));
    start_pulse();
    run_until([&] { return !program_active(); });
    EXPECT_EQ(error(), code) << "program " << program;
    (void)data_code(db::code::acknowledge);
  };
  expect(1, 0x88);  // the last block is skippable and "skip block" is set
  expect(2, 0x93);
  expect(3, 0x92);
  expect(4, 0x87);
  expect(5, 0x89);
  expect(6, 0x91);   // L7 -> L8 -> L9: a third subprogram level
  expect(11, 0x6B);  // a G17 pair moves axis B, which a lone axis' module does not have
}

}  // namespace
}  // namespace hil::controllers::s5::test

namespace hil::controllers::s5::test {
namespace {

TEST(Wf725Program, TheProfilesGTableIsTheParsersTable) {
  auto profile = profiles::find_profile("wf725-726");
  ASSERT_TRUE(profile) << profile.error().describe();
  auto syntax = wf725_program_syntax(**profile);
  ASSERT_TRUE(syntax) << syntax.error();
  for (int g = 0; g < 100; ++g) EXPECT_EQ(syntax->group(g), wf725_g_group(g)) << "G" << g;
  Wf725ProgramSyntax narrow;
  narrow.g_group[90] = 1;
  EXPECT_FALSE(parse_wf725_programs("%1\nN1 G91 X1 F1\n", narrow));
  EXPECT_TRUE(parse_wf725_programs("%1\nN1 G90 X1 F1\n", narrow));
}

}  // namespace
}  // namespace hil::controllers::s5::test
