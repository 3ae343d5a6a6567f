// SPDX-License-Identifier: MIT
#pragma once
// A CLM1.4 on simulated drives for tests: the controller model, one hil::motion::Axis per CLM
// axis over a SimDrive (Kv loop), the parameter set from the profile's defaults plus the
// test's overrides, and a virtual clock advanced one NC cycle at a time.

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hil/controllers/clm14/controller.hpp"
#include "hil/controllers/clm14/motion_axis_port.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "hil/serial/clm14/device_data.hpp"

namespace hil::controllers::clm14::testing {

/// Parameters every rig uses unless overridden: linear axes of 10 IU per 1024-line encoder
/// revolution, Vmax 100 IU/s, 1000 IU/s², position reached on M2.00.0 within 0.01 IU.
inline std::map<std::string, std::string> base_parameters() {
  std::map<std::string, std::string> p;
  for (int ax = 1; ax <= 4; ++ax) {
    const auto n = [ax](int k) { return "A" + std::to_string(ax) + (k < 10 ? "0" : "") + std::to_string(k); };
    p[n(0)] = "1 0 0 0 0";
    p[n(1)] = "0010.00000";
    p[n(3)] = "-111111.111";
    p[n(4)] = "+100000.000";
    p[n(6)] = "000100.000";
    p[n(7)] = "000050.000";
    p[n(8)] = "001000";
    p[n(9)] = "000 000";
    p[n(10)] = "0.000";
    p[n(19)] = "01024 1024";
    p[n(20)] = "0 0 00 1";
    p[n(24)] = "00.00.0 +100 1";  // homing option 2 (marker only): HOM needs no switch
    p[n(27)] = ax == 1 ? "M2.00.0 0000.010" : "00.00.0 0000.010";
    p[n(29)] = "00.00.0 0.0 0000";
  }
  p["B011"] = "0000 0000 0";
  p["B012"] = "0000 0000";
  return p;
}

class Rig {
 public:
  using Overrides = std::initializer_list<std::pair<const std::string, std::string>>;
  explicit Rig(Overrides overrides = {}, int axes = 1, Options options = {}) : clm(options) {
    auto d = serial::clm14::load_device_data();
    EXPECT_TRUE(d.has_value()) << (d ? "" : d.error());
    data = *d;
    params = base_parameters();
    if (axes >= 2) params["B000"] = axes == 2 ? "1 0 0" : axes == 3 ? "1 1 0" : "1 1 1";
    for (auto& [k, v] : overrides) params[k] = v;
    clm.set_parameters([this](std::string_view n) {
      const auto it = params.find(std::string(n));
      if (it != params.end()) return it->second;
      return data->parameter_default(n);
    });
    auto settings = make_settings([this](std::string_view n) {
      const auto it = params.find(std::string(n));
      return it != params.end() ? it->second : data->parameter_default(n);
    });
    EXPECT_TRUE(settings.has_value()) << (settings ? "" : settings.error().message);
    for (int ax = 1; ax <= axes; ++ax) {
      mocks::SimDriveConfig dc;
      dc.name = "sim:" + std::to_string(ax);
      dc.plant.kv_per_s = 200.0;
      dc.plant.max_velocity_inc_per_s = 1e8;
      dc.plant.velocity_feedforward = 1.0;
      dc.homing_time = std::chrono::milliseconds(50);
      auto drive = std::make_unique<mocks::SimDrive>(dc);
      auto cfg = make_axis_config(settings->axes[static_cast<std::size_t>(ax - 1)], "a" + std::to_string(ax));
      auto v = motion::validate(cfg);
      EXPECT_TRUE(v.has_value()) << (v ? "" : v.error());
      motion_axes.push_back(std::make_unique<motion::Axis>(cfg, std::move(drive)));
      ports.push_back(std::make_unique<MotionAxisPort>(*motion_axes.back()));
      clm.attach_axis(ax, ports.back().get());
    }
    auto& im = clm.image();
    im.set_bit(sys::emergency_stop_ok, true);
    im.set_bit(sys::immediate_stop_ok, true);
    for (int ax = 0; ax < axes; ++ax) im.set_bit(sys::enable[static_cast<std::size_t>(ax)], true);
  }

