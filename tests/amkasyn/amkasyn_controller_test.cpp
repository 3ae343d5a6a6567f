// SPDX-License-Identifier: MIT
// The amkasyn-sf controller (docs/amkasyn.md, "Scenarios"): the DB text codec, the factory's
// configuration errors (file, line, key), the image mapping (E/A/M byte for byte, the PLC's flag
// writes in the data area, the FB 208 command and status bits), the start/reset/VALUE NEW
// handshake, commanding errors as sf_status device errors, and the AW/AZ axes on simulated drives.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "hil/controllers/amkasyn/amkasyn_controller.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace hil::controllers::amkasyn {
namespace {

using std::chrono::milliseconds;
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// DB text codec

TEST(DbText, SfFileIntoInitAndCommandingDb) {
  auto r = parse_sf_db_text(
      "; comment\nINIT DR0 = 3\ninit DL0 = 2   ; SF2\nDL1 = 0x03\nDW2 = 7936\nDW6 = -10000\nDD10 = 70000\n"
      "DR4 = 10h # hex\n\n");
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->has_init);
  EXPECT_EQ(r->init.dr(0), 3);
  EXPECT_EQ(r->init.dl(0), 2);
  EXPECT_EQ(r->command.dl(1), 3);
  EXPECT_EQ(r->command.dw(2), 7936);
  EXPECT_EQ(r->command.dw(6), -10000);
  EXPECT_EQ(r->command.dd(10), 70000);
  EXPECT_EQ(r->command.uw(10), 70000 & 0xFFFF) << "low word first";
  EXPECT_EQ(r->command.uw(11), 1);
  EXPECT_EQ(r->command.dr(4), 16);
}

TEST(DbText, ErrorsNameLineAndItem) {
  auto e = parse_sf_db_text("INIT DR0 = 1\nDW34 = 1\n");
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().line, 2);
  EXPECT_EQ(e.error().item, "DW34");
  EXPECT_NE(e.error().message.find("34-word commanding DB"), std::string::npos) << e.error().message;
  e = parse_sf_db_text("INIT DW10 = 1\n");
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("init DB"), std::string::npos);
  e = parse_sf_db_text("DR3 = 256\n");
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("does not fit"), std::string::npos);
  e = parse_sf_db_text("DW3 = four\n");
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("not an integer"), std::string::npos);
  e = parse_sf_db_text("XX3 = 1\n");
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("DRn, DLn, DWn or DDn"), std::string::npos);
  e = parse_sf_db_text("DW99999999999999 = 1\n");
  ASSERT_FALSE(e) << "an absurd address is an error, not an exception";
  auto t = parse_table_db_text("INIT DR0 = 1\n");
  ASSERT_FALSE(t);
  EXPECT_NE(t.error().message.find("table DB"), std::string::npos);
}

TEST(DbText, TableDbUpToTheXfipwSize) {
  auto t = parse_table_db_text("DW0 = 10\nDD2 = 0\nDD4 = 500\nDD4000 = -1\n");
  ASSERT_TRUE(t) << t.error().message;
  EXPECT_EQ(t->size(), 4002U);
  EXPECT_EQ(t->dd(4), 500);
  EXPECT_EQ(t->dd(4000), -1);
  EXPECT_FALSE(parse_table_db_text("DD4001 = 1\n"));
}

// ---------------------------------------------------------------------------------------------
// Factory and runs

constexpr const char* ecopy = R"(INIT DR0 = 0
INIT DL0 = 0
INIT DR1 = 3
INIT DR3 = 0
INIT DL3 = 64
INIT DR4 = 1
INIT DL4 = 100
INIT DR5 = 1
INIT DL5 = 101
DR0 = 0
DL0 = 2
DR1 = 1
DL1 = 3
DD2 = 10000
DD4 = 5000
)";

constexpr const char* varsync = R"(INIT DR0 = 3
INIT DL0 = 2
INIT DR2 = 1
INIT DL2 = 0
INIT DR3 = 4
INIT DL3 = 3
INIT DR4 = 4
INIT DL4 = 16
INIT DR5 = 4
INIT DL5 = 16
DR0 = 2
DL0 = 1
DR1 = 1
DL1 = 0
DW2 = 0
DW4 = 10000
DW6 = -10000
)";

