// SPDX-License-Identifier: MIT
// IP247 operating modes on the step planner, virtual time (digest ip247.md §4.4-4.13): jog with
// limit switches and SW limits, reference set/approach, incremental absolute/relative (programmed
// speed reaches the pulse train), offsets BA12-16, automatic with M00 takeovers, interruption and
// continuation, external stop, teach-in, restart after power failure, rotary forced directions.
#include <gtest/gtest.h>

#include <functional>
#include <tuple>

#include "hil/controllers/s5/ip247_axis.hpp"

using namespace hil::controllers::s5;
using hil::stepdir::Ip247Error;
using C = Ip247Command;

namespace {

constexpr std::int64_t cycle_ns = 1'000'000;  // module cycle 1 ms

struct Rig {
  Ip247ProgramStore store;
  Ip247MachineData md;
  Ip247Axis axis{store, 1};
  std::int64_t now = 0;
  Ip247Inputs in;
  std::function<void(Ip247Inputs&, std::int64_t motor_pulses)> switches;
  std::vector<hil::gpio::Edge> edges;
  std::int64_t min_interval_ns = INT64_MAX;
  std::int64_t last_rise = -1;

  explicit Rig(bool load = true) {
    md.limits_normally_closed = false;  // NO switches: inputs 0 = not actuated
    md.sw_start = -400'000;
    md.sw_end = 4'000'000;
    md.zero_offsets = {40'000, 80'000, 120'000, -75'000};
    if (load) {
      EXPECT_EQ(axis.load_machine_data(md, 0), hil::stepdir::Ip247MdError::none);
    }
  }
  void cmd(int ba, C c, std::int64_t value = 0, std::int32_t speed = 0, int byte = 0) {
    axis.command({.ba = ba, .command = c, .byte_param = byte, .speed = speed, .value = value});
  }
  void step() {
    if (switches && axis.planner()) switches(in, axis.planner()->motor_position());
    edges.clear();
    axis.step(now, cycle_ns, in, &edges);
    for (const auto& e : edges) {
      if (e.line == 0 && e.level) {  // step line rising (positive edge)
        if (last_rise >= 0) min_interval_ns = std::min(min_interval_ns, e.t_ns - last_rise);
        last_rise = e.t_ns;
      }
    }
    now += cycle_ns;
  }
  /// Steps until `done` (or the time limit, seconds of module time).
  bool run(const std::function<bool()>& done, double max_s = 120.0) {
    const auto end = now + static_cast<std::int64_t>(max_s * 1e9);
    while (now < end) {
      step();
      if (done()) return true;
    }
    return false;
  }
  bool settle() {
    return run([&] { return !axis.running(); });
  }
};

}  // namespace

TEST(Ip247Axis, WithoutMachineDataOnlyBa4) {
  Rig r(false);
  EXPECT_TRUE(r.axis.attributes() & ip247_attr::md_missing);
  r.cmd(1, C::forward);
  EXPECT_EQ(r.axis.error(), 14);
  r.cmd(4, C::start);
  EXPECT_EQ(r.axis.error(), 0);
  Ip247MachineData bad = r.md;
  bad.pulses_per_rev = 5;
  EXPECT_EQ(r.axis.load_machine_data(bad, 0), static_cast<hil::stepdir::Ip247MdError>(5));
  EXPECT_EQ(r.axis.error(), 15);
}

