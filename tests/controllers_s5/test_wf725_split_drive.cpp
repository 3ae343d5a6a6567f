// SPDX-License-Identifier: MIT
// WF 726 split drive (gantry) MD 27 / MD 29 (docs/wf725.md "Split drive"): two controllers of one
// module (axes A and B) on two simulated drives, stepped on virtual time in the order of
// `hilbridge emulate wf725` (A's axis and cycle, then B's split-drive set-point, axis and cycle).
// The manual's conditions: seeds/wf725-726.md §4.3 MD 27/29/38/39, errors 25, 69, 6A, 6B, 6D.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "wf725_fixture.hpp"

namespace hil::controllers::s5::test {
namespace {

/// One axis of the module: its controller, simulated drive and the PLC's view of its DB axis.
struct Side {
  std::unique_ptr<Wf725Controller> ctl;
  std::unique_ptr<motion::Axis> axis;
  mocks::SimDrive* drive = nullptr;
  int every = 6;

  std::uint16_t word(std::uint16_t w) const { return ctl->read_db_word(w); }
  bool bit(std::uint16_t w, int b) const { return ((word(w) >> b) & 1) != 0; }
  void set_bit(std::uint16_t w, int b, bool on) {
    const auto v = word(w);
    ctl->write_db_word(w, static_cast<std::uint16_t>(on ? (v | (1U << b)) : (v & ~(1U << b))));
  }
  void write_dd(std::uint16_t w, std::int32_t v) {
    ctl->write_db_word(w, static_cast<std::uint16_t>(static_cast<std::uint32_t>(v) >> 16));
    ctl->write_db_word(static_cast<std::uint16_t>(w + 1), static_cast<std::uint16_t>(v & 0xFFFF));
  }
  std::int32_t read_dd(std::uint16_t w) const {
    return static_cast<std::int32_t>((static_cast<std::uint32_t>(word(w)) << 16) |
                                     word(static_cast<std::uint16_t>(w + 1)));
  }
  int error() const { return word(db::dw_error) & 0xFF; }
  int io_error() const { return word(db::dw_io_error); }
  std::int32_t actual() const { return read_dd(db::dd_actual); }
};

class SplitDrive : public ::testing::Test {
 protected:
  SplitDrive() {
    dir = fs::temp_directory_path() /
          ("wf726-split-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir);
  }
  ~SplitDrive() override {
    a.ctl.reset();  // the coupling detaches from either side
    b.ctl.reset();
    fs::remove_all(dir);
  }

  static std::map<int, std::string> md_a() {
    auto md = base_md();
    md[27] = "3";    // A+B
    md[29] = "100";  // µm
    return md;
  }

  void make(Side& s, char letter, const std::map<int, std::string>& md, const mocks::PlantConfig& plant,
            const std::string& programs = {}) {
    std::string text;
    for (const auto& [n, v] : md) text += "MD " + std::to_string(n) + " = " + v + "\n";
    const auto file = dir / (std::string("md-") + letter + ".txt");
    std::ofstream(file) << text;
    ControllerSpec spec;
    spec.device = "wf725-726";
    spec.file = (dir / "scenario.yaml").string();
    spec.line = 3;
    spec.parameters = file;
    if (!programs.empty()) {
      spec.programs = {dir / "progs.wf"};
      std::ofstream(spec.programs.front()) << programs;
    }
    spec.options["axis"] = std::string(1, letter);
    spec.options["db"] = std::to_string(10 + (letter - 'A'));
    ControllerRegistry r;
    register_wf725(r);
    auto c = r.create(spec);
    ASSERT_TRUE(c) << c.error().describe();
    s.ctl.reset(static_cast<Wf725Controller*>(c->release()));
    mocks::SimDriveConfig d;
    d.name = std::string("sim:") + letter;
    d.plant = plant;
    auto drive = std::make_unique<mocks::SimDrive>(d);
    s.drive = drive.get();
    s.axis = std::make_unique<motion::Axis>(s.ctl->axis_specs()[0].config, std::move(drive));
    motion::Axis* ptr = s.axis.get();
    ASSERT_TRUE(s.ctl->bind_axes(std::span<motion::Axis* const>(&ptr, 1)));
    s.every = static_cast<int>(s.ctl->cycle_period() / milliseconds(1));
  }

  static mocks::PlantConfig stiff() {
    mocks::PlantConfig p;
    p.kv_per_s = 200.0;
    p.velocity_lag_s = 0.0;
    p.velocity_feedforward = 1.0;
    return p;
  }

  /// Builds A (MD 27 = 3) and B, couples them as the module does.
  void start(std::map<int, std::string> md_b = base_md(), mocks::PlantConfig plant_b = stiff(),
             const std::string& programs = {}) {
    make(a, 'A', md_a(), stiff(), programs);
    make(b, 'B', md_b, plant_b);
    Wf725Controller* axes[] = {a.ctl.get(), b.ctl.get()};
    const auto coupled = wf725_couple_split_drive(axes);
    ASSERT_TRUE(coupled) << coupled.error();
    ASSERT_NE(a.ctl->split_drive(), nullptr);
  }

  /// The emulator's order per run period: A's machine (axis, cycle), then B's split-drive
  /// set-point, B's machine. `each` after every period (true: stop).
  void run(Duration d, const std::function<bool()>& each = {}) {
    const auto end = now + d;
    while (now < end) {
      now += milliseconds(1);
      ++tick;
      const CycleTime c{now, milliseconds(1)};
      a.ctl->split_drive_period(c);
      a.axis->update(c);
      if (tick % a.every == 0) a.ctl->step(CycleTime{now, a.ctl->cycle_period()});
      b.ctl->split_drive_period(c);
      b.axis->update(c);
      if (tick % b.every == 0) b.ctl->step(CycleTime{now, b.ctl->cycle_period()});
      max_seen_um = std::max(max_seen_um, std::abs(b.axis->status().position - a.axis->status().position) * 1000.0);
      if (each && each()) return;
    }
  }
  bool run_until(const std::function<bool()>& cond, Duration limit = std::chrono::seconds(20)) {
    bool held = false;
    run(limit, [&] { return held = cond(); });
    return held;
  }

  void select(Side& s, db::Submode sub) {
    s.ctl->write_db_word(db::dw_mode, static_cast<std::uint16_t>((1U << (db::bit_mode_traversing - 8)) << 8 |
                                                                 static_cast<unsigned>(sub)));
    run(milliseconds(14));
  }
  void pulse(Side& s, int bit) {
    s.set_bit(db::dw_control, bit, true);
    run(milliseconds(14));
    s.set_bit(db::dw_control, bit, false);
    run(milliseconds(14));
  }
  std::int32_t data_code(Side& s, std::uint16_t code, std::int32_t p1 = 0, std::int32_t p2 = 0) {
    s.ctl->write_db_word(db::dw_data_code, code);
    s.write_dd(db::dd_data_param1, p1);
    s.write_dd(db::dd_data_param2, p2);
    s.set_bit(db::dw_data_execute, 0, true);
    run(milliseconds(14));
    EXPECT_TRUE(s.bit(db::dw_data_status, 0)) << "data code done";
    const auto r = s.read_dd(db::dd_data_result);
    s.set_bit(db::dw_data_execute, 0, false);
    run(milliseconds(14));
    return r;
  }
  /// Both axes synchronized by "setting actual value" (MD 28 of each), enabled; B in submode "0",
  /// A in MDI with the split-drive monitoring bit D 2.3 set.
  void gantry_ready() {
    for (Side* s : {&a, &b}) {
      select(*s, db::Submode::set_actual);
      s->set_bit(db::dw_enable, db::bit_drive_enable, true);
      run(milliseconds(40));
      pulse(*s, db::bit_start);
    }
    select(b, db::Submode::none);
    select(a, db::Submode::mdi);
    a.set_bit(db::dw_enable, db::bit_split_monitoring, true);
    run(milliseconds(20));
  }
  /// MDI on A: G90 to `um` at `feed` (10^-2 mm/min), start.
  void mdi(std::int32_t um, std::int32_t feed) {
    (void)data_code(a, db::code::mdi_position, um);
    (void)data_code(a, db::code::mdi_feed, feed);
    pulse(a, db::bit_start);
  }
  bool at_rest(const Side& s) const {
    return s.axis->status().state == motion::AxisState::standstill && !s.axis->status().busy;
  }

  fs::path dir;
  Side a, b;
  TimePoint now{};
  long tick = 0;
  double max_seen_um = 0.0;  ///< largest |B - A| of the actual positions in any period
};

TEST_F(SplitDrive, ACoupledMdiMoveKeepsBothAxesTogether) {
  mocks::PlantConfig softer = stiff();
  softer.kv_per_s = 150.0;  // a real partner: 10 % velocity lag, another gain
  softer.velocity_feedforward = 0.9;
  start(base_md(), softer);
  gantry_ready();
  ASSERT_TRUE(a.ctl->synchronized());
  ASSERT_TRUE(b.ctl->synchronized());
  mdi(80'000, 300'000);  // 80 mm at 3000 mm/min
  std::int32_t dc30_moving = 0;
  ASSERT_TRUE(run_until([&] { return a.actual() > 40'000; }));
  EXPECT_GT(b.actual(), 39'000) << "B moves with A (one command, two drives)";
  dc30_moving = data_code(a, db::code::split_difference);
  ASSERT_TRUE(run_until([&] { return a.bit(db::dw_status, db::bit_peh) && at_rest(b); }));
  EXPECT_EQ(a.error(), 0);
  EXPECT_EQ(b.error(), 0);
  EXPECT_EQ(a.actual(), 80'000);
  EXPECT_NEAR(b.actual(), 80'000, 2);
  // B lags A by v (1 - ff) / Kv = 50 mm/s x 0.1 / 150 = 33 µm while moving: compared, below MD 29.
  const double max_cmp = a.ctl->split_drive()->max_difference_um;
  EXPECT_GT(max_cmp, 20.0) << "the comparison saw the lag";
  EXPECT_LT(max_cmp, 60.0);
  EXPECT_LT(max_seen_um, 60.0);
  EXPECT_LT(dc30_moving, -20) << "data code 30 while moving: B behind A";
  EXPECT_GT(dc30_moving, -60);
  EXPECT_NEAR(data_code(a, db::code::split_difference), 0, 2) << "together at rest";
  EXPECT_NEAR(data_code(b, db::code::split_difference), 0, 2) << "B's DB axis reads it too";
  // Set up: jogging A moves B as well.
  select(a, db::Submode::set_up);
  (void)data_code(a, db::code::jog_feed, 120'000);
  a.set_bit(db::dw_control, db::bit_minus, true);
  run(milliseconds(500));
  a.set_bit(db::dw_control, db::bit_minus, false);
  ASSERT_TRUE(run_until([&] { return at_rest(a) && at_rest(b); }));
  EXPECT_LT(a.actual(), 80'000 - 5'000);
  EXPECT_NEAR(b.actual(), a.actual(), 2);
  EXPECT_EQ(a.error(), 0);
}

TEST_F(SplitDrive, ASubmodeSelectedTogetherWithTheStartCouplesFromTheFirstPeriod) {
  start();
  gantry_ready();
  select(a, db::Submode::none);
  (void)data_code(a, db::code::mdi_position, 20'000);
  (void)data_code(a, db::code::mdi_feed, 300'000);
  // The PLC writes the submode MDI and the start bit in one go.
  a.ctl->write_db_word(db::dw_mode, static_cast<std::uint16_t>(0x0100 | static_cast<unsigned>(db::Submode::mdi)));
  a.set_bit(db::dw_control, db::bit_start, true);
  max_seen_um = 0.0;
  ASSERT_TRUE(run_until([&] { return a.bit(db::dw_status, db::bit_peh) && at_rest(b) && a.actual() == 20'000; }));
  EXPECT_NEAR(b.actual(), 20'000, 1);
  EXPECT_LT(max_seen_um, 2.0) << "identical drives, one set-point from the first period";
  EXPECT_EQ(a.error(), 0);
}

TEST_F(SplitDrive, AnAutomaticProgramWithFlyingBlockChangesMovesTheGantry) {
  mocks::PlantConfig softer = stiff();
  softer.kv_per_s = 150.0;
  softer.velocity_feedforward = 0.9;
  start(base_md(), softer,
        "%7\nN1 G90 X 20 000 F 300 000\nN2 G90 X 40 000 F 600 000\nN3 G90 X 5 000 F 300 000 M0\n"
        "N4 G91 X 1 000 F 100 000\n");
  gantry_ready();
  select(a, db::Submode::automatic);
  a.ctl->write_db_word(db::dw_program, 7);
  pulse(a, db::bit_start);
  ASSERT_TRUE(run_until([&] { return a.bit(db::dw_flags, 0) && a.bit(db::dw_status, db::bit_peh) && at_rest(b); }))
      << "M0: waits for the start";
  EXPECT_NEAR(a.actual(), 5'000, 1) << "in the PEH window MD 33";
  EXPECT_NEAR(b.actual(), 5'000, 2);
  EXPECT_EQ(a.ctl->block_changes_um().size(), 1U) << "N1 -> N2 flying (same direction), N2 -> N3 reverses";
  pulse(a, db::bit_start);
  ASSERT_TRUE(run_until([&] { return !a.bit(db::dw_flags, 1) && a.bit(db::dw_status, db::bit_peh) && at_rest(b); }));
  EXPECT_EQ(a.actual(), 6'000);
  EXPECT_NEAR(b.actual(), 6'000, 2);
  EXPECT_EQ(a.error(), 0);
  EXPECT_EQ(b.error(), 0);
  // 100 mm/s: B's lag v (1 - ff) / Kv = 67 µm, under MD 29 = 100 µm.
  EXPECT_GT(a.ctl->split_drive()->max_difference_um, 40.0);
  EXPECT_LT(a.ctl->split_drive()->max_difference_um, 100.0);
}

TEST_F(SplitDrive, ASlowPartnerRaises25OnBothAndTheMotionStops) {
  mocks::PlantConfig slow = stiff();
  slow.max_velocity_inc_per_s = 20'000.0;  // 20 mm/s: the partner cannot follow 50 mm/s
  start(base_md(), slow);
  gantry_ready();
  mdi(80'000, 300'000);
  ASSERT_TRUE(run_until([&] { return a.error() != 0; }, std::chrono::seconds(5)));
  EXPECT_EQ(a.error(), 0x25);
  EXPECT_EQ(b.error(), 0x25);
  EXPECT_TRUE(a.bit(db::dw_status, db::bit_error)) << "D 3.5";
  EXPECT_TRUE(b.bit(db::dw_status, db::bit_error));
  const double diff = a.ctl->split_drive()->last_difference_um;
  EXPECT_LT(diff, -100.0) << "B behind A by more than MD 29";
  EXPECT_GT(diff, -100.0 - 6 * 30.0) << "caught within one module cycle of crossing MD 29";
  run(milliseconds(500));
  EXPECT_EQ(a.axis->status().state, motion::AxisState::disabled) << "25 switches the drives off";
  EXPECT_EQ(b.axis->status().state, motion::AxisState::disabled);
  EXPECT_LT(a.actual(), 20'000) << "the motion was terminated, far from 80 mm";
  const auto rest = a.actual();
  run(milliseconds(500));
  EXPECT_EQ(a.actual(), rest);
  EXPECT_EQ(a.error(), 0x25) << "latched until acknowledged";
  // 800C alone: the axes are still apart, the comparison raises 25 again at once.
  (void)data_code(a, db::code::acknowledge);
  (void)data_code(b, db::code::acknowledge);
  run(milliseconds(100));
  EXPECT_EQ(a.error(), 0x25);
  // Monitoring off, acknowledged: the drives come back on D 2.0, data code 31 (shift 0) squares the
  // gantry again at 600 mm/min, then the monitoring is switched on without an error.
  a.set_bit(db::dw_enable, db::bit_split_monitoring, false);
  (void)data_code(a, db::code::acknowledge);
  (void)data_code(b, db::code::acknowledge);
  run(milliseconds(100));
  ASSERT_EQ(a.error(), 0);
  ASSERT_EQ(b.error(), 0);
  EXPECT_LT(data_code(a, db::code::split_difference), -100);
  EXPECT_EQ(data_code(a, db::code::split_shift, 0, 60'000), 0);
  EXPECT_EQ(a.io_error(), 0);
  ASSERT_TRUE(run_until([&] { return at_rest(b) && !a.ctl->split_drive()->following; }, std::chrono::seconds(5)));
  EXPECT_NEAR(b.actual(), a.actual(), 1);
  EXPECT_NEAR(data_code(a, db::code::split_difference), 0, 1);
  a.set_bit(db::dw_enable, db::bit_split_monitoring, true);
  run(milliseconds(100));
  EXPECT_EQ(a.error(), 0);
}

TEST_F(SplitDrive, ADriveFaultOfThePartnerIsMirroredAs6AAndStopsA) {
  start();
  gantry_ready();
  mdi(80'000, 300'000);
  ASSERT_TRUE(run_until([&] { return a.actual() > 20'000; }));
  ASSERT_TRUE(b.drive->inject_fault("not_ready", true));
  ASSERT_TRUE(run_until([&] { return a.error() != 0; }, std::chrono::seconds(2)));
  EXPECT_EQ(a.error(), 0x6A) << "an error in the slave during the function";
  EXPECT_EQ(b.error(), 0x14) << "the slave's own error: drive not ready";
  ASSERT_TRUE(run_until([&] { return at_rest(a); }, std::chrono::seconds(5)));
  EXPECT_LT(a.actual(), 80'000) << "A stopped on its ramp";
  EXPECT_EQ(a.axis->status().state, motion::AxisState::standstill) << "6A stops, the drive stays on";
}

TEST_F(SplitDrive, UnequalMd1Md2Md38Md39Give6DAtTheStart) {
  auto md_b = base_md();
  md_b[2] = "400";  // MD 2 (deceleration) differs
  start(md_b);
  gantry_ready();
  mdi(10'000, 300'000);
  run(milliseconds(200));
  EXPECT_EQ(a.error(), 0x6D);
  EXPECT_EQ(b.error(), 0);
  EXPECT_EQ(a.actual(), 0) << "nothing moved";
  EXPECT_EQ(b.actual(), 0);
  EXPECT_EQ(wf725_split_md_mismatch(a.ctl->machine_data(), b.ctl->machine_data()), 2);
}

TEST_F(SplitDrive, TheSlaveOutsideSubmode0Gives69And6B) {
  start();
  gantry_ready();
  select(b, db::Submode::mdi);
  mdi(10'000, 300'000);
  EXPECT_EQ(b.error(), 0x69);
  EXPECT_EQ(a.error(), 0x6B);
  EXPECT_EQ(a.actual(), 0);
  // Back to "0", acknowledged: the coupled start runs.
  select(b, db::Submode::none);
  (void)data_code(a, db::code::acknowledge);
  EXPECT_EQ(b.error(), 0x69) << "self-acknowledging: B's next start clears it";
  pulse(b, db::bit_start);
  EXPECT_EQ(b.error(), 0);
  pulse(a, db::bit_start);  // the MDI position was not consumed by the refused start
  ASSERT_TRUE(run_until([&] { return a.bit(db::dw_status, db::bit_peh) && at_rest(b) && a.actual() == 10'000; }));
  EXPECT_NEAR(b.actual(), 10'000, 2);
}

TEST_F(SplitDrive, DataCode30ReadsTheDifferenceAnd31ShiftsTheSlave) {
  auto md_b = base_md();
  md_b[28] = "20";  // B's actual value is set 20 µm beyond A's
  start(md_b);
  gantry_ready();
  EXPECT_EQ(data_code(a, db::code::split_difference), 20);
  // Data code 31: B 5 mm beyond A at 600 mm/min; A stands.
  EXPECT_EQ(data_code(a, db::code::split_shift, 5'000, 60'000), 0);
  EXPECT_EQ(a.io_error(), 0);
  ASSERT_TRUE(run_until([&] { return b.actual() > 4'000; }, std::chrono::seconds(3)));
  EXPECT_EQ(a.actual(), 0) << "the master stands";
  ASSERT_TRUE(run_until([&] { return at_rest(b) && !a.ctl->split_drive()->following; }, std::chrono::seconds(3)));
  EXPECT_NEAR(b.actual(), 5'000, 1);
  EXPECT_NEAR(data_code(a, db::code::split_difference), 0, 1) << "the shift is commanded";
  EXPECT_EQ(a.error(), 0);
  // A coupled move keeps the shift: B 5 mm beyond A all the way (identical drives).
  mdi(30'000, 300'000);
  double worst_um = 0.0;
  ASSERT_TRUE(run_until([&] {
    worst_um = std::max(worst_um, std::abs(static_cast<double>(b.actual() - a.actual() - 5'000)));
    return a.bit(db::dw_status, db::bit_peh) && at_rest(b) && a.actual() == 30'000;
  }));
  EXPECT_NEAR(b.actual(), 35'000, 2);
  EXPECT_LT(worst_um, 2.0);
  // 31 with feed 0: 145; 31 in the slave's DB axis: 113; 30 on an uncoupled module: 113.
  (void)data_code(a, db::code::split_shift, 0, 0);
  EXPECT_EQ(a.io_error(), 0x0145);
  (void)data_code(b, db::code::split_shift, 1'000, 60'000);
  EXPECT_EQ(b.io_error(), 0x0113);
}

TEST_F(SplitDrive, TheAxesApartByMoreThanMd29RefuseTheStartWith25) {
  auto md_b = base_md();
  md_b[28] = "150";  // 150 µm > MD 29 = 100 µm: not synchronized together
  start(md_b);
  gantry_ready();
  EXPECT_EQ(a.error(), 0x25) << "compared continuously: at rest too";
  EXPECT_EQ(b.error(), 0x25);
  EXPECT_EQ(a.actual(), 0);
}

TEST_F(SplitDrive, WithoutTheMonitoringBitNoComparison) {
  auto md_b = base_md();
  md_b[28] = "150";
  start(md_b);
  gantry_ready();
  a.set_bit(db::dw_enable, db::bit_split_monitoring, false);
  (void)data_code(a, db::code::acknowledge);
  (void)data_code(b, db::code::acknowledge);
  run(milliseconds(60));
  ASSERT_EQ(a.error(), 0);
  mdi(10'000, 300'000);
  ASSERT_TRUE(run_until([&] { return a.bit(db::dw_status, db::bit_peh) && at_rest(b) && a.actual() == 10'000; }));
  EXPECT_NEAR(b.actual(), 10'000, 2) << "B's residual 150 µm ramped out while coupled (no set-point step)";
  EXPECT_LT(max_seen_um, 160.0);
  EXPECT_EQ(a.error(), 0);
}

TEST_F(SplitDrive, Md27IsReadAtPowerUpAndCouplingErrorsNameTheCause) {
  start();
  select(a, db::Submode::none);
  a.ctl->write_db_word(db::dw_mode, static_cast<std::uint16_t>((1U << (db::bit_mode_machine_data - 8)) << 8));
  run(milliseconds(14));
  (void)data_code(a, db::code::write_md, 27, 5);
  EXPECT_EQ(a.ctl->pending_md(), (std::vector<int>{27})) << "MD 27 applies at the next power-up";
  EXPECT_EQ(a.ctl->split_drive()->slave, b.ctl.get()) << "still A+B";
  // MD 27 = 5 (A+C) on a module with A and B only: the module refuses to start.
  auto md = md_a();
  md[27] = "5";
  Side c;
  make(c, 'A', md, stiff());
  Wf725Controller* axes[] = {c.ctl.get()};
  const auto r = wf725_couple_split_drive(axes);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("no axis C"), std::string::npos) << r.error();
  // Roller feed (MD 42 = 1 clears the actual value at every start) cannot be a split drive.
  auto roller = base_md();
  roller[42] = "1";
  Side d, e;
  make(d, 'A', md_a(), stiff());
  make(e, 'B', roller, stiff());
  const auto r2 = d.ctl->couple_split_drive(*e.ctl);
  ASSERT_FALSE(r2);
  EXPECT_NE(r2.error().find("roller feed"), std::string::npos) << r2.error();
  EXPECT_EQ(d.ctl->split_drive(), nullptr) << "nothing coupled";
  EXPECT_EQ(wf725_split_partner(3), 'B');
  EXPECT_EQ(wf725_split_partner(5), 'C');
  EXPECT_EQ(wf725_split_partner(6), '\0');
}

}  // namespace
}  // namespace hil::controllers::s5::test
