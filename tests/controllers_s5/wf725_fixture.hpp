// SPDX-License-Identifier: MIT
#pragma once
// A WF 725/726 controller on one simulated axis, stepped on virtual time (1 ms run period, the
// controller at its cycle), commanded through the DB axis words like an S5 PLC.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace hil::controllers::s5::test {

namespace fs = std::filesystem;
namespace db = wf_db;
using std::chrono::milliseconds;

/// The MD list of examples/controllers/wf725-axis-a.txt (1 µm/inc, 6000 mm/min, 500 mm/s²).
inline std::map<int, std::string> base_md() {
  return {{49, "1"},    {4, "1"},     {1, "500"},    {2, "500"},     {3, "6000"},    {6, "0"},      {7, "1"},
          {8, "0"},     {9, "1"},     {10, "21"},    {11, "-24537"}, {12, "-42728"}, {13, "96417"}, {14, "137428"},
          {15, "47"},   {16, "0"},    {17, "0"},     {18, "0"},      {19, "1"},      {20, "0"},     {21, "4"},
          {22, "1.00"}, {23, "8000"}, {24, "12000"}, {25, "40"},     {26, "1200"},   {27, "0"},     {28, "0"},
          {29, "0"},    {30, "150"},  {31, "0"},     {32, "30"},     {33, "11"},     {34, "10000"}, {35, "0"},
          {36, "0"},    {38, "0"},    {39, "0"},     {40, "0"},      {41, "0"},      {42, "0"},     {46, "500"},
          {47, "500"},  {50, "0"}};
}

class Wf725Fixture : public ::testing::Test {
 protected:
  Wf725Fixture() {
    dir = fs::temp_directory_path() /
          ("wf725-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir);
    spec.device = "wf725-726";
    spec.file = (dir / "scenario.yaml").string();
    spec.line = 3;
  }
  ~Wf725Fixture() override { fs::remove_all(dir); }

  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  }
  /// Builds the controller from `md` and `programs` (text), binds a simulated axis.
  void start(const std::map<int, std::string>& md, const std::string& programs = {}) {
    std::string text;
    for (const auto& [n, v] : md) text += "MD " + std::to_string(n) + " = " + v + "\n";
    spec.parameters = write("md.txt", text);
    if (!programs.empty()) spec.programs = {write("progs.wf", programs)};
    ControllerRegistry r;
    register_wf725(r);
    auto c = r.create(spec);
    ASSERT_TRUE(c) << c.error().describe();
    ctl.reset(static_cast<Wf725Controller*>(c->release()));
    mocks::SimDriveConfig d;
    d.name = "sim:A";
    d.plant.kv_per_s = 200.0;
    d.plant.velocity_lag_s = 0.0;
    d.plant.velocity_feedforward = 1.0;
    axis = std::make_unique<motion::Axis>(ctl->axis_specs()[0].config, std::make_unique<mocks::SimDrive>(d));
    motion::Axis* ptr = axis.get();
    ASSERT_TRUE(ctl->bind_axes(std::span<motion::Axis* const>(&ptr, 1)));
    ctl->io().attach(inputs);
    every = static_cast<int>(ctl->cycle_period() / milliseconds(1));
  }
  /// Runs `d` of virtual time; `each` is called after every controller cycle (return true to stop).
  void run(Duration d, const std::function<bool()>& each = {}) {
    const auto end = now + d;
    while (now < end) {
      now += milliseconds(1);
      axis->update(CycleTime{now, milliseconds(1)});
      if (++tick % every == 0) {
        ctl->step(CycleTime{now, ctl->cycle_period()});
        if (each && each()) return;
      }
    }
  }
  /// Runs until `cond` holds after a controller cycle, at most `limit`. True when it held.
  bool run_until(const std::function<bool()>& cond, Duration limit = std::chrono::seconds(20)) {
    bool held = false;
    run(limit, [&] { return held = cond(); });
    return held;
  }

  // ---- the PLC side: whole DB words (read_db_word / write_db_word) ---------------------------
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
  /// Mode bits (DL 0) and submode (DR 0).
  void select(std::uint8_t mode_bit, db::Submode sub) {
    ctl->write_db_word(db::dw_mode,
                       static_cast<std::uint16_t>((1U << (mode_bit - 8)) << 8 | static_cast<unsigned>(sub)));
    run(milliseconds(12));
  }
  void traverse(db::Submode sub) { select(db::bit_mode_traversing, sub); }
  void drive_enable() {
    set_bit(db::dw_enable, db::bit_drive_enable, true);
    run(milliseconds(40));
  }
  /// Executes data code `code` with its parameters (rising edge of D 12.0), returns DD 18.
  std::int32_t data_code(std::uint16_t code, std::int32_t p1 = 0, std::int32_t p2 = 0) {
    ctl->write_db_word(db::dw_data_code, code);
    write_dd(db::dd_data_param1, p1);
    write_dd(db::dd_data_param2, p2);
    set_bit(db::dw_data_execute, 0, true);
    run(milliseconds(8));
    EXPECT_TRUE(bit(db::dw_data_status, 0)) << "data code done";
    const auto r = read_dd(db::dd_data_result);
    set_bit(db::dw_data_execute, 0, false);
    run(milliseconds(8));
    return r;
  }
  void pulse(int b) {
    set_bit(db::dw_control, b, true);
    run(milliseconds(8));
    set_bit(db::dw_control, b, false);
    run(milliseconds(8));
  }
  void start_pulse() { pulse(db::bit_start); }
  int error() const { return word(db::dw_error) & 0xFF; }
  int io_error() const { return word(db::dw_io_error); }
  std::int32_t actual() const { return read_dd(db::dd_actual); }
  double command_mm() const { return axis->status().command_position; }
  /// Synchronizes with "setting actual value" (MD 28) in traversing mode.
  void synchronize() {
    traverse(db::Submode::set_actual);
    drive_enable();
    start_pulse();
  }
  int count(int code) const {
    int n = 0;
    for (const auto& e : ctl->errors().history())
      if (e.code == code && e.catalogue == ctl->profile().catalogue("traversing")) ++n;
    return n;
  }

  /// Inputs driven from the test: X7 inputs by predicate on the axis.
  struct Inputs : IoSource {
    std::function<void(IoImage&)> fn;
    void read(TimePoint, IoImage& image) noexcept override {
      if (fn) fn(image);
    }
  };

  fs::path dir;
  ControllerSpec spec;
  std::unique_ptr<Wf725Controller> ctl;
  std::unique_ptr<motion::Axis> axis;
  Inputs inputs;
  TimePoint now{};
  int every = 4;
  long tick = 0;
};

}  // namespace hil::controllers::s5::test