class AmkController : public ::testing::Test {
 protected:
  AmkController() {
    dir = fs::temp_directory_path() / ("hil_amk_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                       "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
    spec.device = "amkasyn-sf";
    spec.file = (dir / "scenario.yaml").string();
    spec.line = 7;
    spec.cycle = milliseconds(1);
  }
  ~AmkController() override { fs::remove_all(dir); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  }
  std::expected<std::unique_ptr<Controller>, ConfigError> create() {
    ControllerRegistry r;
    register_amkasyn(r);
    return r.create(spec);
  }
  /// Builds the controller and one simulated axis per declared axis, enabled by the controller.
  void start() {
    auto c = create();
    ASSERT_TRUE(c) << c.error().describe();
    ctl.reset(static_cast<AmkasynController*>(c->release()));
    std::vector<motion::Axis*> ptrs;
    for (const auto& a : ctl->axis_specs()) {
      mocks::SimDriveConfig d;
      d.name = "sim:" + a.name;
      d.plant.kv_per_s = 200.0;
      d.plant.velocity_lag_s = 0.0;
      d.plant.velocity_feedforward = 1.0;
      axes.push_back(std::make_unique<motion::Axis>(a.config, std::make_unique<mocks::SimDrive>(d)));
      ptrs.push_back(axes.back().get());
    }
    ASSERT_TRUE(ctl->bind_axes(ptrs));
    ctl->io().attach(script);
  }
  void run(Duration d) {
    const auto end = now + d;
    while (now < end) {
      now += milliseconds(1);
      for (auto& a : axes) a->update(CycleTime{now, milliseconds(1)});
      ctl->step(CycleTime{now, milliseconds(1)});
    }
  }
  struct Script : IoSource {
    std::vector<std::pair<BitAddress, bool>> pending;
    void read(TimePoint, IoImage& image) noexcept override {
      for (const auto& [a, v] : pending) image.set(a, v);
      pending.clear();
    }
  };
  void set(std::string_view signal, bool v) {
    auto a = ctl->resolve_bit(signal);
    ASSERT_TRUE(a) << a.error();
    script.pending.emplace_back(*a, v);
  }
  bool get(std::string_view signal) {
    auto a = ctl->resolve_bit(signal);
    return a && ctl->io().get(*a);
  }
  fs::path dir;
  ControllerSpec spec;
  std::unique_ptr<AmkasynController> ctl;
  std::vector<std::unique_ptr<motion::Axis>> axes;
  Script script;
  TimePoint now{};
};

TEST_F(AmkController, ImageMappingAndNames) {
  spec.parameters = write("ecopy.txt", ecopy);
  spec.options = {{"aw1", "X"}};
  start();
  auto bit = [&](std::string_view s) { return *ctl->resolve_bit(s); };
  EXPECT_EQ(bit("E 16.2"), (BitAddress{IoArea::input, 16, 2}));
  EXPECT_EQ(bit("A 8.0"), (BitAddress{IoArea::output, 8, 0}));
  EXPECT_EQ(bit("M 101.0"), (BitAddress{IoArea::marker, 101, 0})) << "an SF output in the flag area";
  EXPECT_EQ(bit("M 232.0"), (BitAddress{IoArea::marker, 232, 0})) << "MB 232 is the SF status";
  EXPECT_EQ(bit("M 100.0"), (BitAddress{IoArea::data, 116, 0})) << "a flag the PLC writes";
  EXPECT_EQ(bit("sf0_start"), (BitAddress{IoArea::data, 0, 0}));
  EXPECT_EQ(bit("sf0_read_value"), (BitAddress{IoArea::data, 0, 3}));
  EXPECT_EQ(bit("sf0_active"), (BitAddress{IoArea::data, 0, 4}));
  EXPECT_FALSE(ctl->resolve_bit("sf1_start")) << "no SF1 in this setup";
  EXPECT_FALSE(ctl->resolve_bit("Q 1.0"));
  ASSERT_EQ(ctl->trace_signals(), std::vector<std::string>{"AA1_mV"});
}

TEST_F(AmkController, EcopyOnThePlcFlagAutoStart) {
  spec.parameters = write("ecopy.txt", ecopy);
  spec.options = {{"aw1", "X"}};
  start();
  run(milliseconds(20));
  EXPECT_TRUE(get("sf0_active"));
  EXPECT_EQ(ctl->trace_value(0), 10000.0);
  EXPECT_FALSE(get("M 101.0"));
  set("M 100.0", true);
  run(milliseconds(1));
  EXPECT_EQ(ctl->process_image().m[100] & 1, 1) << "the PLC's flag write reached the SF's flag image";
  EXPECT_EQ(ctl->trace_value(0), 5000.0);
  EXPECT_TRUE(get("M 101.0"));
  set("M 100.0", false);
  run(milliseconds(1));
  EXPECT_EQ(ctl->trace_value(0), 10000.0);
  EXPECT_FALSE(get("M 101.0"));
  EXPECT_FALSE(ctl->errors().any());
}

TEST_F(AmkController, StartResetValueNewHandshake) {
  spec.parameters = write("ecopy.txt", ecopy);
  spec.options = {{"aw1", "X"}, {"start", "input"}};
  start();
  run(milliseconds(20));
  EXPECT_FALSE(get("sf0_active")) << "start: input waits for the PLC";
  EXPECT_EQ(ctl->trace_value(0), 0.0);
  set("sf0_start", true);
  run(milliseconds(1));
  EXPECT_TRUE(get("sf0_active"));
  EXPECT_FALSE(get("sf0_error"));
  EXPECT_FALSE(get("M 232.0"));
  EXPECT_EQ(ctl->trace_value(0), 10000.0);
  // START while active: error 2, MB 232 bit 0, MB 233 = 2, a device error; the SF keeps running.
  set("sf0_start", false);
  run(milliseconds(1));
  set("sf0_start", true);
  run(milliseconds(1));
  EXPECT_TRUE(get("sf0_error"));
  EXPECT_TRUE(get("M 232.0"));
  EXPECT_EQ(ctl->process_image().m[233], 2);
  EXPECT_TRUE(get("sf0_active"));
  ASSERT_TRUE(ctl->errors().any());
  EXPECT_EQ(ctl->errors().active().front().code, 2);
  EXPECT_EQ(std::string(ctl->errors().active().front().fault.code.category().name()), "amkasyn-sf.sf_status");
  // VALUE NEW while active: accepted (ECOPY has it).
  set("sf0_value_new", true);
  run(milliseconds(1));
  EXPECT_FALSE(get("sf0_error"));
  // RESET: the SF stops (AA1 keeps its last value), VALUE NEW is then refused with error 3.
  set("sf0_reset", true);
  run(milliseconds(1));
  EXPECT_FALSE(get("sf0_active"));
  set("sf0_value_new", false);
  run(milliseconds(1));
  set("sf0_value_new", true);
  run(milliseconds(1));
  EXPECT_TRUE(get("sf0_error"));
  EXPECT_EQ(ctl->process_image().m[233], 3);
  // READ VALUE belongs to XFIPW: error 1 for ECOPY.
  set("sf0_read_value", true);
  run(milliseconds(1));
  EXPECT_EQ(ctl->process_image().m[233], 1);
  EXPECT_EQ(ctl->acknowledge(Acknowledgement::acknowledge), 3U);
  EXPECT_FALSE(ctl->errors().any());
}

TEST_F(AmkController, ValueNewSendsItsOwnCommandingDb) {
  spec.parameters = write("ecopy.txt", ecopy);
  write("ecopy-vn.txt",
        "; VALUE NEW for SF0: new values for both E1 states\nDR0 = 0\nDL0 = 2\nDR1 = 5\nDL1 = 3\n"
        "DD2 = 7000\nDD4 = 3000\n");
  spec.options = {{"aw1", "X"}, {"value_new", "ecopy-vn.txt"}};
  start();
  run(milliseconds(20));
  EXPECT_EQ(ctl->trace_value(0), 10000.0);
  set("sf0_value_new", true);
  run(milliseconds(1));
  EXPECT_FALSE(get("sf0_error"));
  EXPECT_EQ(ctl->trace_value(0), 7000.0) << "ECOPY takes Value_E1_0 / Value_E1_1 at VALUE NEW";
  set("M 100.0", true);
  run(milliseconds(1));
  EXPECT_EQ(ctl->trace_value(0), 3000.0);
  // A VALUE NEW DB the profile refuses, for an SF the setup lacks, or with INIT lines.
  write("bad-vn.txt", "DR0 = 0\nDL0 = 2\nDR1 = 5\nDD2 = 1\nDW40 = 1\n");
  spec.options = {{"aw1", "X"}, {"value_new", "bad-vn.txt"}};
  auto e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().file, (dir / "bad-vn.txt").string());
  EXPECT_EQ(e.error().line, 5);
  write("other-vn.txt", "DR0 = 7\nDR1 = 5\n");
  spec.options = {{"aw1", "X"}, {"value_new", "other-vn.txt"}};
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "DR0");
  EXPECT_NE(e.error().message.find("names no SF"), std::string::npos) << e.error().describe();
  write("init-vn.txt", "INIT DR0 = 0\nDR0 = 0\nDR1 = 5\n");
  spec.options = {{"aw1", "X"}, {"value_new", "init-vn.txt"}};
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "INIT");
}

