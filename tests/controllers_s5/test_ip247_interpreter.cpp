// SPDX-License-Identifier: MIT
// IP247 program interpreter on an ideal axis (every motion completes at once): M-output sequence,
// M00 halt points, loops, subprograms, offsets, rotary direction rules, G10 rules and the run-time
// errors with the module's numbers (digest ip247.md §3.4-3.10, §4.9).
#include <gtest/gtest.h>

#include <map>

#include "hil/controllers/s5/ip247_interpreter.hpp"

using namespace hil::controllers::s5;
using hil::stepdir::Ip247Error;
using Kind = Ip247Action::Kind;

namespace {

struct Bench {
  std::map<int, Ip247Program> programs;
  Ip247MachineData md;
  Ip247Offsets off;
  std::int64_t p = 0;  ///< internal position
  Ip247Interpreter in{[this](int n) -> const Ip247Program* {
    auto it = programs.find(n);
    return it == programs.end() ? nullptr : &it->second;
  }};
  std::vector<Ip247Action> actions;
  int halts = 0;

  Bench() {
    md.sw_start = -1'000'000;
    md.sw_end = 1'000'000;
    md.fmax_hz = 10'000;  // 10 µm/pulse -> vmax 6000 mm/min
  }
  void add(const char* text) {
    auto prog = parse_ip247_program(text);
    ASSERT_TRUE(prog) << prog.error().message;
    programs[prog->number] = *prog;
  }
  std::int64_t x() const { return p + off.zero() + off.tool(); }
  /// Runs to the end; returns the last action (end or fault).
  Ip247Action run(int number, bool single_block = false) {
    EXPECT_EQ(in.start(number, md, p, single_block), Ip247Error::none);
    for (int guard = 0; guard < 100000; ++guard) {
      Ip247Action a = in.next(off);
      if (a.kind == Kind::pending) continue;
      actions.push_back(a);
      if (a.halt_before) ++halts;
      if (a.kind == Kind::motion) p = a.target;
      if (a.kind == Kind::end || a.kind == Kind::fault) return a;
    }
    ADD_FAILURE() << "program did not end";
    return {};
  }
};

}  // namespace

TEST(Ip247Interpreter, MOutputSequenceOfTheManual) {
  // §2.6.9 / vectors ip247.md 9: M255, M255, M255, M10, M10, M10, -, M20, M30, M30, M60.
  Bench b;
  b.md.sw_start = -5'000'000;
  b.md.sw_end = 5'000'000;
  b.add(
      "% 5\nN05 G91\nN10 G74\nN15 G24 F3\nN20 X1000 F2000 M10\nN30 G57\nN35 X-500 F2000\nN45 G20\nN50 G74 M20\n"
      "N60 X500 F100 M30\nN65 G26\nN70 X1000 F2000 M60\nN75 M02\n");
  b.in.enable_trace(true);
  auto end = b.run(5);
  ASSERT_EQ(end.kind, Kind::end);
  std::map<int, int> first;  // N -> M output after its first execution
  for (const auto& t : b.in.trace()) first.emplace(t.block, t.m_output);
  const std::vector<std::pair<int, int>> expect{{5, 255}, {10, 255}, {15, 255}, {20, 10}, {30, 10}, {35, 10},
                                                {45, 10}, {50, 20},  {60, 30},  {65, 30}, {70, 60}};
  for (auto [n, m] : expect) EXPECT_EQ(first[n], m) << "N" << n;
  EXPECT_EQ(end.m_output, 2);  // M02 after the end
}

