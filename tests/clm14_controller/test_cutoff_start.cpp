// SPDX-License-Identifier: MIT
// CLM1.4 flying cutoff A138 "Functions 2" (manual §7.12, digest §5.11: "task 1 starts
// immediately on Manual -> Auto at 'previous length instruction - 1', or at 0000 per A138 / !CL0
// / keys"): the start line of task 1, the start-at-0000 input and option, !CL0, and the raster
// detection by level or edge.
#include <gtest/gtest.h>

#include <cmath>

#include "rig.hpp"

namespace hil::controllers::clm14 {
namespace {

using namespace std::chrono_literals;
using testing::bit;
using testing::Rig;

motion::Limits material_limits(double v) {
  motion::Limits l;
  l.velocity = std::abs(v);
  l.acceleration = 400.0;
  return l;
}

#define CUTOFF_PARAMETERS                                                    \
  {"A100", "1 5 0 0 0"}, {"C000", "01250 0000"}, {"C001", "5 0 00 0 0 0"}, { \
    "C002", "0020.00000"                                                     \
  }

/// Line 0000 clears V600; the length instruction is at 0003, the line before it sets V601.
const std::vector<std::pair<int, std::string>> program{{0, "SET V600 = +00000000.000000"},
                                                       {1, "NOP"},
                                                       {2, "SET V601 = +00000001.000000"},
                                                       {3, "LML 1 000100.000"},
                                                       {4, "WAI 00.100"},
                                                       {5, "EOS"},
                                                       {6, "JMP 0002"}};

/// Runs the first entry into Automatic until the first part's length instruction waits, leaves
/// Automatic with the carriage home, marks V600 / V601 and enters Automatic again. Returns the
/// first line task 1 ran: 0 when V600 was cleared, 2 when only V601 was set again.
struct Reentry {
  explicit Reentry(Rig::Overrides o) : r(o) {
    material = &r.add_master_encoder();
    r.program(program);
    r.run_for(20ms);
    r.enter_auto();
    EXPECT_FALSE(material->move_velocity(40.0, material_limits(40.0)));
    EXPECT_TRUE(r.run_until([&] { return r.clm.cuts() == 1; }, 10s));
    // the carriage returns; the next LML (line 0003 again) waits for its part
    EXPECT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 3 && std::abs(r.pos(1)) < 0.005; }, 10s));
    EXPECT_FALSE(material->stop());
    r.run_for(500ms);
    r.set(sys::automatic, false);
    r.cycle();
    r.cycle();
    EXPECT_EQ(r.clm.mode(), Mode::manual);
  }
  /// Enter Automatic again; the first line task 1 ran (0 or 2), -1 if neither.
  int enter() {
    EXPECT_TRUE(r.clm.set_variable(600, 5 * micro_one));
    EXPECT_TRUE(r.clm.set_variable(601, 0));
    r.set(sys::automatic, true);
    r.run_for(20ms);
    EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
    if (r.clm.variable(600) == 0) return 0;
    if (r.clm.variable(600) == 5 * micro_one && r.clm.variable(601) == micro_one) return 2;
    return -1;
  }
  void manual() {
    r.set(sys::automatic, false);
    r.cycle();
    r.cycle();
  }
  Rig r;
  motion::Axis* material = nullptr;
};

TEST(ClmCutoffStart, ManualToAutomaticStartsBeforeTheLastLengthInstruction) {
  Reentry e({CUTOFF_PARAMETERS});
  EXPECT_EQ(e.enter(), 2);
}

TEST(ClmCutoffStart, A138AlwaysBeginsAt0000) {
  Reentry e({CUTOFF_PARAMETERS, {"A138", "00.00.0 0 1"}});
  EXPECT_EQ(e.enter(), 0);
}

TEST(ClmCutoffStart, A138InputPulseInManualSelects0000Once) {
  Reentry e({CUTOFF_PARAMETERS, {"A138", "I1.00.2 0 0"}});
  e.r.pulse(bit("I1.00.2"));
  EXPECT_EQ(e.enter(), 0);
  // the request is used up: the next entry starts before the length instruction again (the
  // program ran to its LML at 0003 once more)
  ASSERT_TRUE(e.r.run_until([&] { return e.r.clm.task(1).pc == 3; }, 2s));
  e.manual();
  EXPECT_EQ(e.enter(), 2);
}

TEST(ClmCutoffStart, A138InputSetAtTheEntrySelects0000) {
  Reentry e({CUTOFF_PARAMETERS, {"A138", "I1.00.2 0 0"}});
  e.r.set(bit("I1.00.2"), true);
  EXPECT_EQ(e.enter(), 0);
}

TEST(ClmCutoffStart, Cl0InManualSelects0000) {
  Reentry e({CUTOFF_PARAMETERS});
  EXPECT_TRUE(e.r.clm.command_start_0000());
  EXPECT_EQ(e.enter(), 0);
  EXPECT_FALSE(e.r.clm.command_start_0000()) << "!CL0 in Automatic is refused";
}

TEST(ClmCutoffStart, ParameterModeForgetsTheLengthInstruction) {
  Reentry e({CUTOFF_PARAMETERS});
  e.r.set(sys::parameter_mode, true);
  e.r.cycle();
  e.r.set(sys::parameter_mode, false);
  e.r.run_for(20ms);
  EXPECT_EQ(e.enter(), 0);
}

/// LMK with a Raster 1 mark at material 50 that stays high: the first two cut points.
std::pair<double, double> held_raster_cuts(const std::string& a138) {
  Rig r({CUTOFF_PARAMETERS, {"A138", a138}});
  auto& material = r.add_master_encoder();
  r.program({{0, "NOP"}, {1, "LMK 1 000200.000 000030.000"}, {2, "WAI 00.100"}, {3, "EOS"}, {4, "JMP 0001"}});
  r.run_for(20ms);
  r.enter_auto();
  EXPECT_FALSE(material.move_velocity(40.0, material_limits(40.0)));
  std::pair<double, double> cuts{};
  while (r.clm.cuts() < 2 && r.now < TimePoint{} + 30s) {
    r.set(sys::raster1, r.clm.master_position() >= 50.0);
    r.cycle();
    if (r.clm.cuts() == 1 && cuts.first == 0.0) cuts.first = r.clm.last_cut_point();
  }
  cuts.second = r.clm.last_cut_point();
  return cuts;
}

TEST(ClmCutoffStart, A138RasterByLevelOrByEdge) {
  // edge (1): the mark's rising edge (50 + one or two cycles of sampling) + 30; the mark stays
  // high, no new edge: the second part is the programmed 200 IU
  const auto edge = held_raster_cuts("00.00.0 1 0");
  EXPECT_NEAR(edge.first, 80.0 + 0.12, 0.045);
  EXPECT_NEAR(edge.second - edge.first, 200.0, 0.0045);
  // level (0): the same first cut; after the de-sync the input is still high: that is the next
  // mark, so the second cut falls 30 IU after the de-sync, far before 200 IU
  const auto level = held_raster_cuts("00.00.0 0 0");
  EXPECT_NEAR(level.first, edge.first, 0.0045);
  EXPECT_LT(level.second - level.first, 60.0);
  EXPECT_GT(level.second - level.first, 30.0);
}

}  // namespace
}  // namespace hil::controllers::clm14