TEST_F(AmkController, VarsyncDrivesTheSlaveAxisFromTheMasterAxis) {
  spec.parameters = write("varsync.txt", varsync);
  spec.options = {{"az1", "M"}, {"aw3", "S"}};
  start();
  ASSERT_EQ(ctl->axis_specs().size(), 2U);
  EXPECT_EQ(ctl->axis_specs()[0].name, "S") << "AW axes first, then the AZ masters";
  EXPECT_EQ(ctl->axis_specs()[0].units, "inc");
  motion::Axis& s = *axes[0];
  motion::Axis& m = *axes[1];
  run(milliseconds(50));
  ASSERT_EQ(m.status().state, motion::AxisState::standstill);
  ASSERT_FALSE(m.move_relative(5000.0, motion::Limits{10000.0, 100000.0}));
  run(milliseconds(1000));
  EXPECT_EQ(s.status().command_inc, 5000);
  EXPECT_EQ(s.status().state, motion::AxisState::standstill) << "the set-point rests: the coupled state ends";
  set("E 16.2", true);  // mirror
  run(milliseconds(2));
  EXPECT_TRUE(get("A 16.2"));
  ASSERT_FALSE(m.move_relative(2000.0, motion::Limits{10000.0, 100000.0}));
  run(milliseconds(1000));
  EXPECT_EQ(s.status().command_inc, 3000);
  EXPECT_EQ(s.status().position_inc, 3000);
}