TEST(Ip247Interpreter, ZeroOffsetProgramGivesMinus130ThenMinus10) {
  // §2.6.6.7 / vectors ip247.md 11. BA13 10 mm forward: zero_ba = -10 000; BA6 0 mm: p = 10 000.
  Bench b;
  b.md.zero_offsets = {40'000, 80'000, 120'000, 0};
  b.add(
      "%1 Hauptprogramm\nN1 L9\nN2 X40.000 F500\nN3 G54\nN4 L9\nN5 X40.000 F500\nN6 G55\nN7 L9\nN8 X40.000 F500\n"
      "N9 G56\nN10 G74\nN11 M02\n");
  b.add("L9 Unterprogramm\nN1 X0 F100 M10\nN2 G04 F50\nN3 X10 F100\nN4 G04 F50\nN5 X20 F100\nN6 G04 F50\nN7 M02\n");
  b.off.zero_ba = -10'000;
  b.p = 10'000;
  ASSERT_EQ(b.x(), 0);
  std::vector<std::int64_t> drilled;
  EXPECT_EQ(b.in.start(1, b.md, b.p, false), Ip247Error::none);
  std::int64_t at_g74 = 0;
  for (;;) {
    auto a = b.in.next(b.off);
    if (a.kind == Kind::motion) {
      b.p = a.target;
      if (a.reference) at_g74 = b.x();
    }
    if (a.kind == Kind::dwell) drilled.push_back(b.x());
    if (a.kind == Kind::end || a.kind == Kind::fault) {
      ASSERT_EQ(a.kind, Kind::end);
      break;
    }
  }
  // holes at 0/10/20 mm in every frame
  EXPECT_EQ(drilled, (std::vector<std::int64_t>{0, 10'000, 20'000, 0, 10'000, 20'000, 0, 10'000, 20'000}));
  EXPECT_EQ(at_g74, -130'000);
  EXPECT_EQ(b.x(), -10'000);  // program offsets cleared at the end, the BA13 shift remains
  EXPECT_EQ(b.p, 0);
}

TEST(Ip247Interpreter, M00TakeoverCounts) {
  // §2.6.9: from X100 to X500 three takeovers; §4.3.1 example also three.
  Bench b;
  b.add("%1\nN10 G10 X100 F500 M00\nN20 M00\nN30 G56 M00\nN40 X500 F1000\nN50 M02\n");
  b.add("%2\nN10 X100 F1000 M00\nN15 M00\nN20 G56 M00\nN25 G43 X200 F100 M02\n");
  b.add("%3\nN10 X100 F1000 M00\nN20 M02\n");
  b.add("%4\nN10 X100 F1000 M00\nN20 G04 F10\nN30 M02\n");
  b.add("%5\nN10 X100 F1000\nN20 M00\nN30 G57 M00\nN40 M02\n");
  EXPECT_EQ(b.run(1).kind, Kind::end);
  EXPECT_EQ(b.halts, 3);
  EXPECT_FALSE(b.actions[0].flying);  // M00 has priority over G10
  b.halts = 0;
  EXPECT_EQ(b.run(2).kind, Kind::end);
  EXPECT_EQ(b.halts, 3);
  b.halts = 0;
  EXPECT_EQ(b.run(3).kind, Kind::end);
  EXPECT_EQ(b.halts, 0);  // M00 followed only by M02: no effect
  b.halts = 0;
  EXPECT_EQ(b.run(4, true).kind, Kind::end);
  EXPECT_EQ(b.halts, 2);  // BA9: one halt before each of the two actions; M00 adds none
  b.halts = 0;
  EXPECT_EQ(b.run(5, true).kind, Kind::end);
  EXPECT_EQ(b.halts, 3);  // BA9: X100, and each standalone M00 is a zero-length motion
}

TEST(Ip247Interpreter, LoopsAndSubprograms) {
  Bench b;
  b.add("%9\nN10 G74 M10\nN20 G24 F5\nN30 L36\nN40 X50 F2000\nN50 G20\nN60 M02\n");
  b.add("L36\nN1 G91\nN2 X1 F100\nN3 M02\n");
  EXPECT_EQ(b.run(9).kind, Kind::end);
  int l36 = 0;
  for (const auto& a : b.actions) l36 += a.program == 36 ? 1 : 0;
  EXPECT_EQ(l36, 5);  // F5 = 5 passes (docs/ip247.md)
  Bench r;
  r.in = Ip247Interpreter(
      [&r](int n) -> const Ip247Program* {
        auto it = r.programs.find(n);
        return it == r.programs.end() ? nullptr : &it->second;
      },
      {.loop_count_is_passes = false});
  r.add("%9\nN20 G24 F5\nN40 X50 F2000\nN50 G20\nN60 M02\n");
  r.run(9);
  EXPECT_EQ(r.actions.size(), 7u);  // 6 passes + end
}

TEST(Ip247Interpreter, RunTimeErrors) {
  const struct {
    const char* main;
    const char* sub;
    Ip247Error error;
    int block;
  } cases[] = {
      {"%1\nN10 L7\nN20 M02\n", nullptr, Ip247Error::db_not_present, 10},
      {"%1\nN10 L2\nN20 M02\n", "L2\nN1 G24 F0\nN2 X1 F10\nN3 G20\nN4 M02\n", Ip247Error::endless_loop_not_outer, 1},
      {"%1\nN10 G24 F0\nN20 G91\nN30 G20\nN40 M02\n", nullptr, Ip247Error::endless_loop_not_outer, 30},
      {"%1\nN10 L1\nN20 M02\n", nullptr, Ip247Error::nesting_too_deep, 10},
      {"%1\nN10 X100 F9000\nN20 M02\n", nullptr, Ip247Error::speed_too_high, 10},
      {"%1\nN10 X2000 F100\nN20 M02\n", nullptr, Ip247Error::traversing_range_exceeded, 10},
      {"%1\nN10 G10 X100 F100\nN20 G04 F10\nN30 M02\n", nullptr, Ip247Error::flying_change_failed, 20},
      {"%1\nN10 G10 X100 F100\nN20 X50 F100\nN30 M02\n", nullptr, Ip247Error::flying_change_failed, 20},
      {"%1\nN10 G10 X100 F100\nN15 G54\nN20 X500 F100\nN30 M02\n", nullptr, Ip247Error::flying_change_failed, 15},
      {"%1\nN10 G10 X100 F100\nN30 M02\n", nullptr, Ip247Error::flying_change_failed, 30},
  };
  for (const auto& c : cases) {
    Bench b;
    b.add(c.main);
    if (c.sub) b.add(c.sub);
    auto a = b.run(1);
    ASSERT_EQ(a.kind, Kind::fault) << c.main;
    EXPECT_EQ(a.error, c.error) << c.main;
    EXPECT_EQ(a.block, c.block) << c.main;
  }
  Bench deg;
  deg.md.unit = Ip247Unit::degree;
  deg.add("%1\nN10 G70\nN20 M02\n");
  EXPECT_EQ(deg.run(1).error, Ip247Error::g_not_allowed);
}

TEST(Ip247Interpreter, RotaryDirectionRules) {
  // §2.6.6.5 / digest §3.8, rotary 0..360 degrees, start at 0.
  Bench b;
  b.md.unit = Ip247Unit::degree;
  b.md.rotary = true;
  b.md.sw_start = 0;
  b.md.sw_end = 360'000;
  b.md.fmax_hz = 100'000;
  b.add(
      "%1\nN10 G74 M10\nN20 G27\nN30 X180 F1000 M30\nN40 G25 X0 F500\nN50 G26\nN60 X0 F1000 M60\nN70 G25 X360 F500\n"
      "N80 M02\n");
  b.p = 90'000;
  ASSERT_EQ(b.run(1).kind, Kind::end);
  std::vector<std::int64_t> targets;
  for (const auto& a : b.actions) {
    if (a.kind == Kind::motion) targets.push_back(a.target);
  }
  // G74: shortest 90 -> 0; G27 backward to 180 (-180); G25 to 0: tie goes forward (+180 -> 360);
  // G26 X0 at 0: one full revolution forward; G25 X360 at 0: no motion.
  EXPECT_EQ(targets, (std::vector<std::int64_t>{0, -180'000, 0, 360'000, 360'000}));
  EXPECT_EQ(ip247_rotary_delta(0, 0, 360'000, Ip247Rotary::backward), -360'000);
  EXPECT_EQ(ip247_rotary_delta(10'000, 350'000, 360'000, Ip247Rotary::shortest), -20'000);
  Bench f;  // rotary G10 chain with shortest paths in different directions -> 47
  f.md = b.md;
  f.add("%1\nN10 G10 X90 F100\nN20 X10 F100\nN30 M02\n");
  auto a = f.run(1);
  EXPECT_EQ(a.error, Ip247Error::no_direction_change_in_flying_change);
}

TEST(Ip247Interpreter, ToolOffsetsAndUnits) {
  // Bild 2/19: BA15 100 forward, program G44 twice with MD tool 10 -> 80, kept after the end.
  Bench b;
  b.md.tool_offset = 10'000;
  b.off.tool_ba = 100'000;
  b.add("%1\nN10 G44\nN20 G44\nN30 M02\n");
  b.run(1);
  EXPECT_EQ(b.off.tool(), 80'000);
  // G70 on a mm axis: X in 0.1 inch, F in 0.1 inch/min.
  Bench u;
  u.add("%1\nN10 G70 X100 F1000\nN20 G71 X100 F1000\nN30 M02\n");
  u.run(1);
  EXPECT_EQ(u.actions[0].target, 254'000);
  EXPECT_DOUBLE_EQ(u.actions[0].speed, 2540.0);
  EXPECT_EQ(u.actions[1].target, 100'000);
  // Absolute targets aim at the tool tip: a positive tool offset makes the module aim lower.
  Bench t;
  t.off.tool_ba = 20'000;
  t.add("%1\nN10 X100 F1000\nN20 M02\n");
  t.run(1);
  EXPECT_EQ(t.actions[0].target, 80'000);
}
