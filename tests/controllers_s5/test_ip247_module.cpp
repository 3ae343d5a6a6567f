// SPDX-License-Identifier: MIT
// The running IP247 module behind the RK512 data-block endpoint, on virtual time: MD and VP images
// (no overwrite, rejected images not stored, running program not deletable), the axis interface
// DX commands and status words, a limit switch raising 26 in the error byte.
#include <gtest/gtest.h>

#include "hil/controllers/s5/ip247_interface.hpp"
#include "hil/controllers/s5/ip247_module_endpoint.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"

using namespace hil::controllers::s5;
using hil::serial::s5::Rk512Error;
using namespace std::chrono_literals;

namespace {
struct Module {
  Ip247ModulePolicy policy;
  hil::mocks::legacy::DbStore store;
  hil::TimePoint now{};
  explicit Module(Ip247ModuleOptions o) : policy(o) { policy.on_time(now); }
  void run(hil::Duration d) {
    const auto end = now + d;
    while (now < end) {
      now += 1ms;
      policy.on_time(now);
    }
  }
  Rk512Error dx(std::vector<std::uint16_t> w) { return policy.on_write_dx(store, 1, 0, w); }
  std::vector<std::uint16_t> status() {
    std::vector<std::uint16_t> out;
    EXPECT_EQ(policy.on_read_dx(store, 1, 0, 14, out), Rk512Error::ok);
    return out;
  }
};
}  // namespace