  void program(const std::vector<std::pair<int, std::string>>& lines) {
    auto r = clm.load_program(lines);
    ASSERT_TRUE(r.has_value()) << r.error().message;
  }
  void cycle() {
    now += period;
    clm.cycle(now);
    for (auto& a : motion_axes) a->update(CycleTime{now, period});
    if (material) material->update(CycleTime{now, period});
  }
  /// Master encoder 1 (C000/C001/C002) on a simulated drive: a motion::Axis in IU whose
  /// increments are the encoder's quadrature counts - the material of a flying cutoff, the
  /// master of a FOL slave. It is enabled here; move it with material->move_velocity(...).
  motion::Axis& add_master_encoder() {
    auto settings = make_settings([this](std::string_view n) {
      const auto it = params.find(std::string(n));
      return it != params.end() ? it->second : data->parameter_default(n);
    });
    EXPECT_TRUE(settings.has_value());
    mocks::SimDriveConfig dc;
    dc.name = "sim:me1";
    dc.plant.kv_per_s = 200.0;
    dc.plant.max_velocity_inc_per_s = 1e8;
    dc.plant.velocity_feedforward = 1.0;
    auto cfg = master_encoder_config(settings->me1, settings->axes[0], "me1");
    auto v = motion::validate(cfg);
    EXPECT_TRUE(v.has_value()) << (v ? "" : v.error());
    material = std::make_unique<motion::Axis>(cfg, std::make_unique<mocks::SimDrive>(dc));
    encoder = std::make_unique<MotionMasterEncoder>(*material);
    clm.attach_master_encoder(encoder.get());
    (void)material->enable();
    return *material;
  }
  void run_for(Duration d) {
    const TimePoint end = now + d;
    while (now < end) cycle();
  }
  /// Run until `done()` or `limit` elapsed; returns whether done.
  template <class F>
  bool run_until(F done, Duration limit = std::chrono::seconds(60)) {
    const TimePoint end = now + limit;
    while (now < end) {
      cycle();
      if (done()) return true;
    }
    return false;
  }
  void set(const BitAddress& a, bool v) { clm.image().set_bit(a, v); }
  [[nodiscard]] bool get(const BitAddress& a) const { return clm.image().bit(a); }
  /// Select Automatic and give a Start edge.
  void start_auto() {
    enter_auto();
    pulse(sys::start);
  }
  void enter_auto() {
    run_for(std::chrono::milliseconds(20));  // power-up: the drives enable
    set(sys::automatic, true);
    cycle();
    cycle();
  }
  void pulse(const BitAddress& a) {
    set(a, true);
    cycle();
    set(a, false);
    cycle();
  }
  [[nodiscard]] double pos(int axis = 1) const { return clm.position(axis); }

  std::shared_ptr<const serial::clm14::DeviceData> data;
  std::map<std::string, std::string> params;
  Controller clm;
  std::vector<std::unique_ptr<motion::Axis>> motion_axes;
  std::vector<std::unique_ptr<MotionAxisPort>> ports;
  std::unique_ptr<motion::Axis> material;
  std::unique_ptr<MotionMasterEncoder> encoder;
  TimePoint now{};
  Duration period{std::chrono::milliseconds(2)};
};

inline BitAddress bit(std::string_view s) {
  auto b = parse_bit(s);
  EXPECT_TRUE(b.has_value()) << s;
  return b.value_or(BitAddress{});
}
inline ByteAddress byte(std::string_view s) {
  auto b = parse_byte(s);
  EXPECT_TRUE(b.has_value()) << s;
  return b.value_or(ByteAddress{});
}

}  // namespace hil::controllers::clm14::testing
