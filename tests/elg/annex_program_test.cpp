// SPDX-License-Identifier: MIT
// The manual's annex program (13.2, digest §11.1) run end to end on ideal axes: the NC program
// drives the PC interface, the PC drives the ELG, the ELG drives C. Checks the number of teeth
// cut, the index position kept across the ON/OFF cycles, and C within one increment of the
// linkage equation throughout.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hil/controllers/elg/gearbox.hpp"
#include "hil/controllers/elg/nc_interpreter.hpp"
#include "hil/controllers/elg/pc_interface.hpp"
#include "hil/core/text_file.hpp"

namespace elg = hil::controllers::elg;

namespace {

/// The manual's annex program (13.2) as shipped with the ELG example; tests run in the source tree.
std::string annex_program() {
  auto text = hil::read_text_file("examples/controllers/elg-annex.nc");
  EXPECT_TRUE(text) << text.error();
  return text.value_or("");
}

/// Ideal axes: X, Z move at the commanded speed exactly; B turns at the spindle speed; C goes
/// where the ELG says (following in one cycle, indexing at 10 deg/s). Units: mm, counts.
struct IdealMachine final : elg::NcMachine {
  static constexpr double ms_mm = 0.0005;  // Z/X measuring-system unit (0.5 um)
  static constexpr double rapid_mm_s = 100.0;
  double x = 0, z = 0, y = 0;
  double tx = 0, tz = 0, speed = 0;
  double rpm = 0;
  int dir = 0;
  double b = 0;  // counts
  elg::PcInterface* pc = nullptr;
  std::vector<int> m_log;

  void move(const elg::NcTargets& t, bool rapid, double feed) override {
    tx = t.x.value_or(tx);
    tz = t.z.value_or(tz);
    speed = rapid ? rapid_mm_s : feed;
  }
  bool in_position() const override { return x == tx && z == tz && !pc->read_in_disable(); }
  elg::NcTargets position() const override { return {x, y, z}; }
  void spindle(double r, int d) override {
    rpm = r;
    dir = d;
  }
  void m_function(int m) override {
    m_log.push_back(m);
    pc->on_m_function(m);
  }
  void advance(double dt) {
    auto approach = [&](double& p, double target) {
      const double step = speed * dt;
      p = std::abs(target - p) <= step ? target : p + (target > p ? step : -step);
    };
    approach(x, tx);
    approach(z, tz);
    b += dir * rpm / 60.0 * 4 * 180000 * dt;
  }
  std::int64_t z_counts() const { return std::llround(z / ms_mm); }
};

}  // namespace

TEST(ElgAnnexProgram, SinglePitchHelicalCycleOnIdealAxes) {
  auto program = elg::parse_nc_program(annex_program());
  ASSERT_TRUE(program) << program.error().what();
  elg::NcInterpreter nc(std::move(*program));
  elg::GearboxConfig config;  // N00 = N02 = 180 000, MS 0.5 um
  elg::Gearbox box(config);
  elg::PcInterface pc;
  IdealMachine machine;
  machine.pc = &pc;

  const double dt = 0.002;
  double t = 0;
  std::int64_t c = 0;
  int couplings = 0;
  bool was_coupled = false;
  std::int64_t c_at_couple = 0, z_at_couple = 0;
  std::vector<std::int64_t> index_positions;
  double worst = 0;
  bool params_sent = false;
  for (int cycle = 0; cycle < 2'000'000 && nc.state() == elg::NcState::running; ++cycle) {
    nc.step(t, machine);
    // The R-parameter transfer NC -> PC -> ELG (5.1): R20/R21 -> Z0/Z2, R12/R13 -> ud_z/ud_y.
    if (!params_sent && nc.blocks_executed() >= 2) {
      elg::GearInput in{static_cast<int>(nc.r(20)), static_cast<int>(nc.r(21)), elg::Decimal5::from_double(nc.r(12)),
                        elg::Decimal5::from_double(nc.r(13))};
      ASSERT_TRUE(box.set_input(in));
      params_sent = true;
    }
    machine.advance(dt);
    elg::AxisFeedback axes{std::llround(machine.b), machine.z_counts(), 0, c, 0, true};
    const std::size_t alarms_before = box.alarms().size();
    const auto& st = box.step(pc.signals(), axes);
    if (st.c_mode == elg::CMode::follow) {
      c = st.c_set;
    } else if (st.c_mode == elg::CMode::position) {
      const std::int64_t step = 40;  // 10 deg/s at 2000 counts/deg and 2 ms
      c = std::abs(st.c_set - c) <= step ? st.c_set : c + (st.c_set > c ? step : -step);
    }
    pc.after_step(st, box.alarms().size() > alarms_before);
    if (st.coupled && !was_coupled) {
      ++couplings;
      c_at_couple = c;
      z_at_couple = axes.z;
    }
    if (!st.coupled && was_coupled) index_positions.push_back(c);
    was_coupled = st.coupled;
    if (st.coupled) {
      // The equation in degrees (Z0 = 0, EZT: the cutter term is dropped): C counts = 2000/deg.
      const double ideal = static_cast<double>(c_at_couple) +
                           static_cast<double>(axes.z - z_at_couple) * 0.0005 * 8.18511 / 10.0 * 2000.0;
      worst = std::max(worst, std::abs(static_cast<double>(c) - ideal));
    }
    t += dt;
  }
  ASSERT_EQ(nc.state(), elg::NcState::ended) << nc.error();
  EXPECT_TRUE(box.alarms().empty()) << static_cast<int>(box.alarms().front());
  EXPECT_EQ(couplings, 10);   // ten gaps cut
  EXPECT_EQ(nc.r(14), 10.0);  // the tooth counter R14
  EXPECT_LE(worst, 1.0);      // C within one increment of the equation
  ASSERT_EQ(index_positions.size(), 10u);
  for (std::size_t i = 0; i < index_positions.size(); ++i) {
    // After each cut, before its index: C is back at the gap's start, i pitches from the first.
    EXPECT_EQ(index_positions[i], static_cast<std::int64_t>(i) * 72000) << "gap " << i;
  }
  EXPECT_EQ(c, 720000);              // ten pitches: the start position mod 360 deg
  EXPECT_EQ(box.status().tooth, 0);  // M55 cancelled single pitch
  EXPECT_EQ(machine.m_log, (std::vector<int>{52, 54, 50, 51, 56, 50, 51, 56, 50, 51, 56, 50, 51, 56, 50, 51, 56,
                                             50, 51, 56, 50, 51, 56, 50, 51, 56, 50, 51, 56, 50, 51, 56, 55}));
}