TEST(Ip247Module, ImagesCommandsAndStatus) {
  Ip247ModuleOptions o;
  o.switches[0].limit_end_at = 6'000;  // pulses = 60 mm
  Module m(o);
  Ip247MachineData md;
  md.limits_normally_closed = false;
  EXPECT_EQ(m.policy.on_write(m.store, 1, 0, make_ip247_md_db(md)), Rk512Error::ok);
  EXPECT_EQ(m.policy.on_write(m.store, 1, 0, make_ip247_md_db(md)), Rk512Error::db_exists);
  Ip247MachineData bad = md;
  bad.db = 2;  // the image's own DB number must be the one it is written to (else rk512:9)
  bad.axis = 2;
  bad.fss_hz = 20'000;
  EXPECT_EQ(m.policy.on_write(m.store, 2, 0, make_ip247_md_db(bad)), Rk512Error::image_rejected);
  EXPECT_NE(m.policy.last_rejection().find("MD error 22"), std::string::npos) << m.policy.last_rejection();
  EXPECT_FALSE(m.store.contains(2));

  auto vp = make_ip247_vp_db({.db = 10, .text = "%10\nN10 X50 F3000 M10\nN20 G04 F2\nN30 X0 F3000 M20\nN40 M02\n"});
  EXPECT_EQ(m.policy.on_write(m.store, 10, 0, *vp), Rk512Error::ok);
  auto faulty = make_ip247_vp_db({.db = 11, .text = "%11\nN10 X1 F10 M100\nN20 M02\n"});
  EXPECT_EQ(m.policy.on_write(m.store, 11, 0, *faulty), Rk512Error::image_rejected);
  EXPECT_NE(m.policy.last_rejection().find("syntax error 17 in block N10"), std::string::npos);
  EXPECT_FALSE(m.store.contains(11));

  EXPECT_EQ(m.dx({0x0501, 0, 0, 0, 0x0001}), Rk512Error::ok);                              // BA5 set
  EXPECT_EQ(m.dx({0x080A, 0, 0, 0, 0x0001}), Rk512Error::ok);                              // BA8 program 10 start
  EXPECT_EQ(m.policy.on_write(m.store, 10, 0, {0}), Rk512Error::processing_not_possible);  // running (51)
  m.run(500ms);
  auto s = m.status();
  EXPECT_EQ(s[4], 0);                 // command taken
  EXPECT_EQ(s[11], (8 << 8) | 10);    // BA8, M10
  EXPECT_FALSE((s[12] >> 8) & 0x80);  // running
  const auto actual = static_cast<std::int32_t>((s[5] << 16) | s[6]);
  EXPECT_GT(actual, 0);
  EXPECT_LT(actual, 50'000);
  m.run(10s);
  s = m.status();
  EXPECT_TRUE((s[12] >> 8) & 0x80);
  EXPECT_EQ(s[11] & 0xFF, 2);
  EXPECT_EQ((s[5] << 16) | s[6], 0);
  EXPECT_EQ(m.policy.on_write(m.store, 10, 0, {0}), Rk512Error::ok);  // delete after the run

  EXPECT_EQ(m.dx({0x0700, 0, 0x0001, 0x86A0, 0x0004}), Rk512Error::ok);  // BA7 forward 100 mm
  m.run(10s);
  s = m.status();
  EXPECT_EQ(s[12] & 0xFF, 26);
  EXPECT_GE(static_cast<std::int32_t>((s[5] << 16) | s[6]), 60'000);
  EXPECT_EQ(m.dx({0x0700, 0, 0, 0x00AB, 0x0004}), Rk512Error::ok);  // binary MD: any value is a number
  EXPECT_EQ(m.policy.on_write_dx(m.store, 0, 0, {0}), Rk512Error::db_missing);
}

TEST(Ip247Module, DataJobsThroughTheJobBlockDx4) {
  Module m({});
  Ip247MachineData md;
  md.limits_normally_closed = false;
  std::vector<std::uint16_t> out;
  // The PLC's DB 20 (DX 20) holds an MD image for DB 1 (axis 1); BA20 on tile 0 (axis 1).
  EXPECT_EQ(m.policy.on_write_dx(m.store, 20, 0, make_ip247_md_db(md)), Rk512Error::ok);
  const auto job = [&](std::vector<std::uint16_t> w) {
    EXPECT_EQ(m.policy.on_write_dx(m.store, ip247_job_block_dx, 1, {w.begin() + 1, w.end()}), Rk512Error::ok);
    EXPECT_EQ(m.policy.on_write_dx(m.store, ip247_job_block_dx, 0, {w[0]}), Rk512Error::ok);  // BA last
    EXPECT_EQ(m.policy.on_read_dx(m.store, ip247_job_block_dx, 0, 15, out), Rk512Error::ok);
    return out;
  };
  auto r = job({20, 20, 0, 1, 0, 0});
  EXPECT_EQ(r[0], 0);  // done
  EXPECT_EQ(r[6], 0) << "flags";
  EXPECT_EQ(r[7], 0) << "MB250/MB251";
  EXPECT_EQ(r[9], 70) << "words";
  ASSERT_TRUE(m.policy.axis(1).machine_data());
  EXPECT_TRUE(m.store.contains(1));  // the endpoint's DB 1 mirrors the module's MD image
  // BA20 again: MB250 7 (a set is there).
  r = job({20, 20, 0, 1, 0, 0});
  EXPECT_EQ(r[7] >> 8, 7);
  EXPECT_EQ(r[6], 2) << "PAFE";
  // BA22 on an axis tile: 46; on the data channel (tile 3): stored, readable as DB 10.
  auto vp = make_ip247_vp_db({.db = 10, .text = "%10\nN10 X5 F3000\nN20 M02\n"});
  EXPECT_EQ(m.policy.on_write_dx(m.store, 21, 0, *vp), Rk512Error::ok);
  r = job({22, 21, 0, 10, 0, 0});
  EXPECT_EQ(r[7] & 0xFF, 46);
  EXPECT_EQ(r[6] & 1, 1) << "BFEH";
  r = job({22, 21, 0, 10, 0, 3});
  EXPECT_EQ(r[7], 0);
  EXPECT_EQ(m.policy.on_read(m.store, 10, 0, 1, out), Rk512Error::ok);
  EXPECT_EQ(out[0], (*vp)[0]);
  // BA70 SYS-ID into the PLC's DB 30 from DW 2: 'IP' '24' '7 ' ...
  r = job({70, 0, 0, 30, 2, 3});
  EXPECT_EQ(r[7], 8 << 8) << "DB 30 does not exist in the PLC yet";
  EXPECT_EQ(m.policy.on_write_dx(m.store, 30, 0, std::vector<std::uint16_t>(12, 0)), Rk512Error::ok);
  r = job({70, 0, 0, 30, 2, 3});
  EXPECT_EQ(r[7], 0);
  EXPECT_EQ(r[9], 9);
  EXPECT_EQ(m.policy.on_read_dx(m.store, 30, 2, 3, out), Rk512Error::ok);
  EXPECT_EQ(out[0], ('I' << 8) | 'P');
  EXPECT_EQ(out[1], ('2' << 8) | '4');
  // BA5 set at 0, BA7 forward 10 mm through DX 1, then BA66 actual values while it moves.
  EXPECT_EQ(m.dx({0x0501, 0, 0, 0, 0x0001}), Rk512Error::ok);
  m.run(10ms);
  EXPECT_EQ(m.dx({0x0700, 0, 0, 10'000, 0x0004}), Rk512Error::ok);
  m.run(100ms);
  r = job({66, 0, 0, 30, 0, 0});
  EXPECT_EQ(r[7], 0);
  EXPECT_EQ(m.policy.on_read_dx(m.store, 30, 0, 6, out), Rk512Error::ok);
  const auto actual = static_cast<std::int32_t>((out[0] << 16) | out[1]);
  const auto remaining = static_cast<std::int32_t>((out[4] << 16) | out[5]);
  EXPECT_GT(actual, 0);
  EXPECT_LT(actual, 10'000);
  EXPECT_EQ(actual + remaining, 10'000);
  // BA23 of program 10 on the data channel: DB 10 goes from the endpoint's store too.
  r = job({23, 0, 0, 10, 0, 3});
  EXPECT_EQ(r[7], 0);
  EXPECT_FALSE(m.store.contains(10));
  EXPECT_EQ(m.policy.on_read_dx(m.store, 4, 10, 10, out), Rk512Error::target_too_small);
}