TEST_F(AmkController, ZeroPulseInputLatchesTheCounterOfItsCycle) {
  spec.parameters = write("varsync.txt", varsync);
  spec.options = {{"az1", "M"}, {"aw3", "S"}};
  start();
  EXPECT_EQ(*ctl->resolve_bit("az1_zero"), AmkasynController::zero_pulse_bit(0));
  EXPECT_EQ(AmkasynController::zero_pulse_bit(0), (BitAddress{IoArea::data, 272, 0}));
  EXPECT_FALSE(ctl->resolve_bit("az2_zero")) << "AZ message 2 has no axis in this setup";
  motion::Axis& m = *axes[1];
  run(milliseconds(50));
  ASSERT_FALSE(m.move_relative(5000.0, motion::Limits{10000.0, 100000.0}));
  run(milliseconds(1000));
  EXPECT_EQ(ctl->process_image().az_zero[0].count, 0U);
  set("az1_zero", true);
  run(milliseconds(1));
  EXPECT_EQ(ctl->process_image().az_zero[0].count, 1U);
  EXPECT_EQ(ctl->process_image().az_zero[0].position, 5000) << "the 32-bit counter of the edge's cycle";
  ASSERT_FALSE(m.move_relative(2000.0, motion::Limits{10000.0, 100000.0}));
  run(milliseconds(1000));
  EXPECT_EQ(ctl->process_image().az_zero[0].count, 1U) << "a level is no pulse: only the rising edge latches";
  set("az1_zero", false);
  run(milliseconds(1));
  set("az1_zero", true);
  run(milliseconds(1));
  EXPECT_EQ(ctl->process_image().az_zero[0].count, 2U);
  EXPECT_EQ(ctl->process_image().az_zero[0].position, 7000);
}

TEST_F(AmkController, Swq1GoesThroughTheDrivesSynchronousRatio) {
  spec.parameters = write("varsync.txt", varsync);
  // ID 32893 / ID 32892 = 196608 / 131072 = 1.5, exact over odd master steps.
  spec.options = {{"az1", "M"}, {"aw3", "S"}, {"aw3_id32893", "196608"}, {"aw3_id32892", "131072"}};
  start();
  run(milliseconds(50));
  ASSERT_FALSE(axes[1]->move_relative(5001.0, motion::Limits{10000.0, 100000.0}));
  run(milliseconds(1000));
  EXPECT_EQ(axes[0]->status().command_inc, 7501) << "5001 x 1.5 = 7501.5: the half stays as a remainder";
  ASSERT_FALSE(axes[1]->move_relative(1.0, motion::Limits{10000.0, 100000.0}));
  run(milliseconds(500));
  EXPECT_EQ(axes[0]->status().command_inc, 7503) << "5002 x 1.5";
  spec.options = {{"az1", "M"}, {"aw3", "S"}, {"aw3_id32892", "100"}};
  auto e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "controller.aw3_id32892");
}