TEST(ElgNcProgram, ParsesTheAnnexProgram) {
  auto p = elg::parse_nc_program(annex_program());
  ASSERT_TRUE(p) << p.error().what();
  EXPECT_EQ(p->number, 100);
  EXPECT_EQ(p->comment, "Single pitch with helical teeth");
  ASSERT_EQ(p->blocks.size(), 16u);
  EXPECT_EQ(p->blocks[1].number, -1);  // the continuation line has no N word
  const auto& n55 = p->blocks[static_cast<std::size_t>(p->find(55))];
  ASSERT_EQ(n55.r.size(), 1u);
  EXPECT_EQ(n55.r[0].op, elg::RAssign::Op::add);
  EXPECT_EQ(n55.r[0].from_r, 15);
  const auto& n60 = p->blocks[static_cast<std::size_t>(p->find(60))];
  ASSERT_TRUE(n60.jump);
  EXPECT_EQ(n60.jump->condition, 3);
  EXPECT_EQ(n60.jump->target, 20);
  EXPECT_EQ(n60.jump->ra, 21);
  EXPECT_EQ(n60.jump->rb, 14);
  EXPECT_DOUBLE_EQ(*p->blocks[static_cast<std::size_t>(p->find(10))].f, 0.5);
}

TEST(ElgNcProgram, BadProgramsNameLineAndBlock) {
  struct Case {
    const char* text;
    int line;
    const char* fragment;
  };
  const Case cases[] = {
      {"N10 G0\n", 1, "%nnn header"},
      {"%1\nN10 Q5\n", 2, "unknown address 'Q'"},
      {"%1\nN10 G0\nN10 G1\n", 3, "used twice"},
      {"%1\nN10 @03 - 20 R1 R2\n", 2, "does not exist"},
      {"%1\nN10 R5\n", 2, "value or an R parameter"},
      {"%1\nN10 X1 X2\n", 2, "twice"},
      {"%1\nN10 (open comment\n", 2, "not closed"},
      {"%1\nN10 G0 N20\n", 2, "must come first"},
      {"%1\nN10 @07 - 10\n", 2, "jump code"},
      {"%1\nN10 G\x01\n", 2, "G must be followed"},
  };
  for (const auto& c : cases) {
    auto p = elg::parse_nc_program(c.text);
    ASSERT_FALSE(p) << c.text;
    EXPECT_EQ(p.error().line, c.line) << c.text;
    EXPECT_NE(p.error().message.find(c.fragment), std::string::npos) << p.error().what();
  }
}

TEST(ElgNcProgram, IncrementalAndFeedPerMinute) {
  auto p = elg::parse_nc_program("%2\nN1 G91 G94 G1 F600 Z5\nN2 Z5\nN3 M30\n");
  ASSERT_TRUE(p);
  elg::NcInterpreter nc(std::move(*p));
  elg::PcInterface pc;
  IdealMachine m;
  m.pc = &pc;
  double t = 0;
  while (nc.step(t, m) == elg::NcState::running && t < 10) {
    m.advance(0.001);
    t += 0.001;
  }
  EXPECT_EQ(nc.state(), elg::NcState::ended);
  EXPECT_DOUBLE_EQ(m.z, 10.0);
  EXPECT_DOUBLE_EQ(m.speed, 10.0);  // 600 mm/min
}

TEST(ElgNcProgram, FeedMoveWithoutFeedIsAnError) {
  auto p = elg::parse_nc_program("%3\nN1 G1 Z5\n");
  ASSERT_TRUE(p);
  elg::NcInterpreter nc(std::move(*p));
  elg::PcInterface pc;
  IdealMachine m;
  m.pc = &pc;
  EXPECT_EQ(nc.step(0, m), elg::NcState::error);
  EXPECT_NE(nc.error().find("N1"), std::string::npos);
}
