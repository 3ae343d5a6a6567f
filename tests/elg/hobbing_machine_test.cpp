// SPDX-License-Identifier: MIT
// The annex program (13.2) on the motion core: B, C, X, Z are motion::Axis objects on simulated
// drives (hil::mocks::SimDrive) stepped on virtual time; the HobbingMachine runs NC, PC and ELG.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hil/controllers/elg/hobbing_machine.hpp"
#include "hil/core/text_file.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace elg = hil::controllers::elg;
namespace motion = hil::motion;
using std::chrono::milliseconds;

namespace {

/// The manual's annex program (13.2) as shipped with the ELG example; tests run in the source tree.
std::string annex_program() {
  auto text = hil::read_text_file("examples/controllers/elg-annex.nc");
  EXPECT_TRUE(text) << text.error();
  return text.value_or("");
}

std::unique_ptr<motion::Axis> make_axis(const std::string& name, motion::Ratio ratio, double v, double a,
                                        double window) {
  motion::AxisConfig c;
  c.name = name;
  c.inc_per_unit = ratio;
  c.limits = {v, a, a * 20};
  c.quick_stop_deceleration = a * 2;
  c.jog_velocity = v / 10;
  c.following_error.static_window = window;
  c.standstill_window = window;
  c.in_position_window = window / 2;
  c.in_position_timeout = milliseconds(2000);
  EXPECT_TRUE(motion::validate(c)) << motion::validate(c).error();
  hil::mocks::SimDriveConfig d;
  d.name = "sim:" + name;
  d.plant.kv_per_s = 200.0;
  d.plant.velocity_lag_s = 0.0005;
  d.plant.velocity_feedforward = 1.0;
  d.plant.max_velocity_inc_per_s = 1e9;
  return std::make_unique<motion::Axis>(c, std::make_unique<hil::mocks::SimDrive>(d));
}

}  // namespace

TEST(ElgHobbingMachine, AnnexProgramOnSimulatedDrives) {
  auto program = elg::parse_nc_program(annex_program());
  ASSERT_TRUE(program) << program.error().what();
  elg::HobbingConfig config;  // MD 396* = 180 000, MS 0.5 um
  auto b = make_axis("B", elg::rotary_counts_per_degree(180000), 3600.0, 36000.0, 5.0);
  auto c = make_axis("C", elg::rotary_counts_per_degree(180000), 360.0, 3600.0, 1.0);
  auto x = make_axis("X", elg::linear_counts_per_mm(500), 100.0, 1000.0, 1.0);
  auto z = make_axis("Z", elg::linear_counts_per_mm(500), 100.0, 1000.0, 1.0);
  elg::HobbingMachine machine(std::move(*program), config, {b.get(), c.get(), z.get(), x.get(), nullptr});

  hil::TimePoint now{};
  const auto period = milliseconds(2);
  std::vector<motion::Axis*> axes{b.get(), c.get(), x.get(), z.get()};
  auto cycle = [&] {
    now += period;
    for (auto* axis : axes) axis->update(hil::CycleTime{now, period});
    machine.step(hil::CycleTime{now, period});
  };
  cycle();
  for (auto* axis : axes) ASSERT_FALSE(axis->enable());
  for (int i = 0; i < 20; ++i) cycle();
  for (auto* axis : axes) ASSERT_EQ(axis->status().state, motion::AxisState::standstill) << axis->config().name;
  machine.start();
  std::vector<std::int64_t> index_positions, off_positions;
  bool was_coupled = false;
  double worst_c_lag = 0;
  for (int i = 0; i < 400000 && machine.nc().state() == elg::NcState::running; ++i) {
    cycle();
    ASSERT_TRUE(machine.error().empty()) << machine.error();
    for (auto* axis : axes) ASSERT_NE(axis->status().state, motion::AxisState::error) << axis->config().name;
    const bool coupled = machine.gearbox().status().coupled;
    if (!was_coupled && coupled) index_positions.push_back(machine.c_set());  // the gap's start
    if (was_coupled && !coupled) off_positions.push_back(machine.c_set());
    if (coupled) worst_c_lag = std::max(worst_c_lag, std::abs(c->status().following_error));
    was_coupled = coupled;
  }
  for (int i = 0; i < 500; ++i) cycle();  // C settles on the last index
  ASSERT_EQ(machine.nc().state(), elg::NcState::ended) << machine.nc().error();
  EXPECT_TRUE(machine.gearbox().alarms().empty());
  EXPECT_EQ(machine.couplings(), 10);
  EXPECT_LE(machine.worst_linkage_error_counts(), 1.0);  // C set value within one increment
  ASSERT_EQ(index_positions.size(), 10u);
  ASSERT_EQ(off_positions.size(), 10u);
  for (std::size_t i = 0; i < 10; ++i) {
    // Each gap starts exactly on the pitch grid (the index position is kept across ON/OFF), and
    // the coupling hands C back within one count of it (Z settles to within a count of Z10).
    EXPECT_EQ(index_positions[i], static_cast<std::int64_t>(i) * 72000) << "gap " << i;
    EXPECT_LE(std::llabs(off_positions[i] - static_cast<std::int64_t>(i) * 72000), 1) << "gap " << i;
  }
  EXPECT_EQ(c->status().command_inc, 720000);
  EXPECT_LE(std::llabs(c->status().position_inc - 720000), 2);
  EXPECT_LT(worst_c_lag, 1.0);  // deg: the table follows the coupling inside its window
  EXPECT_NEAR(z->status().position, 10.0, 0.001);
}

