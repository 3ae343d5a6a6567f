// SPDX-License-Identifier: MIT
#pragma once
// Builds init and commanding DBs the way the manual prints them (DR/DL/DW/DD by address).
#include <gtest/gtest.h>

#include "hil/controllers/amkasyn/sf_runtime.hpp"

namespace hil::controllers::amkasyn::testing {

struct Init {
  DataBlock db{10};
  Init(int type, int number) {
    db.set_dr(0, static_cast<std::uint8_t>(type));
    db.set_dl(0, static_cast<std::uint8_t>(number));
  }
  Init& mode(int m) { return db.set_dr(1, static_cast<std::uint8_t>(m)), *this; }
  Init& factor(int f) { return db.set_dl(1, static_cast<std::uint8_t>(f)), *this; }
  Init& source(int address, int offset) {
    db.set_dl(2, static_cast<std::uint8_t>(address));
    db.set_dr(2, static_cast<std::uint8_t>(offset));
    return *this;
  }
  Init& sink(int address, int offset) {
    db.set_dl(3, static_cast<std::uint8_t>(address));
    db.set_dr(3, static_cast<std::uint8_t>(offset));
    return *this;
  }
  Init& in(int mask, int byte) {
    db.set_dr(4, static_cast<std::uint8_t>(mask));
    db.set_dl(4, static_cast<std::uint8_t>(byte));
    return *this;
  }
  Init& out(int mask, int byte) {
    db.set_dr(5, static_cast<std::uint8_t>(mask));
    db.set_dl(5, static_cast<std::uint8_t>(byte));
    return *this;
  }
  Init& tab(int k, int db_no) {
    if (k % 2 == 0)
      db.set_dr(static_cast<std::size_t>(6 + k / 2), static_cast<std::uint8_t>(db_no));
    else
      db.set_dl(static_cast<std::size_t>(6 + k / 2), static_cast<std::uint8_t>(db_no));
    return *this;
  }
};

/// A commanding DB: DR0 SF number, DL0 fct, DR1 code, DL1 BA.
inline DataBlock command(int sf, int fct, int code, int ba) {
  DataBlock c(34);
  c.set_dr(0, static_cast<std::uint8_t>(sf));
  c.set_dl(0, static_cast<std::uint8_t>(fct));
  c.set_dr(1, static_cast<std::uint8_t>(code));
  c.set_dl(1, static_cast<std::uint8_t>(ba));
  return c;
}

class SfTest : public ::testing::Test {
 protected:
  explicit SfTest(int id2_half_ms = 2) : rt(id2_half_ms, dbs) {}
  void init_ok(const Init& i) {
    const auto s = rt.init(i.db, image);
    ASSERT_FALSE(s.error) << s.text;
  }
  void start_ok(const DataBlock& c) {
    const auto s = rt.command(c, image);
    ASSERT_FALSE(s.error) << s.text;
    ASSERT_EQ(image.m[232], 0);
  }
  void cycles(int n) {
    for (int i = 0; i < n; ++i) rt.cycle(image);
  }
  DbStore dbs;
  ProcessImage image;
  SfRuntime rt;
};

}  // namespace hil::controllers::amkasyn::testing