TEST_F(AmkController, ConfigurationErrorsNameFileLineAndKey) {
  spec.parameters = write("varsync.txt", varsync);
  spec.options = {{"az1", "M"}};
  auto e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "INIT DL3");
  EXPECT_NE(e.error().message.find("aw3: NAME"), std::string::npos) << e.error().describe();
  EXPECT_EQ(e.error().line, 6);

  spec.options = {{"aw3", "S"}};
  e = create();
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("az1: NAME"), std::string::npos) << e.error().describe();

  spec.options = {{"aw3", "S"}, {"az1", "M"}, {"bogus", "1"}};
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "controller.bogus");
  EXPECT_EQ(e.error().line, 7);
  EXPECT_EQ(e.error().file, spec.file);

  spec.options = {{"aw3", "S"}, {"az1", "M"}, {"aw3_mode", "3C0043"}};
  e = create();
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("SWQ1"), std::string::npos) << e.error().describe();

  spec.options = {{"aw3", "S"}, {"az1", "M"}};
  spec.cycle = milliseconds(1) + std::chrono::microseconds(250);
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "controller.cycle");
  spec.cycle = milliseconds(1);

  // A value the profile refuses: its file, line and parameter.
  std::string bad = varsync;
  bad.replace(bad.find("DW4 = 10000"), 11, "DW4 = 99999");
  spec.parameters = write("bad.txt", bad);
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().file, (dir / "bad.txt").string());
  EXPECT_EQ(e.error().line, 16);
  EXPECT_NE(e.error().key.find("DW4"), std::string::npos) << e.error().describe();

  spec.parameters = dir / "missing.txt";
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().file, (dir / "missing.txt").string());
  EXPECT_NE(e.error().message.find("cannot read"), std::string::npos) << e.error().describe();

  spec.parameters = write("noinit.txt", "DR0 = 0\nDR1 = 1\n");
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "INIT_DR0") << e.error().describe();  // the profile's rule: the SF type is required

  // Two files for one SF number.
  spec.parameters = write("varsync.txt", varsync);
  spec.programs = {write("varsync2.txt", varsync)};
  e = create();
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("already initialised"), std::string::npos) << e.error().describe();
}

TEST_F(AmkController, AnAzMessageIsReadOneWayAndTheModesMatchTheSinks) {
  // DCOPY of the 32-bit AZ message 1 into MD 40 besides VARSYNC reading its 16-bit high word.
  spec.parameters = write("varsync.txt", varsync);
  spec.programs = {write("dcopy.txt",
                         "INIT DR0 = 0\nINIT DL0 = 0\nINIT DR2 = 16\nINIT DR3 = 40\nINIT DL3 = 129\n"
                         "DR0 = 0\nDL0 = 1\nDR1 = 1\nDL1 = 0\n")};
  spec.options = {{"aw3", "S"}, {"az1", "M"}};
  auto e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "controller.az1");
  EXPECT_NE(e.error().message.find("both"), std::string::npos) << e.error().describe();
  // Alone, the DCOPY reads the count as 32 bits: MD 40 = the master's increments.
  spec.parameters = spec.programs.front();
  spec.programs.clear();
  spec.options = {{"az1", "M"}};
  start();
  run(milliseconds(20));
  ASSERT_FALSE(axes[0]->move_relative(70000.0, motion::Limits{100000.0, 1000000.0}));
  run(milliseconds(1500));
  EXPECT_EQ(axes[0]->status().position_inc, 70000);
  EXPECT_EQ(ctl->process_image().md(40), 70000) << "beyond 16 bits: the 32-bit form";
  EXPECT_FALSE(get("M 232.0"));
}

constexpr const char* binea = R"(INIT DR0 = 8
INIT DL0 = 0
INIT DR2 = 5
INIT DL2 = 2
INIT DR5 = 1
INIT DL5 = 8
INIT DR6 = 16
DR0 = 0
DR1 = 1
DL1 = 1
DW3 = 2
DW4 = 2
)";