TEST(ElgHobbingMachine, ReferenceThenIncWithSsfkOnSimulatedDrives) {
  // C is referenced (REF on the cam: the zero mark every 2000 counts, MD 240* = 0), then INC steps of
  // 1000 increments (2000 counts) land on the target plus the SSFK compensation: every point "+",
  // one point per 1000 counts, MD 328* = 10 counts.
  auto program = elg::parse_nc_program("%1\nN5 M30\n");
  ASSERT_TRUE(program);
  elg::HobbingConfig config;
  config.gearbox.setup.zero_mark_counts = 2000;
  config.ssfk.active = true;
  config.ssfk.distance = 1000;
  config.ssfk.step = 10;
  config.ssfk.flags = elg::SsfkData::filled(0xAA);
  auto b = make_axis("B", elg::rotary_counts_per_degree(180000), 3600.0, 36000.0, 5.0);
  auto c = make_axis("C", elg::rotary_counts_per_degree(180000), 360.0, 3600.0, 1.0);
  auto x = make_axis("X", elg::linear_counts_per_mm(500), 100.0, 1000.0, 1.0);
  auto z = make_axis("Z", elg::linear_counts_per_mm(500), 100.0, 1000.0, 1.0);
  elg::HobbingMachine machine(std::move(*program), config, {b.get(), c.get(), z.get(), x.get(), nullptr});
  hil::TimePoint now{};
  const auto period = milliseconds(2);
  std::vector<motion::Axis*> axes{b.get(), c.get(), x.get(), z.get()};
  auto cycle = [&] {
    now += period;
    for (auto* axis : axes) axis->update(hil::CycleTime{now, period});
    machine.step(hil::CycleTime{now, period});
  };
  cycle();
  for (auto* axis : axes) ASSERT_FALSE(axis->enable());
  for (int i = 0; i < 20; ++i) cycle();
  auto& panel = machine.pc_signals().panel;
  panel.override_position = 14;  // 100 %
  panel.mode = elg::PanelMode::ref;
  panel.ref_cam = true;
  panel.key_plus = true;
  cycle();
  panel.key_plus = false;
  for (int i = 0; i < 1000 && !machine.gearbox().status().referenced; ++i) cycle();
  ASSERT_TRUE(machine.gearbox().status().referenced);
  EXPECT_EQ(machine.gearbox().status().c_offset, -2000);  // the mark at 2000 counts is MD 240* = 0
  for (int i = 0; i < 200; ++i) cycle();
  ASSERT_FALSE(c->status().busy);
  panel.mode = elg::PanelMode::inc;
  panel.inc_factor = 1000;
  for (int step = 1; step <= 3; ++step) {
    const std::int64_t before = machine.c_set();
    panel.key_plus = true;
    cycle();
    panel.key_plus = false;
    for (int i = 0; i < 1000 && machine.gearbox().setup().moving(); ++i) cycle();
    ASSERT_FALSE(machine.gearbox().setup().moving()) << "step " << step;
    const std::int64_t target = machine.c_set();
    EXPECT_EQ(target, before + 2000);
    // ELG position from the reference point, one "+" point per 1000 counts passed.
    const std::int64_t expected_comp = (target - 2000) / 1000 * 10;
    EXPECT_EQ(machine.ssfk_compensation(), expected_comp) << "step " << step;
    EXPECT_EQ(c->status().command_inc, target + expected_comp) << "step " << step;
  }
  EXPECT_TRUE(machine.gearbox().alarms().empty());
}