TEST(Ip247Axis, IncrementalAbsoluteRunsAtTheProgrammedSpeed) {
  Rig r;
  r.cmd(6, C::start, 50'000, 1000);
  EXPECT_EQ(r.axis.error(), 10);  // reference point missing
  r.cmd(5, C::start, 0, 0, 1);    // set reference
  EXPECT_TRUE(r.axis.referenced());
  EXPECT_EQ(r.axis.actual(), 0);
  r.cmd(6, C::start, 50'000, 1000);
  EXPECT_TRUE(r.axis.running());
  EXPECT_FALSE(r.axis.attributes() & ip247_attr::finished);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.actual(), 50'000);
  EXPECT_TRUE(r.axis.position_reached());
  EXPECT_TRUE(r.axis.attributes() & ip247_attr::position_reached);
  EXPECT_EQ(r.axis.remaining(), 0);
  // 1000 mm/min at 10 µm/pulse = 1666.7 Hz: the shortest step interval is 1/f_v, not 1/fmax.
  EXPECT_GE(r.min_interval_ns, 599'000);
  EXPECT_LE(r.min_interval_ns, 601'000);
  r.min_interval_ns = INT64_MAX;
  r.last_rise = -1;
  r.cmd(6, C::start, 0, 0);  // speed 0 = MD incremental speed 3000 mm/min = fmax 5 kHz
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.actual(), 0);
  EXPECT_GE(r.min_interval_ns, 200'000);
  EXPECT_LE(r.min_interval_ns, 201'000);
  r.cmd(6, C::start, 5'000'000, 0);
  EXPECT_EQ(r.axis.error(), 23);  // outside the SW limits
  r.cmd(6, C::start, 100'000'000, 0);
  EXPECT_EQ(r.axis.error(), 62);
  r.cmd(7, C::forward, 10'000, 99'999);  // above vmax: clamped, warning 7, still moves
  EXPECT_EQ(r.axis.error(), 7);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.actual(), 10'000);
}

TEST(Ip247Axis, ZeroOffsetVectors) {
  // vectors ip247.md 13: 100 mm backward, then set reference (coordinate 0) -> actual 100 mm.
  Rig r;
  r.cmd(13, C::backward, 100'000);
  r.cmd(5, C::start, 0, 0, 1);
  EXPECT_EQ(r.axis.actual(), 100'000);
  // vectors 15: BA13 -50 mm backward == 50 mm forward; BA13 10 mm forward at 0 -> -10 mm.
  Rig a, b;
  a.cmd(13, C::backward, -50'000);
  b.cmd(13, C::forward, 50'000);
  EXPECT_EQ(a.axis.actual(), b.axis.actual());
  EXPECT_EQ(a.axis.actual(), -50'000);
  Rig c;
  c.cmd(13, C::forward, 10'000);
  EXPECT_EQ(c.axis.actual(), -10'000);
  c.cmd(12, C::start, 400'000);  // set actual value
  EXPECT_EQ(c.axis.actual(), 400'000);
  c.cmd(14, C::start);
  EXPECT_EQ(c.axis.actual(), 0);
  c.cmd(15, C::forward, 30'000);
  EXPECT_EQ(c.axis.actual(), 30'000);
  c.cmd(15, C::backward, -80'000);  // sign multiplied in: 80 mm forward
  EXPECT_EQ(c.axis.actual(), 80'000);
  c.cmd(16, C::start);
  EXPECT_EQ(c.axis.actual(), 0);
  c.cmd(12, C::start, 100'000'000);
  EXPECT_EQ(c.axis.error(), 62);
}

TEST(Ip247Axis, DrillExampleWithToolOffset) {
  // §4.3.8: BA6 50, BA15 100 forward, BA6 200, BA16, BA6 50.
  Rig r;
  r.cmd(5, C::start, 0, 0, 1);
  r.cmd(6, C::start, 50'000);
  ASSERT_TRUE(r.settle());
  r.cmd(15, C::forward, 100'000);
  EXPECT_EQ(r.axis.actual(), 150'000);
  r.cmd(6, C::start, 200'000);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.actual(), 200'000);
  EXPECT_EQ(r.axis.internal_position(), 100'000);  // the holder aims lower by the tool length
  r.cmd(16, C::start);
  r.cmd(6, C::start, 50'000);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.actual(), 50'000);
}

TEST(Ip247Axis, ZeroOffsetProgramOnTheAxis) {
  // §2.6.6.7 / vectors ip247.md 11: -130 mm after G74, -10 mm after the end.
  Rig r;
  r.md.zero_offsets = {40'000, 80'000, 120'000, 0};
  ASSERT_EQ(r.axis.delete_machine_data(), Ip247Error::none);
  ASSERT_EQ(r.axis.load_machine_data(r.md, 0), hil::stepdir::Ip247MdError::none);
  ASSERT_EQ(r.store.write(1,
                          "%1 Hauptprogramm\nN1 L9\nN2 X40.000 F500\nN3 G54\nN4 L9\nN5 X40.000 F500\nN6 G55\n"
                          "N7 L9\nN8 X40.000 F500\nN9 G56\nN10 G74\nN11 M02\n"),
            Ip247Error::none);
  ASSERT_EQ(r.store.write(9,
                          "L9 Unterprogramm\nN1 X0 F100 M10\nN2 G04 F50\nN3 X10 F100\nN4 G04 F50\nN5 X20 F100\n"
                          "N6 G04 F50\nN7 M02\n"),
            Ip247Error::none);
  r.cmd(5, C::start, 0, 0, 1);
  r.cmd(13, C::forward, 10'000);
  EXPECT_EQ(r.axis.actual(), -10'000);
  r.cmd(6, C::start, 0);
  ASSERT_TRUE(r.settle());
  r.cmd(8, C::start, 0, 0, 1);
  ASSERT_TRUE(r.axis.running());
  EXPECT_EQ(r.store.erase(1), Ip247Error::program_active);
  std::int64_t last_running = 0;
  ASSERT_TRUE(r.run(
      [&] {
        if (r.axis.running()) last_running = r.axis.actual();
        return !r.axis.running();
      },
      600));
  EXPECT_EQ(r.axis.error(), 0);
  EXPECT_EQ(last_running, -130'000);
  EXPECT_EQ(r.axis.actual(), -10'000);
  EXPECT_EQ(r.axis.m_history(), (std::vector<int>{255, 10, 2}));
  EXPECT_EQ(r.store.erase(1), Ip247Error::none);
}

TEST(Ip247Axis, M00NeedsThreeTakeoversAndSingleBlockSteps) {
  Rig r;
  ASSERT_EQ(r.store.write(2, "%2\nN10 X100 F1000 M00\nN15 M00\nN20 G56 M00\nN25 G43 X200 F100 M02\n"),
            Ip247Error::none);
  r.cmd(5, C::start, 0, 0, 1);
  r.cmd(8, C::start, 0, 0, 2);
  int takeovers = 0;
  ASSERT_TRUE(r.run([&] {
    if (r.axis.waits_for_takeover()) {
      ++takeovers;
      r.cmd(8, C::takeover);
    }
    return !r.axis.running();
  }));
  EXPECT_EQ(takeovers, 3);
  EXPECT_EQ(r.axis.takeovers(), 3);
  // X200 was reached with G56 (Z = -120 mm) and G43 (T = +2.3 mm): p = 200 + 120 - 2.3 mm. At the end the
  // program zero offset is removed (x = p + T = 320 mm); the tool offset stays.
  EXPECT_EQ(r.axis.internal_position(), 317'700);
  EXPECT_EQ(r.axis.actual(), 320'000);
  EXPECT_EQ(r.axis.offsets().tool_prog, 2'300);
  EXPECT_EQ(r.axis.m_history(), (std::vector<int>{255, 0, 2}));
  // Wrong command while waiting: takeover with another BA aborts with error 2.
  ASSERT_EQ(r.store.write(3, "%3\nN10 X0 F1000\nN20 X10 F1000\nN30 M02\n"), Ip247Error::none);
  r.cmd(9, C::start, 0, 0, 3);
  ASSERT_TRUE(r.run([&] { return r.axis.waits_for_takeover(); }));
  r.cmd(9, C::takeover);
  ASSERT_TRUE(r.run([&] { return r.axis.waits_for_takeover(); }));
  EXPECT_TRUE(r.axis.position_reached());
  r.cmd(8, C::takeover);
  EXPECT_EQ(r.axis.error(), 2);
  EXPECT_TRUE(r.settle());
}

TEST(Ip247Axis, InterruptionAndContinuation) {
  Rig r;
  ASSERT_EQ(r.store.write(4, "%4\nN10 X300 F3000 M10\nN20 X0 F3000 M20\nN30 M02\n"), Ip247Error::none);
  r.cmd(5, C::start, 0, 0, 1);
  r.cmd(8, C::start, 0, 0, 4);
  ASSERT_TRUE(r.run([&] { return r.axis.actual() > 100'000; }));
  r.cmd(8, C::stop);
  EXPECT_EQ(r.axis.error(), 65);
  ASSERT_TRUE(r.settle());
  EXPECT_TRUE(r.axis.interrupted());
  EXPECT_FALSE(r.axis.position_reached());
  EXPECT_GT(r.axis.remaining(), 0);
  EXPECT_EQ(r.axis.remaining() + r.axis.actual(), 300'000);
  EXPECT_EQ(r.axis.m_output(), 10);
  r.cmd(8, C::takeover);  // continue at the interruption point
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.actual(), 0);
  EXPECT_EQ(r.axis.m_history(), (std::vector<int>{255, 10, 20, 2}));
  // Start after an interruption restarts from the first block; a second Stop aborts.
  r.cmd(8, C::start, 0, 0, 4);
  ASSERT_TRUE(r.run([&] { return r.axis.actual() > 50'000; }));
  r.cmd(8, C::stop);
  ASSERT_TRUE(r.settle());
  r.cmd(8, C::stop);
  EXPECT_FALSE(r.axis.interrupted());
  EXPECT_EQ(r.store.erase(4), Ip247Error::none);
}

TEST(Ip247Axis, LimitSwitchAbortsAndLocksTheDirection) {
  Rig r;
  // NO switch "end" actuated from 20 mm (2000 pulses) on.
  r.switches = [](Ip247Inputs& in, std::int64_t p) { in.limit_end = p >= 2'000; };
  r.cmd(1, C::forward);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.error(), 26);
  EXPECT_GE(r.axis.actual(), 20'000);
  EXPECT_TRUE(r.axis.attributes() & ip247_attr::finished);
  const auto at = r.axis.actual();
  r.cmd(1, C::forward);  // locked
  EXPECT_EQ(r.axis.error(), 26);
  EXPECT_FALSE(r.axis.running());
  EXPECT_EQ(r.axis.actual(), at);
  r.cmd(7, C::backward, 30'000);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.error(), 0);
  r.cmd(7, C::forward, 1'000);  // released while moving back: unlocked
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.error(), 0);
  // NC switches: a broken wire (input 0) is an overrun.
  Rig nc(false);
  nc.md.limits_normally_closed = true;
  ASSERT_EQ(nc.axis.load_machine_data(nc.md, 0), hil::stepdir::Ip247MdError::none);
  nc.in.limit_start = true;
  nc.in.limit_end = false;
  nc.cmd(1, C::forward);
  nc.step();
  nc.step();
  EXPECT_EQ(nc.axis.error(), 26);
}

TEST(Ip247Axis, NoPulsesWhileBbIsLow) {
  // BB low (the power section off, or a step/dir drive still in its reset pulse): a job that would
  // output pulses is refused with error 53 and not a single pulse goes out; once BB is high the
  // same job runs. Before, the module pulsed into a drive that could not take them, and a retrofit
  // follower anchored later lost them (the machine axis ended short by the pulses of that time).
  Rig r;
  r.in.ready = false;
  r.step();
  const std::int64_t p0 = r.axis.planner()->motor_position();
  for (const auto& [ba, c, byte] : {std::tuple{7, C::forward, 0}, std::tuple{1, C::backward, 0},
                                    std::tuple{5, C::start, 0}, std::tuple{8, C::start, 1}}) {
    r.cmd(ba, c, 1'000, 0, byte);
    EXPECT_EQ(r.axis.error(), 53) << "BA" << ba;
    EXPECT_FALSE(r.axis.running()) << "BA" << ba;
    for (int i = 0; i < 50; ++i) r.step();
    EXPECT_EQ(r.axis.planner()->motor_position(), p0) << "BA" << ba;
  }
  r.cmd(5, C::start, 0, 0, 1);  // set reference: no pulses, allowed
  EXPECT_EQ(r.axis.error(), 0);
  r.in.ready = true;
  r.step();
  r.cmd(7, C::forward, 1'000);
  EXPECT_EQ(r.axis.error(), 0);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.planner()->motor_position(), p0 + 100);  // 1000 um at 10 um/pulse
}

TEST(Ip247Axis, SoftwareLimitBrakesFromTheLimit) {
  Rig r;
  r.cmd(5, C::start, 0, 0, 1);
  r.cmd(6, C::start, 3'990'000);
  ASSERT_TRUE(r.settle());
  r.cmd(1, C::forward);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.error(), 29);
  EXPECT_GT(r.axis.actual(), 4'000'000);  // overshoot up to the braking distance
  r.cmd(2, C::backward);
  ASSERT_TRUE(r.run([&] { return r.axis.actual() < 3'000'000; }));
  r.cmd(2, C::stop);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.error(), 0);
}

TEST(Ip247Axis, ExternalStopAndStart) {
  Rig r;
  r.cmd(7, C::forward, 500'000);
  r.run([&] { return r.axis.actual() > 10'000; });
  r.in.external_stop = true;
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.error(), 27);
  r.cmd(7, C::forward, 10'000);  // input still 1: the job waits for the falling edge (message 6)
  EXPECT_EQ(r.axis.error(), 6);
  const auto at = r.axis.actual();
  for (int k = 0; k < 50; ++k) r.step();
  EXPECT_EQ(r.axis.actual(), at);
  r.in.external_stop = false;
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.actual(), at + 10'000);
}

TEST(Ip247Axis, TeachInRecordsAProgram) {
  // §4.3.4 example (incremental speed 2500 mm/min).
  Rig r(false);
  r.md.incremental_speed = 2500;
  ASSERT_EQ(r.axis.load_machine_data(r.md, 0), hil::stepdir::Ip247MdError::none);
  r.cmd(5, C::start, 0, 0, 1);
  r.cmd(10, C::start, 0, 0, 7);
  EXPECT_TRUE(r.axis.teach_in());
  EXPECT_TRUE(r.axis.attributes() & ip247_attr::teach_in);
  r.cmd(7, C::forward, 1'258'250);
  ASSERT_TRUE(r.settle());
  r.cmd(7, C::takeover);
  EXPECT_EQ(r.axis.error(), 3);  // block stored
  r.cmd(6, C::start, 3'000'000);
  ASSERT_TRUE(r.settle());
  r.cmd(6, C::takeover);
  r.cmd(8, C::start, 0, 0, 1);
  EXPECT_EQ(r.axis.error(), 30);  // only jog/incremental in teach-in
  r.cmd(11, C::start);
  EXPECT_FALSE(r.axis.teach_in());
  ASSERT_NE(r.store.text(7), nullptr);
  EXPECT_EQ(*r.store.text(7), "%  7\nN1 X1258.250 F2500\nN2 X3000.000 F2500\nN3 M02\n");
  r.cmd(10, C::start, 0, 0, 7);
  EXPECT_EQ(r.axis.error(), 49);  // the number is used
}

TEST(Ip247Axis, RestartAfterPowerFailure) {
  Rig r;
  r.md.reference_coordinate = 5'000;
  ASSERT_EQ(r.axis.delete_machine_data(), Ip247Error::none);
  ASSERT_EQ(r.axis.load_machine_data(r.md, 0), hil::stepdir::Ip247MdError::none);
  r.cmd(5, C::start, 0, 0, 1);
  r.cmd(13, C::forward, 1'000);
  r.cmd(7, C::forward, 100'000);
  r.run([&] { return r.axis.actual() > 20'000; });
  r.axis.power_restart(true);
  EXPECT_EQ(r.axis.error(), 8);
  EXPECT_FALSE(r.axis.referenced());
  EXPECT_EQ(r.axis.ba(), 4);
  EXPECT_EQ(r.axis.actual(), 5'000 - 1'000);  // reference coordinate, offsets kept
  r.axis.power_restart(false);
  EXPECT_TRUE(r.axis.attributes() & ip247_attr::md_missing);
}

TEST(Ip247Axis, RotaryForcedDirectionIsAFullRevolution) {
  Rig r(false);
  r.md.unit = Ip247Unit::degree;
  r.md.rotary = true;
  r.md.sw_start = 0;
  r.md.sw_end = 360'000;
  r.md.gear_bu_per_rev = 360'000;
  r.md.pulses_per_rev = 400;  // 900 m°/pulse
  r.md.fmax_hz = 5'000;
  r.md.jog1 = r.md.jog2 = r.md.incremental_speed = r.md.reference_speed = 60'000;
  r.md.reference_coordinate = 0;
  r.md.tool_offset = 0;
  ASSERT_EQ(r.axis.load_machine_data(r.md, 0), hil::stepdir::Ip247MdError::none);
  r.cmd(5, C::start, 0, 0, 1);
  r.cmd(6, C::forward, 0);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.internal_position(), 360'000);  // one revolution forward
  EXPECT_EQ(r.axis.actual(), 0);
  r.cmd(6, C::start, 360'000);  // shortest path: 360 == 0, no motion
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.internal_position(), 360'000);
  r.cmd(6, C::backward, 270'000);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.internal_position(), 270'000);
  r.cmd(6, C::start, 90'000);  // tie (180 each way): forward
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.internal_position(), 450'000);
  EXPECT_EQ(r.axis.actual(), 90'000);
  r.cmd(12, C::start, 400'000);  // 90 -> 400: the range becomes 310..670
  EXPECT_EQ(r.axis.actual(), 400'000);
  r.cmd(6, C::start, 0);
  EXPECT_EQ(r.axis.error(), 23);
  // vectors ip247.md 7: 0 and 360 are both valid targets; a range of 400..800 degrees is legal.
  Rig w(false);
  w.md = r.md;
  w.md.sw_start = 400'000;
  w.md.sw_end = 800'000;
  w.md.reference_coordinate = 400'000;
  EXPECT_EQ(w.axis.load_machine_data(w.md, 0), hil::stepdir::Ip247MdError::none);
  w.md.sw_end = 300'000;
  Ip247ProgramStore s2;
  Ip247Axis bad(s2, 1);
  EXPECT_EQ(bad.load_machine_data(w.md, 0), static_cast<hil::stepdir::Ip247MdError>(21));
}

TEST(Ip247Axis, ReferenceApproachWithCamAndLimit) {
  Rig r;  // reference direction backward (MD 20h); away = forward
  r.md.reference_speed = 1200;
  // cam between -10 mm and -5 mm, limit end at +100 mm (physical pulses, 10 µm/pulse)
  r.switches = [](Ip247Inputs& in, std::int64_t p) {
    in.reference = p >= -1'000 && p <= -500;
    in.limit_end = p >= 10'000;
  };
  r.cmd(5, C::start);
  ASSERT_TRUE(r.settle());
  EXPECT_EQ(r.axis.error(), 0);
  EXPECT_TRUE(r.axis.referenced());
  EXPECT_EQ(r.axis.actual(), r.md.reference_coordinate);
  EXPECT_EQ(r.axis.planner()->motor_position(), -1'001);  // first pulse off the cam in the reference direction
  // A cam that is never left: error 59 after 2500 single steps.
  Rig bad;
  bad.switches = [](Ip247Inputs& in, std::int64_t) { in.reference = true; };
  bad.step();  // on the cam at the start (special case 3): leave it in single steps
  bad.cmd(5, C::start);
  ASSERT_TRUE(bad.settle());
  EXPECT_EQ(bad.axis.error(), 59);
  EXPECT_FALSE(bad.axis.referenced());
}