TEST_F(AmkController, TableDbErrors) {
  spec.parameters = write("binea.txt", binea);
  spec.options = {{"aw2", "W"}};
  auto e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "INIT DR6");
  EXPECT_EQ(e.error().line, 7);
  EXPECT_NE(e.error().message.find("tables: \"16=FILE\""), std::string::npos) << e.error().describe();

  spec.options = {{"aw2", "W"}, {"tables", "16=nothere.txt"}};
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "controller.tables");
  EXPECT_NE(e.error().message.find("DB16"), std::string::npos) << e.error().describe();

  write("db16.txt", "DW0 = 9\nDD4 = 2500\nDQ6 = 1\n");
  spec.options = {{"aw2", "W"}, {"tables", "DB16 = db16.txt"}};
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().file, (dir / "db16.txt").string());
  EXPECT_EQ(e.error().line, 3);

  spec.options = {{"aw2", "W"}, {"tables", "sixteen=db16.txt"}};
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "controller.tables");
}

TEST_F(AmkController, BadTableContentIsARefusedStartNotACrash) {
  // |dY| >= 32768 in a BINEA-free FIPZ table: START error 1 with the rule, the SF stays in RESET.
  spec.parameters = write("fipz.txt", R"(INIT DR0 = 2
INIT DL0 = 1
INIT DR3 = 4
INIT DL3 = 1
INIT DR4 = 1
INIT DL4 = 8
INIT DR6 = 20
DR0 = 1
DR1 = 1
DL1 = 16
DW3 = 2
DW4 = 1
DD8 = 1
DW10 = 200
)");
  write("db20.txt", "DW0 = 3\nDD2 = 0\nDD4 = 40000\n");
  spec.options = {{"aw1", "S"}, {"tables", "20=db20.txt"}};
  start();
  run(milliseconds(50));
  EXPECT_FALSE(get("sf1_active"));
  EXPECT_TRUE(get("sf1_error"));
  ASSERT_TRUE(ctl->errors().any());
  const auto& err = ctl->errors().active().front();
  EXPECT_EQ(err.code, 1);
  EXPECT_EQ(err.axis, 0) << "on AW1's axis";
  EXPECT_NE(err.fault.text.find("32768"), std::string::npos) << err.fault.text;
  EXPECT_EQ(axes[0]->status().state, motion::AxisState::standstill);
}

// ---------------------------------------------------------------------------------------------
// awN_message16: the analog input A1 of an AW drive (vector 6.9 REGL)

TEST(AnalogSchedule, EachWordIsHeldFromItsTimeUntilTheNext) {
  const auto s = parse_analog_schedule(" 0ms=2108, 3ms = 2128 ,1s=0x0800, 1000001us=65535");
  ASSERT_TRUE(s) << s.error();
  ASSERT_EQ(s->size(), 4U);
  EXPECT_EQ(analog_word_at(*s, milliseconds(0)), 2108);
  EXPECT_EQ(analog_word_at(*s, std::chrono::microseconds(2999)), 2108);
  EXPECT_EQ(analog_word_at(*s, milliseconds(3)), 2128);
  EXPECT_EQ(analog_word_at(*s, milliseconds(999)), 2128);
  EXPECT_EQ(analog_word_at(*s, std::chrono::seconds(1)), 0x800);
  EXPECT_EQ(analog_word_at(*s, std::chrono::seconds(5)), 65535);
  const auto late = parse_analog_schedule("5ms=2148");
  ASSERT_TRUE(late);
  EXPECT_EQ(analog_word_at(*late, milliseconds(4)), 0) << "no input before the first step";
  EXPECT_EQ(analog_word_at(*late, milliseconds(5)), 2148);
}

