// SPDX-License-Identifier: MIT
// Combined programs across the axes of a WF 726 (docs/wf725.md, "Combined programs"): the
// interpolation pairs on input (174, 181), blocks of another axis one after the other, G17-G19
// pairs that start and end together at the path feed, the slave checks 69/6B, a slave error as
// 6A, RESET of the master, D2, 7A, and the M functions that stay the master's.
#include <cmath>

#include "hil/controllers/s5/wf726_module_controller.hpp"
#include "wf726_module_fixture.hpp"

namespace hil::controllers::s5::test {
namespace {

using M = Wf726ModuleFixture;

Wf725SyntaxError parse_error(std::string_view text) {
  auto p = parse_wf725_programs(text);
  return p ? Wf725SyntaxError{} : p.error();
}

TEST(Wf726Interpolation, PairsAreCheckedOnInputWithTheirBlock) {
  EXPECT_TRUE(parse_wf725_programs("%1\nN1 A G17 G90 X 30 000 F 60 000\nN2 B X 40 000\nN3 X 0\n"));
  EXPECT_TRUE(parse_wf725_programs("%1\nN1 C G18 X 1 F 100\nN2 A G18 X 2\n"));  // either order, G repeated
  EXPECT_TRUE(parse_wf725_programs("%1\n/N1 B G19 X 1 F 100\n/N2 C X 2\n"));
  const auto expect = [](std::string_view text, int code, int program, int block, int line) {
    const auto e = parse_error(text);
    EXPECT_EQ(e.code, code) << text << ": " << e.message;
    EXPECT_EQ(e.program, program) << text;
    EXPECT_EQ(e.block, block) << text;
    EXPECT_EQ(e.line, line) << text;
    EXPECT_FALSE(e.message.empty());
  };
  // 174: the assignment of letters and G is not kept.
  expect("%1\nN1 A G18 X 1 F 100\nN2 B X 2\n", 174, 1, 2, 3);      // B is not in A+C
  expect("%1\nN1 G17 X 1 F 100\nN2 B X 2\n", 174, 1, 1, 2);        // the opener has no letter
  expect("%3\nN1 A G17 X 1 F 100\nN2 A X 2\n", 174, 3, 2, 3);      // one block per axis
  expect("%1\nN1 A G17 X 1 F 100\nN2 B G18 X 2\n", 174, 1, 2, 3);  // another G of the group
  expect("%1\nN1 A G17 X 1 F 100\nN2 B F 100\n", 174, 1, 2, 3);    // no position
  expect("%1\nN1 A G17 X 1 F 100\n/N2 B X 2\n", 174, 1, 2, 3);     // one of them skippable
  expect("%1\nN1 A G17 G92 X 1 F 100\nN2 B X 2\n", 174, 1, 1, 2);  // G92 in a pair
  // 181: the pair is not entered in sequence / in ascending block numbers.
  expect("%1\nN1 X 5 F 100\nN7 A G17 X 1 F 100\n", 181, 1, 7, 3);  // no partner
  expect("%1\nN1 A G17 X 1 F 100\n%2\nN1 X 1 F 100\n", 181, 1, 1, 2);
  expect("%1\nN5 A G17 X 1 F 100\nN3 B X 2\n", 181, 1, 3, 3);
  expect("%1\nN1 A G17 X 1 F 100\nN2 L5 P1\n", 181, 1, 2, 3);
  // Nothing of a faulty text: the good program before the bad one is not returned either.
  EXPECT_FALSE(parse_wf725_programs("%1\nN1 X 1 F 100\n%2\nN1 A G19 X 1 F 100\nN2 B X 2\n"));
  // The canonical text keeps letters and pairs.
  const auto p = parse_wf725_programs("%4 AB\nN1 A G17 G91 X 30 000 F 60 000 M21\nN2 B X -4\nN3 C X 7\n");
  ASSERT_TRUE(p);
  const auto back = parse_wf725_programs(make_wf725_program_text(p->front()));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->front(), p->front());
  EXPECT_TRUE(wf725_pair_partner(p->front(), 1));
  EXPECT_FALSE(wf725_pair_partner(p->front(), 0));
  EXPECT_FALSE(wf725_pair_partner(p->front(), 2));
}

TEST_F(M, BlocksOfAnotherAxisRunOneAfterTheOther) {
  start("AB", "%5\nN1 G90 X 10 000 F 60 000\nN2 B X 20 000\nN3 X 0\nN4 B G91 X -5 000 F 30 000\n");
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 5);
  bool overlap = false, b_moved = false, b_shows_program = false;
  ASSERT_TRUE(run_until([&] {
    overlap = overlap || (moving('A') && moving('B'));
    b_moved = b_moved || moving('B');
    b_shows_program = b_shows_program || (word('B', db::dw_block) >> 8) == 5;
    return !program_active('A');
  }));
  EXPECT_FALSE(overlap) << "consecutive blocks of different axes run one after the other";
  EXPECT_TRUE(b_moved);
  EXPECT_TRUE(b_shows_program) << "the slave shows the master's program in DL 22";
  EXPECT_EQ(error('A'), 0);
  EXPECT_EQ(error('B'), 0);
  run(milliseconds(100));
  EXPECT_NEAR(actual('A'), 0, 2);
  EXPECT_NEAR(actual('B'), 15'000, 2);  // N4: G91 from 20 mm
  EXPECT_EQ(c('B').master(), nullptr);
  EXPECT_EQ(word('B', db::dw_block), 0);
}

// Path of the pair: A 30 mm, B 40 mm, 50 mm at F 600 mm/min = 10 mm/s: A 6 mm/s, B 8 mm/s.
struct PairRun {
  long start_a = -1, start_b = -1, end_a = -1, end_b = -1;
  double peak_a = 0, peak_b = 0;
};

PairRun run_pair(M& t) {
  PairRun r;
  long cycle = 0;
  EXPECT_TRUE(t.run_until([&] {
    ++cycle;
    const double va = std::abs(t.ax('A').status().command_velocity), vb = std::abs(t.ax('B').status().command_velocity);
    r.peak_a = std::max(r.peak_a, va);
    r.peak_b = std::max(r.peak_b, vb);
    if (va > 0 && r.start_a < 0) r.start_a = cycle;
    if (vb > 0 && r.start_b < 0) r.start_b = cycle;
    if (va > 0) r.end_a = cycle;
    if (vb > 0) r.end_b = cycle;
    return !t.program_active('A');
  }));
  return r;
}

TEST_F(M, G17PairStartsAndEndsTogetherAtThePathFeed) {
  start("AB", "%6\nN1 A G17 G90 X 30 000 F 60 000\nN2 B X 40 000\n");
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 6);
  const auto r = run_pair(*this);
  EXPECT_EQ(r.start_a, r.start_b) << "both axes start in the same cycle";
  EXPECT_EQ(r.end_a, r.end_b) << "both axes arrive in the same cycle";
  EXPECT_NEAR(r.peak_a, 6.0, 0.01);  // mm/s
  EXPECT_NEAR(r.peak_b, 8.0, 0.01);
  // 50 mm at 10 mm/s, plus the ramps of a few ms
  EXPECT_NEAR(static_cast<double>((r.end_a - r.start_a) * every), 5000.0, 30.0);
  run(milliseconds(100));
  EXPECT_NEAR(actual('A'), 30'000, 2);
  EXPECT_NEAR(actual('B'), 40'000, 2);
  EXPECT_EQ(error('A'), 0);
  EXPECT_EQ(error('B'), 0);
}

TEST_F(M, PairFeedIsReducedToTheSlowerAxisMd3AndRampsStayTogether) {
  auto md_b = base_md();
  md_b[3] = "300";  // B: 5 mm/s at most; B would need 8 mm/s at F 600 mm/min
  md_b[1] = "50";   // and a tenth of A's ramp
  md_b[2] = "50";
  start("AB", "%6\nN1 B G17 G91 X 40 000 F 60 000\nN2 A X 30 000\n", {{'B', md_b}});
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 6);
  const auto r = run_pair(*this);
  EXPECT_EQ(r.start_a, r.start_b);
  EXPECT_EQ(r.end_a, r.end_b);
  EXPECT_NEAR(r.peak_b, 5.0, 0.01);
  EXPECT_NEAR(r.peak_a, 3.75, 0.01);  // the path keeps its direction: 30/40 of B's speed
  run(milliseconds(100));
  EXPECT_NEAR(actual('A'), 30'000, 2);
  EXPECT_NEAR(actual('B'), 40'000, 2);
}

TEST_F(M, SlaveNotInSubmode0Is69ThereAnd6BInTheMasterAndNothingMoves) {
  start("AB", "%7\nN1 B X 10 000 F 60 000\n");
  ready('B', db::Submode::mdi);
  ready('A', db::Submode::automatic);
  start_program('A', 7);
  EXPECT_EQ(error('A'), 0x6B);
  EXPECT_EQ(error('B'), 0x69);
  EXPECT_FALSE(program_active('A'));
  run(milliseconds(300));
  EXPECT_FALSE(moving('B'));
  EXPECT_EQ(actual('B'), 0);
  // Submode "0" on B, 800C on A: the program runs.
  traverse('B', db::Submode::none);
  acknowledge('A');
  start_program('A', 7);
  ASSERT_TRUE(run_until([&] { return !program_active('A'); }));
  run(milliseconds(100));
  EXPECT_EQ(error('A'), 0);
  EXPECT_EQ(error('B'), 0);  // 69 is self-acknowledging: the slave's next block cleared it
  EXPECT_NEAR(actual('B'), 10'000, 2);
}

TEST_F(M, ASlaveThatLeftSubmode0BeforeItsBlockIs69And6BThere) {
  start("AB", "%7\nN1 X 10 000 F 60 000\nN2 B X 10 000\n");
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 7);
  ASSERT_TRUE(program_active('A'));
  traverse('B', db::Submode::mdi);  // while A runs N1
  ASSERT_TRUE(run_until([&] { return !program_active('A'); }));
  EXPECT_EQ(error('A'), 0x6B);
  EXPECT_EQ(error('B'), 0x69);
  EXPECT_NEAR(actual('A'), 10'000, 2);
  EXPECT_EQ(actual('B'), 0);
}

TEST_F(M, ASlaveOnItsPreLimitIs96ThereAnd6AInTheMaster) {
  start("AB", "%6\nN1 A G17 G90 X 30 000 F 60 000\nN2 B X 120 000\n");  // B's MD 13: 96.417 mm
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 6);
  ASSERT_TRUE(run_until([&] { return !program_active('A'); }));
  run(milliseconds(100));
  EXPECT_EQ(error('B'), 0x96);
  EXPECT_EQ(error('A'), 0x6A);
  EXPECT_EQ(actual('B'), 96'417) << "stopped exactly on the pre-limit";
}

TEST_F(M, SingleStepOntoThePartnerRunsThePairAndASkippedPairIsSkippedWhole) {
  start("AB", "%6\n/N1 A G17 G90 X 30 000 F 60 000\n/N2 B X 40 000\nN3 X 5 000 F 60 000\n");
  ready('B', db::Submode::none);
  ready('A', db::Submode::single_step);
  c('A').write_db_word(db::dw_enable, static_cast<std::uint16_t>(word('A', db::dw_enable) | (2U << 8)));  // DL 2 = N2
  start_program('A', 6);
  ASSERT_TRUE(run_until([&] { return !program_active('A'); }));
  run(milliseconds(100));
  EXPECT_NEAR(actual('A'), 30'000, 2);
  EXPECT_NEAR(actual('B'), 40'000, 2);
  // Automatic cycle with "skip block": the pair N1/N2 is skipped, N3 runs.
  traverse('A', db::Submode::automatic);
  set_bit('A', db::dw_control, db::bit_skip, true);
  start_program('A', 6);
  ASSERT_TRUE(run_until([&] { return !program_active('A'); }));
  run(milliseconds(100));
  EXPECT_EQ(error('A'), 0);
  EXPECT_NEAR(actual('A'), 5'000, 2);
  EXPECT_NEAR(actual('B'), 40'000, 2);
}

TEST_F(M, AnAxisTheModuleLacksIs6B) {
  start("AB", "%8\nN1 C X 10 000 F 60 000\n");
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 8);
  EXPECT_EQ(error('A'), 0x6B);
  EXPECT_EQ(error('B'), 0);
}

TEST_F(M, SlaveErrorDuringThePairIs6AInTheMasterAndStopsEveryAxis) {
  start("AB", "%6\nN1 A G17 G90 X 30 000 F 60 000\nN2 B X 40 000\n");
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 6);
  run(std::chrono::seconds(2));
  ASSERT_TRUE(moving('A'));
  set_bit('B', db::dw_enable, db::bit_drive_enable, false);  // B's drive enable drops: 13 there
  run(milliseconds(500));
  EXPECT_EQ(error('B'), 0x13);
  EXPECT_EQ(error('A'), 0x6A);
  EXPECT_FALSE(program_active('A'));
  EXPECT_FALSE(moving('A'));
  EXPECT_LT(actual('A'), 20'000);
  EXPECT_EQ(c('B').master(), nullptr);
}

TEST_F(M, ResetOfTheMasterEndsTheProgramOnEveryAxis) {
  start("AB", "%6\nN1 A G17 G90 X 30 000 F 60 000\nN2 B X 40 000\nN3 X 0\n");
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 6);
  run(std::chrono::seconds(2));
  ASSERT_TRUE(moving('B'));
  pulse('A', db::bit_reset);
  run(milliseconds(500));
  EXPECT_FALSE(moving('A'));
  EXPECT_FALSE(moving('B'));
  EXPECT_FALSE(program_active('A'));
  EXPECT_EQ(c('B').master(), nullptr);
  EXPECT_LT(actual('B'), 30'000);
  EXPECT_EQ(error('A'), 0);
  EXPECT_EQ(error('B'), 0);
  // B takes its own jobs again (MDI is not refused as busy).
  EXPECT_TRUE(c('B').traversing());
}

TEST_F(M, InterpolationWithAJerkLimitIsD2) {
  auto md_b = base_md();
  md_b[38] = "1000";
  start("AB", "%6\nN1 A G17 X 30 000 F 60 000\nN2 B X 40 000\n", {{'B', md_b}});
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 6);
  run(milliseconds(200));
  EXPECT_EQ(error('A'), 0xD2);
  EXPECT_FALSE(program_active('A'));
  EXPECT_EQ(actual('A'), 0);
  EXPECT_EQ(actual('B'), 0);
}

TEST_F(M, InterpolationOnAWf725Is7A) {
  auto md = base_md();
  for (const int n : {27, 29, 38, 39, 46, 47}) md.erase(n);  // no such MD on a WF 725
  md[15] = "1";
  start("AB", "%6\nN1 A G17 X 30 000 F 60 000\nN2 B X 40 000\n", {{'A', md}, {'B', md}}, "WF725A");
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 6);
  run(milliseconds(200));
  EXPECT_EQ(error('A'), 0x7A);
  EXPECT_EQ(actual('B'), 0);
}

TEST_F(M, MFunctionsOfASlaveBlockAreTheMastersAfterItsMotion) {
  start("AB", "%9\nN1 B X 10 000 F 60 000 M21\nN2 X 5 000\n");
  ready('B', db::Submode::none);
  ready('A', db::Submode::automatic);
  start_program('A', 9);
  ASSERT_TRUE(run_until([&] { return bit('A', db::dw_status, db::bit_m_strobe); }));
  EXPECT_EQ(word('A', db::dw_status) >> 8, 21);
  EXPECT_NEAR(actual('B'), 10'000, 2) << "the M function comes after the slave's motion";
  EXPECT_FALSE(moving('A')) << "the master waits for the acknowledgement";
  set_bit('A', db::dw_enable, db::bit_m_ack, true);
  run(milliseconds(24));
  set_bit('A', db::dw_enable, db::bit_m_ack, false);
  ASSERT_TRUE(run_until([&] { return !program_active('A'); }));
  run(milliseconds(100));
  EXPECT_NEAR(actual('A'), 5'000, 2);
  EXPECT_EQ(c('A').m_history(), std::vector<int>{21});
  EXPECT_TRUE(c('B').m_history().empty());
}

}  // namespace
}  // namespace hil::controllers::s5::test

namespace hil::controllers::s5::test {
namespace {

using W726Setup = Wf725Fixture;

TEST_F(W726Setup, AxisBAndCInOneControllerBlockFormOneModule) {
  std::string text;
  for (const auto& [n, v] : base_md()) text += "MD " + std::to_string(n) + " = " + v + "\n";
  spec.parameters = write("a.txt", text);
  spec.options["axis_b"] = "b.txt";  // relative to the scenario
  spec.options["axis_c"] = write("c.txt", text).string();
  spec.options["db_c"] = "20";
  (void)write("b.txt", text);
  spec.programs = {write("p.wf", "%3 AC\nN1 A G18 X 5 F 600\nN2 C X 7\n")};
  ControllerRegistry r;
  register_wf725(r);
  auto c = r.create(spec);
  ASSERT_TRUE(c) << c.error().describe();
  auto& m = static_cast<Wf726ModuleController&>(**c);
  ASSERT_EQ(m.axis_specs().size(), 3U);
  EXPECT_EQ(m.axis_specs()[1].name, "B");
  EXPECT_EQ(m.module().size(), 3U);
  EXPECT_EQ(m.module_axis(2).interface_db().number, 20);
  EXPECT_EQ(m.module_axis(1).interface_db().number, 11);
  EXPECT_NE(m.module_axis(2).programs().find(3), nullptr) << "one program memory";
  // The DB axes of B and C in the image: the name and the S5 address are the same bit.
  const auto start_c = m.resolve_bit("start_C");
  ASSERT_TRUE(start_c);
  const auto addr = m.resolve_bit("DB20 D 1.0");
  ASSERT_TRUE(addr) << addr.error();
  EXPECT_EQ(*start_c, *addr);
  EXPECT_TRUE(m.resolve_bit("x7_e1"));
  EXPECT_TRUE(m.resolve_bit("limit_plus_B"));
  EXPECT_FALSE(m.resolve_bit("DB12 D 1.0"));
  ASSERT_TRUE(m.write_data_word(30, 0, 7));  // a user data block, shared by the axes
  EXPECT_EQ(*m.module_axis(2).read_data_word(30, 0), 7);
  // On two machine axes: the PLC's words reach each axis, its errors show on its machine axis.
  mocks::SimDriveConfig d;
  d.plant.kv_per_s = 200.0;
  d.plant.velocity_lag_s = 0.0;
  d.plant.velocity_feedforward = 1.0;
  std::vector<std::unique_ptr<motion::Axis>> axes;
  std::vector<motion::Axis*> ptrs;
  for (const auto& a : m.axis_specs()) {
    d.name = "sim:" + a.name;
    axes.push_back(std::make_unique<motion::Axis>(a.config, std::make_unique<mocks::SimDrive>(d)));
    ptrs.push_back(axes.back().get());
  }
  ASSERT_TRUE(m.bind_axes(ptrs));
  TimePoint t{};
  const auto cycles = [&](int n) {
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < 6; ++k) {
        t += milliseconds(1);
        for (auto& a : axes) a->update(CycleTime{t, milliseconds(1)});
      }
      (void)m.step(CycleTime{t, m.cycle_period()});
    }
  };
  for (const int db : {10, 11, 20}) {
    ASSERT_TRUE(m.write_data_word(db, db::dw_mode, 0x0100 | static_cast<unsigned>(db::Submode::set_actual)));
    ASSERT_TRUE(m.write_data_word(db, db::dw_enable, 1));
  }
  cycles(10);
  for (const int db : {10, 11, 20}) ASSERT_TRUE(m.write_data_word(db, db::dw_control, 1));
  cycles(3);
  for (const int db : {10, 11, 20}) ASSERT_TRUE(m.write_data_word(db, db::dw_control, 0));
  cycles(3);
  EXPECT_TRUE((*m.read_data_word(20, db::dw_status) >> db::bit_syn) & 1U) << "C synchronized through DB20";
  EXPECT_TRUE(m.io().get(*m.resolve_bit("drive_enable_C")));
  // C in automatic (not "0"): program 3 on A gives 69 on C and 6B on A, on their machine axes.
  ASSERT_TRUE(m.write_data_word(10, db::dw_mode, 0x0100 | static_cast<unsigned>(db::Submode::automatic)));
  ASSERT_TRUE(m.write_data_word(20, db::dw_mode, 0x0100 | static_cast<unsigned>(db::Submode::automatic)));
  ASSERT_TRUE(m.write_data_word(10, db::dw_program, 3));
  cycles(3);
  ASSERT_TRUE(m.write_data_word(10, db::dw_control, 1));
  cycles(3);
  EXPECT_EQ(*m.read_data_word(10, db::dw_error) & 0xFF, 0x6B);
  EXPECT_EQ(*m.read_data_word(20, db::dw_error) & 0xFF, 0x69);
  const auto shown = [&](int index, int code) {
    return std::ranges::any_of(m.errors().active(),
                               [&](const DeviceError& e) { return e.axis == index && e.code == code; });
  };
  EXPECT_TRUE(shown(0, 0x6B));
  EXPECT_TRUE(shown(2, 0x69));
  EXPECT_TRUE(m.io().get(*m.resolve_bit("error_A")));
  EXPECT_TRUE(m.io().get(*m.resolve_bit("device_error")));
  // 800C in DB10 clears 6B on A: gone from its machine axis too.
  ASSERT_TRUE(m.write_data_word(10, db::dw_control, 0));
  ASSERT_TRUE(m.write_data_word(10, db::dw_data_code, db::code::acknowledge));
  ASSERT_TRUE(m.write_data_word(10, db::dw_data_execute, 1));
  cycles(3);
  EXPECT_FALSE(shown(0, 0x6B));
  EXPECT_TRUE(shown(2, 0x69));
  // Two axes on one DB axis number are refused.
  spec.options["db_c"] = "11";
  auto bad = r.create(spec);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().describe().find("DB11"), std::string::npos) << bad.error().describe();
}

}  // namespace
}  // namespace hil::controllers::s5::test
