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
  EXPECT_EQ(m.policy.on_write_dx(m.store, 4, 0, {0}), Rk512Error::db_missing);
}