TEST(AnalogSchedule, ErrorsNameTheItem) {
  const auto error = [](std::string_view text) {
    const auto s = parse_analog_schedule(text);
    return s ? std::string("accepted") : s.error();
  };
  EXPECT_NE(error("0ms 2108").find("'0ms 2108': write TIME=WORD"), std::string::npos) << error("0ms 2108");
  EXPECT_NE(error("0=2108").find("'0=2108': the time"), std::string::npos) << error("0=2108");
  EXPECT_NE(error("-1ms=2108").find("the time"), std::string::npos);
  EXPECT_NE(error("1.5ms=2108").find("the time"), std::string::npos);
  EXPECT_NE(error("0ms=65536").find("'0ms=65536': the word"), std::string::npos) << error("0ms=65536");
  EXPECT_NE(error("0ms=-1").find("the word"), std::string::npos);
  EXPECT_NE(error("0ms=0x1FFFF").find("the word"), std::string::npos);
  EXPECT_NE(error("0ms=2108, 3ms=").find("'3ms=': the word"), std::string::npos) << error("0ms=2108, 3ms=");
  EXPECT_NE(error("3ms=2108, 3ms=2128").find("'3ms=2128': the times must increase"), std::string::npos)
      << error("3ms=2108, 3ms=2128");
  EXPECT_NE(error("2s=1, 1s=2").find("increase"), std::string::npos);
  EXPECT_NE(error(" , ").find("no step"), std::string::npos) << error(" , ");
  EXPECT_NE(error("100000s=1").find("at most a day"), std::string::npos);
}

constexpr const char* regl = R"(INIT DR0 = 6
INIT DL0 = 0
INIT DR2 = 2
INIT DL2 = 1
INIT DR3 = 16
INIT DL3 = 1
INIT DR5 = 1
INIT DL5 = 0
DR0 = 0
DL0 = 0
DR1 = 1
DL1 = 0
DW3 = 2
DW4 = 7
DW6 = 512
DW7 = 128
DW8 = 64
DD10 = 1000000
DW12 = 1000
DD14 = 1000000
DW18 = 100
DD20 = 5000000
)";

TEST_F(AmkController, AwMessage16FeedsTheAnalogInputOfItsCycle) {
  // The START comes once the simulated drive is enabled; the REGL's first control cycle is at
  // t = 4 ms (t counts from the controller's first cycle). Vector 6.9: F = 60 N (2108) for four
  // control cycles, then 80 N (2128) from t = 8 ms.
  spec.parameters = write("regl.txt", regl);
  spec.options = {{"aw1", "S"}, {"aw1_mode", "3C0043"}, {"aw1_message16", "0ms=2108, 8ms=2128"}};
  start();
  std::vector<int> words, outputs;
  for (int k = 0; k < 10; ++k) {
    run(milliseconds(1));
    words.push_back(ctl->process_image().aw[0].message16);
    outputs.push_back(ctl->process_image().aw[0].swq2);
  }
  EXPECT_EQ(words, (std::vector<int>{2108, 2108, 2108, 2108, 2108, 2108, 2108, 2108, 2128, 2128}));
  EXPECT_EQ(outputs, (std::vector<int>{0, 0, 0, 0, 5100000, 5120000, 5140000, 5160000, 5125000, 5140000}));
  EXPECT_FALSE(get("A 0.0"));
  EXPECT_FALSE(get("A 0.1"));
}

TEST_F(AmkController, WithoutTheAnalogInputMessage16ReadsZero) {
  spec.parameters = write("regl.txt", regl);
  spec.options = {{"aw1", "S"}, {"aw1_mode", "3C0043"}};
  start();
  run(milliseconds(5));
  EXPECT_EQ(ctl->process_image().aw[0].message16, 0);
  // 0 in 12-bit offset binary is -2048 N: e = 2148 N, the output limited to y_max.
  EXPECT_EQ(ctl->process_image().aw[0].swq2, 1000000 + 5000000);
  EXPECT_TRUE(get("A 0.0")) << "positive limitation";
}

TEST_F(AmkController, AwMessage16ErrorsNameTheKey) {
  spec.parameters = write("regl.txt", regl);
  spec.options = {{"aw1", "S"}, {"aw1_mode", "3C0043"}, {"aw1_message16", "0ms=2108, 3ms=70000"}};
  auto e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "controller.aw1_message16");
  EXPECT_EQ(e.error().file, spec.file);
  EXPECT_EQ(e.error().line, 7);
  EXPECT_NE(e.error().message.find("'3ms=70000'"), std::string::npos) << e.error().describe();
  EXPECT_NE(e.error().message.find("AW1"), std::string::npos) << e.error().describe();

  spec.options = {{"aw1", "S"}, {"aw1_mode", "3C0043"}, {"aw2_message16", "0ms=2048"}};
  e = create();
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().key, "controller.aw2");
  EXPECT_NE(e.error().message.find("aw2: NAME"), std::string::npos) << e.error().describe();
}

}  // namespace
}  // namespace hil::controllers::amkasyn
