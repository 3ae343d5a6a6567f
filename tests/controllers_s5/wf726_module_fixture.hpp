// SPDX-License-Identifier: MIT
#pragma once
// The axes A, B (and C) of one WF 726 (Wf726Module) on simulated drives, stepped on virtual time
// (1 ms run period, the controllers at their cycle), each commanded through its own DB axis.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/controllers/s5/wf726_module.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "wf725_fixture.hpp"

namespace hil::controllers::s5::test {

class Wf726ModuleFixture : public ::testing::Test {
 public:
  Wf726ModuleFixture() {
    dir = fs::temp_directory_path() /
          ("wf726-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir);
  }
  ~Wf726ModuleFixture() override { fs::remove_all(dir); }

  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  }
  /// Builds the axes `letters` of one module from `md` (per letter; base_md() when missing),
  /// the programs (text) stored through the first axis.
  void start(const std::string& letters, const std::string& programs,
             std::map<char, std::map<int, std::string>> md = {}, const std::string& module = "WF726A") {
    for (const char l : letters) {
      const auto& m = md.contains(l) ? md[l] : (md[l] = base_md());
      std::string text;
      for (const auto& [n, v] : m) text += "MD " + std::to_string(n) + " = " + v + "\n";
      ControllerSpec spec;
      spec.device = "wf725-726";
      spec.file = (dir / "scenario.yaml").string();
      spec.parameters = write(std::string("md-") + l + ".txt", text);
      if (ctls.empty() && !programs.empty()) spec.programs = {write("progs.wf", programs)};
      spec.options["axis"] = std::string(1, l);
      spec.options["db"] = std::to_string(10 + (l - 'A'));
      spec.options["module"] = module;
      ControllerRegistry r;
      register_wf725(r);
      auto c = r.create(spec);
      ASSERT_TRUE(c) << c.error().describe();
      ctls.emplace_back(static_cast<Wf725Controller*>(c->release()));
      mocks::SimDriveConfig d;
      d.name = std::string("sim:") + l;
      d.plant.kv_per_s = 200.0;
      d.plant.velocity_lag_s = 0.0;
      d.plant.velocity_feedforward = 1.0;
      axes.push_back(
          std::make_unique<motion::Axis>(ctls.back()->axis_specs()[0].config, std::make_unique<mocks::SimDrive>(d)));
      motion::Axis* ptr = axes.back().get();
      ASSERT_TRUE(ctls.back()->bind_axes(std::span<motion::Axis* const>(&ptr, 1)));
      ASSERT_TRUE(module_.add(*ctls.back()));
    }
    every = static_cast<int>(ctls.front()->cycle_period() / milliseconds(1));
  }
  [[nodiscard]] std::size_t index(char l) const {
    for (std::size_t i = 0; i < ctls.size(); ++i)
      if (ctls[i]->axis_letter() == l) return i;
    ADD_FAILURE() << "no axis " << l;
    return 0;
  }
  Wf725Controller& c(char l) { return *ctls[index(l)]; }
  motion::Axis& ax(char l) { return *axes[index(l)]; }

  void run(Duration d, const std::function<bool()>& each = {}) {
    const auto end = now + d;
    while (now < end) {
      now += milliseconds(1);
      for (auto& a : axes) a->update(CycleTime{now, milliseconds(1)});
      if (++tick % every == 0) {
        for (auto& k : ctls) k->step(CycleTime{now, k->cycle_period()});
        if (each && each()) return;
      }
    }
  }
  bool run_until(const std::function<bool()>& cond, Duration limit = std::chrono::seconds(30)) {
    bool held = false;
    run(limit, [&] { return held = cond(); });
    return held;
  }

  // ---- the PLC side of axis l ------------------------------------------------------------------
  std::uint16_t word(char l, std::uint16_t w) { return c(l).read_db_word(w); }
  bool bit(char l, std::uint16_t w, int b) { return ((word(l, w) >> b) & 1) != 0; }
  void set_bit(char l, std::uint16_t w, int b, bool on) {
    const auto v = word(l, w);
    c(l).write_db_word(w, static_cast<std::uint16_t>(on ? (v | (1U << b)) : (v & ~(1U << b))));
  }
  void traverse(char l, db::Submode sub) {
    c(l).write_db_word(db::dw_mode, static_cast<std::uint16_t>((1U << (db::bit_mode_traversing - 8)) << 8 |
                                                               static_cast<unsigned>(sub)));
    run(milliseconds(12));
  }
  void pulse(char l, int b) {
    set_bit(l, db::dw_control, b, true);
    run(milliseconds(12));
    set_bit(l, db::dw_control, b, false);
    run(milliseconds(12));
  }
  /// Synchronizes (set actual value MD 28 = 0), drive enabled, leaves the axis in `sub`.
  void ready(char l, db::Submode sub) {
    traverse(l, db::Submode::set_actual);
    set_bit(l, db::dw_enable, db::bit_drive_enable, true);
    run(milliseconds(40));
    pulse(l, db::bit_start);
    traverse(l, sub);
  }
  /// Starts program `n` on axis `l` in automatic.
  void start_program(char l, int n) {
    c(l).write_db_word(db::dw_program, static_cast<std::uint16_t>(n));
    pulse(l, db::bit_start);
  }
  /// Data code 800C (acknowledge) on axis l.
  void acknowledge(char l) {
    c(l).write_db_word(db::dw_data_code, db::code::acknowledge);
    set_bit(l, db::dw_data_execute, 0, true);
    run(milliseconds(12));
    set_bit(l, db::dw_data_execute, 0, false);
    run(milliseconds(12));
  }
  int error(char l) { return word(l, db::dw_error) & 0xFF; }
  std::int32_t actual(char l) {
    return static_cast<std::int32_t>((static_cast<std::uint32_t>(word(l, db::dd_actual)) << 16) |
                                     word(l, static_cast<std::uint16_t>(db::dd_actual + 1)));
  }
  bool program_active(char l) { return bit(l, db::dw_flags, 1); }
  bool moving(char l) {
    const auto s = ax(l).status().state;
    return s == motion::AxisState::moving || s == motion::AxisState::stopping;
  }

  fs::path dir;
  std::vector<std::unique_ptr<Wf725Controller>> ctls;
  std::vector<std::unique_ptr<motion::Axis>> axes;
  Wf726Module module_;
  TimePoint now{};
  int every = 6;
  long tick = 0;
};

}  // namespace hil::controllers::s5::test
