// SPDX-License-Identifier: MIT
// Fuzz target: the axis and the planner under arbitrary command streams. Bytes become commands
// with raw doubles (NaN, inf, huge, denormal) and cycles; the axis must never crash, hang or
// command beyond its limits, and planned profiles must end exactly on their targets.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "hil/motion/axis.hpp"
#include "hil/motion/plan.hpp"
#include "test_drive.hpp"

namespace {

using namespace hil::motion;

struct Reader {
  const std::uint8_t* p;
  std::size_t n;
  std::uint8_t byte() {
    if (n == 0) return 0;
    --n;
    return *p++;
  }
  double raw() {
    std::uint64_t b = 0;
    for (int i = 0; i < 8; ++i) b = (b << 8) | byte();
    double d;
    std::memcpy(&d, &b, sizeof d);
    return d;
  }
  double unit() { return static_cast<double>(byte() * 256 + byte()) / 65535.0; }  // [0, 1]
  double log_range(double lo_exp, double hi_exp) { return std::pow(10.0, lo_exp + (hi_exp - lo_exp) * unit()); }
};

#include <cstdio>
const std::uint8_t* g_data = nullptr;
std::size_t g_size = 0;
const bool g_trace = std::getenv("HIL_FUZZ_TRACE") != nullptr;
#define check(ok) check_at((ok), __LINE__)
void check_at(bool ok, int line) {
  if (!ok) {
    std::fprintf(stderr, "fuzz_motion: invariant at line %d broken\n", line);
    if (const char* dump = std::getenv("HIL_FUZZ_DUMP")) {
      if (std::FILE* f = std::fopen(dump, "wb")) {
        std::fwrite(g_data, 1, g_size, f);
        std::fclose(f);
      }
    }
    std::abort();
  }
}

void fuzz_planner(Reader& r) {
  Limits l{r.log_range(-3, 3), r.log_range(-3, 4), (r.byte() & 1) ? r.log_range(-2, 6) : INFINITY};
  Profile p;
  plan_rest_to_rest((r.unit() - 0.5) * 2e4, (r.unit() - 0.5) * 2e4, l, p);
  const State s = p.sample(r.unit() * p.duration());
  const double target = (r.unit() - 0.5) * 2e4;
  plan_position(s, target, l, p);
  check(std::isfinite(p.duration()));
  check(p.sample(p.duration() + 1.0).p == target);
  for (int i = 0; i <= 64; ++i) {
    const State x = p.sample(p.duration() * i / 64.0);
    check(std::fabs(x.v) <= l.velocity * (1 + 1e-6) + 1e-9);
    check(std::fabs(x.a) <= l.acceleration * (1 + 1e-6) + 1e-9);
  }
}

void fuzz_axis(Reader& r) {
  AxisConfig c;
  c.name = "fuzz";
  c.inc_per_unit = {static_cast<std::int64_t>(r.byte()) + 1, static_cast<std::int64_t>(r.byte()) + 1};
  c.rotary = r.byte() & 1;
  c.modulo = static_cast<double>(c.inc_per_unit.den) * 360.0;  // whole increments per turn
  c.limits = {100.0, 1000.0, (r.byte() & 1) ? 20000.0 : INFINITY};
  c.quick_stop_deceleration = 4000.0;
  c.jog_velocity = 10.0;
  c.following_error.static_window = 5.0;
  c.standstill_window = 1.0;
  c.in_position_window = 0.5;
  if (!c.rotary) {
    c.soft_limit_min = -50.0;
    c.soft_limit_max = 50.0;
  }
  c.backlash = r.unit();
  auto drive = std::make_unique<hil::motion::test::TestDrive>();
  auto* d = drive.get();
  Axis axis(c, std::move(drive));
  hil::TimePoint now{};
  const hil::Duration period = std::chrono::milliseconds(1);
  axis.update({now, period});
  axis.enable();
  bool pushed = false;
  double v_envelope = c.limits.velocity;  // highest velocity limit of any accepted move  // the actual position was
                                          // moved behind the axis' back
  while (r.n > 0) {
    const std::uint8_t op = r.byte();
    std::optional<Limits> lim;
    if (op & 0x80) lim = Limits{r.raw(), r.raw(), r.raw()};
    std::error_code ec;
    switch (op & 0x0f) {
      case 0:
        ec = axis.move_absolute(r.raw(), static_cast<Direction>(r.byte() % 3), lim);
        break;
      case 1:
        ec = axis.move_relative(r.raw(), lim);
        break;
      case 2:
        ec = axis.move_velocity(r.raw(), lim);
        break;
      case 3:
        ec = axis.jog(static_cast<int>(r.byte() % 3) - 1);
        break;
      case 4:
        ec = axis.stop();
        break;
      case 5:
        ec = axis.quick_stop();
        break;
      case 6:
        ec = axis.reset();
        break;
      case 7:
        ec = axis.enable();
        break;
      case 8:
        ec = axis.disable();
        break;
      case 9:
        ec = axis.home();
        break;
      case 10:
        d->follow = !d->follow;
        pushed = true;
        break;
      case 11:
        d->position += static_cast<std::int8_t>(r.byte());
        pushed = true;
        break;
      default:
        break;
    }
    if (g_trace) {
      std::fprintf(stderr, "op %d ec %d lim %s state %s\n", op & 0x0f, ec.value(), lim ? "custom" : "-",
                   to_string(axis.status().state));
      if (lim) std::fprintf(stderr, "  limits v %.17g a %.17g j %.17g\n", lim->velocity, lim->acceleration, lim->jerk);
    }
    if (!ec && lim && (op & 0x0f) <= 2) v_envelope = std::max(v_envelope, lim->velocity);
    const int cycles = r.byte();
    for (int i = 0; i < cycles; ++i) {
      axis.update({now += period, period});
      const AxisStatus& s = axis.status();
      if (g_trace) {
        std::fprintf(stderr, "  %s p %.9g v %.9g a %.9g fault %s\n", to_string(s.state), s.command_position,
                     s.command_velocity, s.command_acceleration, s.fault.describe().c_str());
      }
      check(std::isfinite(s.command_position) && std::isfinite(s.command_velocity));
      // Never faster than the highest velocity limit of any accepted move.
      check(std::fabs(s.command_velocity) <= v_envelope * (1 + 1e-6));
      if (!c.rotary && !pushed) check(s.command_position <= 50.0 + 1e-9 && s.command_position >= -50.0 - 1e-9);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  g_data = data;
  g_size = size;
  Reader r{data, size};
  if (r.byte() & 1)
    fuzz_planner(r);
  else
    fuzz_axis(r);
  return 0;
}
