// SPDX-License-Identifier: MIT
// IP247 calculators and PLC-side encodings against the worked examples of vectors/ip247.md
// (items 1, 3, 5, 19, 27, 29), the calculator also through `hilbridge profile calc ip247`.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

#include "hil/controllers/s5/ip247_calc.hpp"
#include "hil/controllers/s5/ip247_interface.hpp"

using namespace hil::controllers::s5;

TEST(Ip247Calc, ManualVectors) {
  // 1: a 200-step motor (1.8 degree) in half step -> 400 pulses/rev.
  auto r = ip247_calculate({.step_angle_deg = 1.8, .half_step = true});
  EXPECT_DOUBLE_EQ(*r.get("pulses_per_rev"), 400.0);
  // 3: lead 4 mm/rev, 400 pulses/rev -> 10 um/pulse.
  r = ip247_calculate({.pulses_per_rev = 400, .gear_um_per_rev = 4000});
  EXPECT_DOUBLE_EQ(*r.get("resolution"), 10.0);
  // 5: jog 3600 mm/min, 500 pulses/rev, 1 mm/rev -> 30 kHz.
  r = ip247_calculate({.pulses_per_rev = 500, .gear_um_per_rev = 1000, .speed_per_min = 3600});
  EXPECT_NEAR(*r.get("frequency"), 30'000.0, 1e-6);
  // 27 [derived]: same drive, fss 1 kHz, a 100 Hz/ms -> F 30526.3 Hz, tau 305.26 ms,
  // braking 20 017 pulses = 40.03 mm.
  r = ip247_calculate(
      {.pulses_per_rev = 500, .gear_um_per_rev = 1000, .speed_per_min = 3600, .fss_hz = 1000, .accel_hz_per_ms = 100});
  EXPECT_NEAR(*r.get("F"), 30'526.3, 0.05);
  EXPECT_NEAR(*r.get("tau"), 305.26, 0.005);
  EXPECT_DOUBLE_EQ(*r.get("braking_distance"), 20'017.0);
  EXPECT_NEAR(*r.get("braking_distance_bu"), 40'034.0, 0.5);
  EXPECT_TRUE(r.problems.empty());
  // 29 [derived]: pulse width bound 5 us at 100 kHz, 31 us (cap) at 5 kHz.
  EXPECT_DOUBLE_EQ(*ip247_calculate({.fmax_hz = 100'000}).get("pulse_width_max"), 5.0);
  EXPECT_DOUBLE_EQ(*ip247_calculate({.fmax_hz = 5'000}).get("pulse_width_max"), 31.0);
  // Rotary reproducibility: 360 degrees at 0.9 degree/pulse, 400 pulses/rev -> 1 revolution.
  r = ip247_calculate({.pulses_per_rev = 400, .gear_um_per_rev = 360'000, .range_bu = 360'000});
  EXPECT_DOUBLE_EQ(*r.get("reference_reproducible"), 1.0);
  r = ip247_calculate({.pulses_per_rev = 400, .gear_um_per_rev = 360'000, .range_bu = 400'000});
  EXPECT_DOUBLE_EQ(*r.get("reference_reproducible"), 0.0);
  EXPECT_FALSE(ip247_calculate({.pulses_per_rev = 5}).problems.empty());
}

TEST(Ip247Interface, BcdAndBinaryEncodings) {
  // vectors ip247.md 19 (§6.2.7.2).
  EXPECT_EQ(encode_ip247_dd(120'000, false), 0x0001D4C0u);
  EXPECT_EQ(encode_ip247_dd(120'000, true), 0x00120000u);
  EXPECT_EQ(encode_ip247_dd(-120'000, false), 0xFFFE2B40u);
  EXPECT_EQ(encode_ip247_dd(-120'000, true), 0xF0120000u);
  EXPECT_EQ(encode_ip247_speed(1000, false), (Ip247SpeedWord{0x03E8, 0}));
  EXPECT_EQ(encode_ip247_speed(1000, true), (Ip247SpeedWord{0x1000, 0}));
  EXPECT_EQ(encode_ip247_speed(10000, false), (Ip247SpeedWord{0x2710, 0}));
  EXPECT_EQ(encode_ip247_speed(10000, true), (Ip247SpeedWord{0x1000, 1}));
  EXPECT_EQ(decode_ip247_dd(0xF0120000u, true), -120'000);
  EXPECT_EQ(decode_ip247_dd(0xFFFE2B40u, false), -120'000);
  EXPECT_EQ(decode_ip247_dd(0x0012A000u, true).error(), hil::stepdir::Ip247Error::path_not_bcd);
  EXPECT_EQ(decode_ip247_speed({0x1000, 1}, true), 10'000);
  EXPECT_EQ(decode_ip247_speed({0x10F0, 0}, true).error(), hil::stepdir::Ip247Error::speed_not_bcd);
  EXPECT_FALSE(encode_ip247_dd(10'000'000, true));
}

TEST(Ip247Interface, AxisDbCommandsAndStatus) {
  Ip247ProgramStore store;
  Ip247Axis axis(store, 1);
  Ip247MachineData md;
  md.limits_normally_closed = false;
  ASSERT_EQ(axis.load_machine_data(md, 0), hil::stepdir::Ip247MdError::none);
  std::vector<std::uint16_t> db(ip247_axis_db_words, 0);
  EXPECT_FALSE(take_ip247_job(db, false));
  db[0] = 0x0501;  // BA5, byte 1 = set reference
  db[4] = 0x0001;  // Start
  auto job = take_ip247_job(db, false);
  ASSERT_TRUE(job && *job);
  axis.command(**job);
  write_ip247_status(db, axis, false);
  EXPECT_EQ(db[4], 0);  // handshake: the job was taken
  EXPECT_EQ(db[12] >> 8, axis.attributes());
  EXPECT_FALSE((db[12] >> 8) & ip247_attr::reference_missing);
  db[0] = 0x0700;
  db[1] = 0;
  db[2] = 0x0000;
  db[3] = 0x2710;  // 10 000 um
  db[4] = 0x0004;  // Vorwärts
  job = take_ip247_job(db, false);
  ASSERT_TRUE(job && *job);
  EXPECT_EQ((*job)->ba, 7);
  EXPECT_EQ((*job)->command, Ip247Command::forward);
  EXPECT_EQ((*job)->value, 10'000);
  db[3] = 0x00AB;
  EXPECT_EQ(take_ip247_job(db, true)->error(), hil::stepdir::Ip247Error::path_not_bcd);
}

namespace {
std::string hilbridge(const std::string& args, int& status) {
  const std::string cmd = std::string(HIL_HILBRIDGE) + " " + args + " 2>&1";
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p)) out += buf.data();
  const int st = ::pclose(p);
  status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return out;
}
}  // namespace

TEST(Ip247Calc, ProfileCalcCommandPrintsTheFigures) {
  int status = -1;
  auto out =
      hilbridge("profile calc ip247 --pulses-per-rev 500 --gear 1000 --speed 3600 --fss 1000 --accel 100", status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("30526.3"), std::string::npos) << out;
  EXPECT_NE(out.find("305.263"), std::string::npos) << out;
  EXPECT_NE(out.find("20017"), std::string::npos) << out;
  EXPECT_NE(out.find("enter in MD DD n+5"), std::string::npos) << out;
  out = hilbridge("profile calc ip247 --step-angle 1.8 --half-step --gear 4000", status);
  EXPECT_EQ(status, 0);
  EXPECT_NE(out.find("400"), std::string::npos);
  out = hilbridge("profile calc ip247 --pulses-per-rev 5", status);
  EXPECT_EQ(status, 1);
  EXPECT_NE(out.find("MD error 5"), std::string::npos);
  out = hilbridge("profile calc nosuch --pulses-per-rev 5", status);
  EXPECT_EQ(status, 2);
}
