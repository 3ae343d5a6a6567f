// SPDX-License-Identifier: MIT
// Property test on virtual time with a fixed seed: for random gear data (Z0, Z2, module, helix and
// lead angles, encoder resolutions), C follows the linkage equation within one increment over
// 10^7 cycles, for spur, helical axial feed and diagonal feed (issue: no drift over hours).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hil/controllers/elg/gear.hpp"

namespace elg = hil::controllers::elg;

namespace {

enum class Kind { spur, helical_axial, diagonal };

struct Case {
  elg::GearInput input;
  elg::GearMachineData md;
};

Case draw(std::mt19937_64& rng, Kind kind) {
  std::uniform_int_distribution<int> z0(-12, 12), z2(2, 999);
  std::uniform_int_distribution<std::int64_t> pulses(1000, 2000000);
  std::uniform_real_distribution<double> module(0.5, 12.0), helix(0.0, 45.0), lead(0.0, 8.0);
  const std::int64_t ms_choices[] = {100, 500, 1000};
  std::uniform_int_distribution<int> ms_pick(0, 2);
  for (;;) {
    Case c;
    c.input.z0 = z0(rng);
    if (c.input.z0 == 0) c.input.z0 = 1;
    c.input.z2 = z2(rng);
    c.md.n00 = pulses(rng);
    c.md.n02 = pulses(rng);
    c.md.ms_z_nm = ms_choices[ms_pick(rng)];
    c.md.ms_y_nm = ms_choices[ms_pick(rng)];
    const double m = module(rng);
    if (kind != Kind::spur) c.input.ud_z = elg::Decimal5::from_double(elg::ud_z_from_gear(helix(rng), m));
    if (kind == Kind::diagonal) c.input.ud_y = elg::Decimal5::from_double(elg::ud_y_from_gear(lead(rng), m));
    if (elg::compute_constants(c.input, c.md)) return c;  // else too large for the registers (2203): redraw
  }
}

void run(Kind kind, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const Case c = draw(rng, kind);
  const auto k = elg::compute_constants(c.input, c.md);
  ASSERT_TRUE(k);
  // Hob at 100..1000 rpm, Z feed 0.1..5 mm/s, Y shift 0..1 mm/s, 1 ms cycle, 10^7 cycles (2.8 h).
  std::uniform_real_distribution<double> rpm(100.0, 1000.0), feed(0.1, 5.0), shift(0.0, 1.0);
  const double b_per_cycle = rpm(rng) / 60.0 * 4.0 * static_cast<double>(c.md.n00) * 1e-3;
  const double z_per_cycle = feed(rng) * 1e6 / static_cast<double>(c.md.ms_z_nm) * 1e-3;
  const double y_per_cycle = kind == Kind::diagonal ? shift(rng) * 1e6 / static_cast<double>(c.md.ms_y_nm) * 1e-3 : 0.0;
  const std::int64_t b0 = 123456789, z0 = -4242, y0 = 17, c0 = 99;
  const elg::Linkage link(*k, b0, z0, y0, c0, true);

  // The reference evaluates the manual's equation in degrees, in long double, from the counts.
  const long double ms_b = 360.0L / (4.0L * static_cast<long double>(c.md.n00));
  const long double ms_c = 360.0L / (4.0L * static_cast<long double>(c.md.n02));
  const long double z2 = c.input.z2;
  const long double ud_z = static_cast<long double>(c.input.ud_z.e5) / 1e5L;
  const long double ud_y = static_cast<long double>(c.input.ud_y.e5) / 1e5L;
  double b_acc = 0, z_acc = 0, y_acc = 0;
  std::int64_t worst = 0;
  for (std::int64_t cycle = 1; cycle <= 10'000'000; ++cycle) {
    b_acc += b_per_cycle;
    z_acc += z_per_cycle;
    y_acc += y_per_cycle;
    const auto db = static_cast<std::int64_t>(b_acc), dz = static_cast<std::int64_t>(z_acc),
               dy = static_cast<std::int64_t>(y_acc);
    const auto set = link.c_set(b0 + db, z0 + dz, y0 + dy);
    ASSERT_TRUE(set) << "cycle " << cycle;
    const long double phi = static_cast<long double>(db) * ms_b * c.input.z0 / z2 +
                            static_cast<long double>(dz) * c.md.ms_z_nm * 1e-6L * ud_z / z2 +
                            static_cast<long double>(dy) * c.md.ms_y_nm * 1e-6L * ud_y / z2;
    const long double ideal = static_cast<long double>(c0) + phi / ms_c;
    const auto err = static_cast<std::int64_t>(std::llround(std::fabs(static_cast<long double>(*set) - ideal) * 2));
    worst = std::max(worst, err);
    ASSERT_LE(std::fabs(static_cast<long double>(*set) - ideal), 1.0L)
        << "cycle " << cycle << " Z0=" << c.input.z0 << " Z2=" << c.input.z2 << " N00=" << c.md.n00
        << " N02=" << c.md.n02;
  }
  // Rounded to the nearest count: never more than half a count off the ideal value.
  EXPECT_LE(worst, 1);
}

}  // namespace

TEST(ElgLinkageProperty, SpurFollowsWithinOneIncrementOver1e7Cycles) {
  run(Kind::spur, 0x5e1f);
}
TEST(ElgLinkageProperty, HelicalAxialFollowsWithinOneIncrementOver1e7Cycles) {
  run(Kind::helical_axial, 0xa1a1);
}
TEST(ElgLinkageProperty, DiagonalFollowsWithinOneIncrementOver1e7Cycles) {
  run(Kind::diagonal, 0xd1a9);
}
