// SPDX-License-Identifier: MIT
// The running IP247 module behind the RK512 data-block endpoint, on virtual time: MD and VP images
// (no overwrite, rejected images not stored, running program not deletable), the axis interface
// DX commands and status words, a limit switch raising 26 in the error byte.
#include <gtest/gtest.h>

#include "hil/controllers/s5/ip247_interface.hpp"
#include "hil/controllers/s5/ip247_module_endpoint.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"
#include "hil/controllers/s5/ip247_rack.hpp"

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

// `hilbridge emulate ip247` with several modules (docs/ip247.md, "Several modules on the line"): two
// modules of one rack, each its own endpoint with the same DB/DX mapping, hold an MD DB 1 and a
// program 10 of their own and run them independently; the PLC's DBs (DX 5..255) are the rack's;
// each module's state file text brings back its own images.
TEST(Ip247Rack, TwoModulesRunTheirProgramsIndependently) {
  EXPECT_FALSE(Ip247Rack::make({}));
  EXPECT_FALSE(Ip247Rack::make({Ip247ModuleOptions{.tile = 4}, Ip247ModuleOptions{.tile = 4}}));
  EXPECT_FALSE(Ip247Rack::make({Ip247ModuleOptions{.tile = 6}}));
  EXPECT_FALSE(Ip247Rack::make(std::vector<Ip247ModuleOptions>(9)));
  auto made = Ip247Rack::make({Ip247ModuleOptions{.tile = 0}, Ip247ModuleOptions{.tile = 4}});
  ASSERT_TRUE(made) << made.error();
  Ip247Rack rack = std::move(*made);
  ASSERT_EQ(rack.size(), 2U);
  EXPECT_EQ(rack.state_path("/s/ip247.json", 0), "/s/ip247-tile0.json");
  EXPECT_EQ(rack.state_path("/s/ip247.json", 1), "/s/ip247-tile4.json");
  hil::TimePoint now{};
  const auto run = [&](hil::Duration d) {
    for (const auto end = now + d; now < end;) {
      now += 1ms;
      for (std::size_t i = 0; i < rack.size(); ++i) rack.policy(i).on_time(now);
    }
  };
  run(1ms);
  const auto write = [&](std::size_t i, std::uint8_t db, const std::vector<std::uint16_t>& w) {
    return rack.policy(i).on_write(rack.endpoint(i).store(), db, 0, w);
  };
  const auto dx = [&](std::size_t i, std::uint8_t n, std::vector<std::uint16_t> w) {
    return rack.policy(i).on_write_dx(rack.endpoint(i).store(), n, 0, w);
  };
  const auto actual = [&](std::size_t i) {
    std::vector<std::uint16_t> s;
    EXPECT_EQ(rack.policy(i).on_read_dx(rack.endpoint(i).store(), 1, 0, 14, s), Rk512Error::ok);
    return static_cast<std::int32_t>((s[5] << 16) | s[6]);
  };
  Ip247MachineData md;
  md.limits_normally_closed = false;
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(write(i, 1, make_ip247_md_db(md)), Rk512Error::ok) << i;
  // Program 10 on each module, different texts: the same DB number is each module's own.
  EXPECT_EQ(write(0, 10, *make_ip247_vp_db({.db = 10, .text = "%10\nN10 X50 F3000\nN20 M02\n"})), Rk512Error::ok);
  EXPECT_EQ(write(1, 10, *make_ip247_vp_db({.db = 10, .text = "%10\nN10 X20 F1500\nN20 X-5 F1500\nN30 M02\n"})),
            Rk512Error::ok);
  EXPECT_EQ(write(1, 10, *make_ip247_vp_db({.db = 10, .text = "%10\nN10 M02\n"})), Rk512Error::db_exists);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(dx(i, 1, {0x0501, 0, 0, 0, 0x0001}), Rk512Error::ok);  // BA5 set at 0
  }
  run(10ms);
  EXPECT_EQ(dx(0, 1, {0x080A, 0, 0, 0, 0x0001}), Rk512Error::ok);  // BA8 program 10 on module 1 only
  run(300ms);
  EXPECT_GT(actual(0), 0);
  EXPECT_EQ(actual(1), 0) << "module 2 did not move";
  EXPECT_EQ(dx(1, 1, {0x080A, 0, 0, 0, 0x0001}), Rk512Error::ok);  // now module 2's own program 10
  run(300ms);
  EXPECT_GT(actual(1), 0);
  EXPECT_EQ(rack.policy(0).on_write(rack.endpoint(0).store(), 10, 0, {0}), Rk512Error::processing_not_possible)
      << "module 1 runs its program 10 (51)";
  run(20s);
  EXPECT_EQ(actual(0), 50'000);
  EXPECT_EQ(actual(1), -5'000);
  EXPECT_EQ(rack.policy(0).axis(1).m_output(), 2);
  EXPECT_EQ(rack.policy(1).axis(1).m_output(), 2);

  // The PLC's DBs are the rack's: DB 20 sent on module 1's line is module 2's Q-DB of a BA20 on its
  // axis 2 (SSNR 5 = tile 4 + axis 2 - 1).
  Ip247MachineData md2 = md;
  md2.db = 2;
  md2.axis = 2;
  EXPECT_EQ(dx(0, 20, make_ip247_md_db(md2)), Rk512Error::ok);
  EXPECT_EQ(dx(1, ip247_job_block_dx, {0, 20, 0, 2, 0, 5}), Rk512Error::ok);
  EXPECT_EQ(dx(1, ip247_job_block_dx, {20}), Rk512Error::ok);
  std::vector<std::uint16_t> job;
  EXPECT_EQ(rack.policy(1).on_read_dx(rack.endpoint(1).store(), ip247_job_block_dx, 0, 15, job), Rk512Error::ok);
  EXPECT_EQ(job[7], 0) << "MB250/MB251";
  EXPECT_TRUE(rack.policy(1).axis(2).machine_data());
  EXPECT_FALSE(rack.policy(0).axis(2).machine_data()) << "module 1 has no axis 2 set";
  EXPECT_TRUE(rack.endpoint(1).store().contains(2));
  EXPECT_FALSE(rack.endpoint(0).store().contains(2));

  // Each module's state (its images) comes back into a new rack, module by module.
  const std::string s0 = rack.endpoint(0).save_state(), s1 = rack.endpoint(1).save_state();
  auto again = Ip247Rack::make({Ip247ModuleOptions{.tile = 0}, Ip247ModuleOptions{.tile = 4}});
  ASSERT_TRUE(again);
  ASSERT_TRUE(again->load(0, s0));
  ASSERT_TRUE(again->load(1, s1));
  ASSERT_TRUE(again->policy(0).programs().find(10));
  ASSERT_TRUE(again->policy(1).programs().find(10));
  EXPECT_EQ(again->policy(0).programs().find(10)->blocks.size(), 2U);
  EXPECT_EQ(again->policy(1).programs().find(10)->blocks.size(), 3U);
  EXPECT_TRUE(again->policy(1).axis(2).machine_data());
  EXPECT_FALSE(again->policy(0).axis(2).machine_data());
}
