// SPDX-License-Identifier: MIT
// Cam tables and the cam coupling: interpolation through the points, continuity where the
// interpolation declares it (random tables, fixed seed), periodic continuation without drift,
// table switching at the table end and at a master position, distance-time cams, validation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hil/motion/cam.hpp"
#include "hil/motion/cam_table.hpp"
#include "hil/motion/master.hpp"

namespace hil::motion {
namespace {

CamTable make(const CamTableSpec& s) {
  auto t = CamTable::make(s);
  EXPECT_TRUE(t.has_value()) << t.error();
  return std::move(*t);
}

CamTableSpec random_spec(std::mt19937_64& rng, CamInterpolation ip, bool periodic, bool equidistant) {
  std::uniform_int_distribution<int> count(4, 40);
  std::uniform_real_distribution<double> dx(10.0, 500.0), dy(-300.0, 300.0);
  CamTableSpec s;
  s.interpolation = ip;
  s.periodic = periodic;
  const int n = count(rng);
  double x = 0, y = 0;
  for (int i = 0; i < n; ++i) {
    s.points.push_back({x, y});
    x += equidistant ? 100.0 : std::round(dx(rng));
    y += std::round(dy(rng));
  }
  if (ip == CamInterpolation::cubic_clamped) {
    s.start_slope = 0.5;
    s.end_slope = -0.25;
  }
  return s;
}

TEST(CamTable, PassesThroughEveryPoint) {
  std::mt19937_64 rng(3);
  for (auto ip : {CamInterpolation::linear, CamInterpolation::cubic_natural, CamInterpolation::cubic_clamped,
                  CamInterpolation::cubic_periodic}) {
    for (int k = 0; k < 50; ++k) {
      const auto spec = random_spec(rng, ip, ip == CamInterpolation::cubic_periodic || k % 2 == 0, k % 3 == 0);
      const CamTable t = make(spec);
      for (const auto& p : spec.points) ASSERT_NEAR(t.value(p.x), p.y, 1e-6 * (1 + std::fabs(p.y)));
    }
  }
}

TEST(CamTable, ContinuousWhereDeclared) {
  // At every knot: y continuous for all; y' and y'' continuous for the cubics (left and right
  // limits agree); periodic cubic: also across the seam (y'(0) = y'(X), y''(0) = y''(X)).
  std::mt19937_64 rng(11);
  for (auto ip : {CamInterpolation::linear, CamInterpolation::cubic_natural, CamInterpolation::cubic_clamped,
                  CamInterpolation::cubic_periodic}) {
    for (int k = 0; k < 200; ++k) {
      const auto spec = random_spec(rng, ip, ip == CamInterpolation::cubic_periodic, k % 2 == 0);
      const CamTable t = make(spec);
      const double eps = 1e-7;
      for (std::size_t i = 1; i + 1 < spec.points.size(); ++i) {
        const double x = spec.points[i].x;
        std::size_t h = 0;
        const CamSample l = t.sample(x - eps, h), r = t.sample(x + eps, h);
        ASSERT_NEAR(l.y, r.y, 1e-3) << to_string(ip) << " knot " << i;
        if (t.continuity() >= 1) {
          ASSERT_NEAR(l.dy, r.dy, 1e-5 * (1 + std::fabs(l.dy))) << to_string(ip);
        }
        if (t.continuity() >= 2) {
          ASSERT_NEAR(l.d2y, r.d2y, 1e-5 * (1 + std::fabs(l.d2y))) << to_string(ip);
        }
      }
      if (t.seam_continuity() >= 2) {
        std::size_t h = 0;
        const CamSample a = t.sample(0.0, h), b = t.sample(t.length(), h);
        ASSERT_NEAR(a.dy, b.dy, 1e-8 * (1 + std::fabs(a.dy)));
        ASSERT_NEAR(a.d2y, b.d2y, 1e-8 * (1 + std::fabs(a.d2y)));
      }
      if (ip == CamInterpolation::cubic_clamped) {
        std::size_t h = 0;
        ASSERT_NEAR(t.sample(0.0, h).dy, 0.5, 1e-9);
        ASSERT_NEAR(t.sample(t.length(), h).dy, -0.25, 1e-9);
      }
    }
  }
}

TEST(CamTable, LinearIsTheSfInterpolation) {
  // FIPW Y table over Xme = 20000: points 0, 1000, 4000, 6000 -> h = 20000/3.
  const CamTable t = make({{{0, 0}, {20000.0 / 3, 1000}, {40000.0 / 3, 4000}, {20000, 6000}}});
  EXPECT_NEAR(t.value(10000), 2500.0, 1e-9);
  EXPECT_NEAR(t.value(20000), 6000.0, 1e-9);
  EXPECT_DOUBLE_EQ(t.value(-5), 0.0);      // clamped
  EXPECT_DOUBLE_EQ(t.value(25000), 6000);  // clamped
}

TEST(CamTable, Validation) {
  EXPECT_FALSE(CamTable::make({{{0, 0}}}).has_value());
  EXPECT_FALSE(CamTable::make({{{0, 0}, {10, 1}, {10, 2}}}).has_value());
  EXPECT_FALSE(CamTable::make({{{1, 0}, {10, 1}}}).has_value());
  EXPECT_FALSE(CamTable::make({{{0, 5}, {10, 1}}}).has_value());
  EXPECT_FALSE(CamTable::make({{{0, 0}, {10, 1.5}}, CamInterpolation::linear, true}).has_value());
  EXPECT_FALSE(
      CamTable::make({{{0, 0}, {5, 1}, {7, 1}, {10, 1}}, CamInterpolation::cubic_periodic, false}).has_value());
  EXPECT_FALSE(CamTable::make({{{0, 0}, {10, NAN}}}).has_value());
  const auto e = CamTable::make({{{0, 0}, {10, 1}, {9, 2}}});
  ASSERT_FALSE(e.has_value());
  EXPECT_NE(e.error().find("point 2"), std::string::npos) << e.error();
}

TEST(CamCoupling, PeriodicContinuationIsExactOverManyPeriods) {
  // A feed cam: 20000 master inc per format, the slave advances 7777 inc per format.
  const CamTable t =
      make({{{0, 0}, {5000, 1000}, {15000, 6777}, {20000, 7777}}, CamInterpolation::cubic_periodic, true});
  CamCoupling c(&t);
  c.start(-3, 100);
  std::int64_t m = -3;
  for (int i = 0; i < 1'000'000; ++i) {
    m += 997;
    c.update(m);
  }
  const std::int64_t u = m + 3;
  const std::int64_t k = u / 20000, r = u % 20000;
  EXPECT_EQ(c.periods(), k);
  EXPECT_NEAR(c.slave_position(), 100 + static_cast<double>(k) * 7777 + t.value(static_cast<double>(r)), 1e-6);
}

TEST(CamCoupling, NonPeriodicHoldsAtTheEnds) {
  const CamTable t = make({{{0, 0}, {1000, 500}, {2000, 2000}}, CamInterpolation::cubic_clamped});
  CamCoupling c(&t);
  c.start(0, 0);
  c.update(5000);
  EXPECT_NEAR(c.slave_position(), 2000.0, 1e-9);
  EXPECT_DOUBLE_EQ(c.slope(), 0.0);
  c.update(-100);
  EXPECT_NEAR(c.slave_position(), 0.0, 1e-9);
}

TEST(CamCoupling, SwitchesAtTheTableEndAndAtAMasterPosition) {
  const CamTable in = make({{{0, 0}, {1000, 500}, {2000, 2000}}});  // coupling table
  const CamTable work = make({{{0, 0}, {1000, 1500}, {2000, 3000}}, CamInterpolation::linear, true});
  CamCoupling c(&in);
  c.start(0, 0);
  c.queue({&work, {}});
  std::int64_t m = 0;
  for (int i = 0; i < 30; ++i) {
    m += 300;  // crosses 2000 between 1800 and 2100
    c.update(m);
    if (m == 1800) {
      EXPECT_NEAR(c.slave_position(), 500 + 1500 * 0.8, 1e-9);
    }
  }
  EXPECT_EQ(c.switches(), 1);
  EXPECT_EQ(c.table(), &work);
  // At 9000: the coupling table gave 2000 up to master 2000, then 1.5 per increment.
  EXPECT_NEAR(c.slave_position(), 2000 + 1.5 * (9000 - 2000), 1e-9);
  c.queue({nullptr, 9500});  // stop (hold) at master 9500
  c.update(9400);
  c.update(9800);
  EXPECT_NEAR(c.slave_position(), 2000 + 1.5 * 7500, 1e-9);
  c.update(20000);
  EXPECT_NEAR(c.slave_position(), 2000 + 1.5 * 7500, 1e-9);
  EXPECT_TRUE(check_switch(work, work));
  EXPECT_FALSE(check_switch(work, in));  // 1.5 at the end of `work`, 0.5 at the start of `in`
}

TEST(CamCoupling, DistanceTimeCamRunsOnATimeMaster) {
  // 1 s of master time in 0.5 ms units (2000 units), slave 0 -> 10000 with rest at both ends.
  const CamTable t = make({{{0, 0}, {1000, 5000}, {2000, 10000}}, CamInterpolation::cubic_clamped});
  TimeMaster time(std::chrono::microseconds(500));
  CamCoupling c(&t);
  c.start(time.position(), 0);
  for (int i = 0; i < 1000; ++i) c.update(time.update(std::chrono::milliseconds(1)));
  EXPECT_NEAR(c.slave_position(), 10000.0, 1e-9);
}

}  // namespace
}  // namespace hil::motion
