// SPDX-License-Identifier: MIT
// Property tests of the planner on sampled time (fixed seed): limits never exceeded, targets
// reached exactly, rest-to-rest duration equal to an independently computed optimum.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hil/motion/plan.hpp"

namespace hil::motion {
namespace {

constexpr double kDt = 0.001;
constexpr double kTol = 1e-9;

struct Sampled {
  double max_v = 0, max_a = 0, max_j = 0, arrival = 0;
};

// Samples every cycle (and checks continuity); returns the observed maxima.
Sampled sample_profile(const Profile& p, double horizon) {
  Sampled s;
  std::size_t hint = 0;
  State prev = p.sample(0.0, hint);
  const int n = static_cast<int>(std::ceil(horizon / kDt)) + 2;
  for (int i = 1; i <= n; ++i) {
    const double t = i * kDt;
    const State st = p.sample(t, hint);
    s.max_v = std::max(s.max_v, std::fabs(st.v));
    s.max_a = std::max(s.max_a, std::fabs(st.a));
    s.max_j = std::max(s.max_j, std::fabs(st.a - prev.a) / kDt);
    prev = st;
  }
  return s;
}

Limits random_limits(std::mt19937_64& rng, bool jerk) {
  std::uniform_real_distribution<double> lv(0.01, 3.0), la(0.05, 30.0), lj(0.5, 3000.0);
  Limits l;
  l.velocity = std::exp(lv(rng)) - 0.9;
  l.acceleration = std::exp(la(rng) / 10.0) * la(rng);
  l.jerk = jerk ? lj(rng) * l.acceleration : std::numeric_limits<double>::infinity();
  return l;
}

// Independent optimum for rest-to-rest: bisection on the peak velocity. The ramp from rest to vp
// has jerk phases t_j = min(A/J, sqrt(vp/J)) and a hold of (vp - J t_j^2)/(J t_j); by symmetry it
// covers vp * T / 2.
double reference_duration(double d, const Limits& l) {
  const auto ramp_time = [&](double vp) {
    if (!std::isfinite(l.jerk)) return vp / l.acceleration;
    const double tj = std::min(l.acceleration / l.jerk, std::sqrt(vp / l.jerk));
    const double hold = (vp - l.jerk * tj * tj) / (l.jerk * tj);
    return 2.0 * tj + std::max(0.0, hold);
  };
  const auto dist = [&](double vp) { return vp * ramp_time(vp); };  // both ramps
  double vp = l.velocity;
  if (dist(vp) > d) {
    double lo = 0.0, hi = l.velocity;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (dist(mid) > d ? hi : lo) = mid;
    }
    vp = 0.5 * (lo + hi);
  }
  return 2.0 * ramp_time(vp) + (d - dist(vp)) / vp;
}

void expect_within(const Sampled& s, const Limits& l, bool check_jerk = true) {
  EXPECT_LE(s.max_v, l.velocity * (1 + kTol) + 1e-12);
  EXPECT_LE(s.max_a, l.acceleration * (1 + kTol) + 1e-12);
  if (check_jerk && l.jerk_limited()) {
    EXPECT_LE(s.max_j, l.jerk * (1 + 1e-6));
  }
}

TEST(RestToRest, RandomMovesRespectLimitsReachTargetAndAreTimeOptimal) {
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> pos(-500.0, 500.0);
  std::uniform_real_distribution<double> small(-0.01, 0.01);
  for (int i = 0; i < 3000; ++i) {
    const bool jerk = i % 4 != 0;
    const Limits l = random_limits(rng, jerk);
    const double from = pos(rng);
    const double to = (i % 3 == 0) ? from + small(rng) : pos(rng);  // include tiny moves (no a, no v reached)
    Profile p;
    plan_rest_to_rest(from, to, l, p);
    const double ref = reference_duration(std::fabs(to - from), l);
    ASSERT_NEAR(p.duration(), ref, 1e-9 * std::max(1.0, ref)) << "move " << i;
    ASSERT_NEAR(rest_to_rest_duration(to - from, l), ref, 1e-9 * std::max(1.0, ref));
    if (ref > 60.0) continue;  // keep sampling cheap
    const Sampled s = sample_profile(p, p.duration());
    SCOPED_TRACE(testing::Message() << "move " << i << " from " << from << " to " << to << " v " << l.velocity << " a "
                                    << l.acceleration << " j " << l.jerk);
    expect_within(s, l, true);
    // Sampled arrival: the first cycle at which the set-point is the target, within one cycle of the optimum.
    const auto arrival_cycle = static_cast<long>(std::ceil(p.duration() / kDt - 1e-9));
    EXPECT_LE(std::fabs(static_cast<double>(arrival_cycle) * kDt - ref), kDt + 1e-12);
    const State end = p.sample(static_cast<double>(arrival_cycle) * kDt);
    EXPECT_EQ(end.p, to);
    EXPECT_EQ(end.v, 0.0);
  }
}

TEST(RestToRest, KnownCasesAllSevenPhases) {
  const Limits l{1.0, 2.0, 10.0};
  // V reached and A reached: T_ramp = 1/2 + 2/10 = 0.7 covering 0.35 each side -> 0.7 for 2 ramps.
  EXPECT_NEAR(rest_to_rest_duration(2.0, l), 1.4 + 1.3, 1e-12);
  // A reached, V not: vp^2/A + vp A/J = d, d = 0.3 -> vp = 0.6 (0.18 + 0.12); T = 2 (0.3 + 0.2)
  EXPECT_NEAR(rest_to_rest_duration(0.3, l), 1.0, 1e-12);
  // Neither: d = 2 J t^3 with t = 0.1 -> d = 0.02, T = 4 t
  EXPECT_NEAR(rest_to_rest_duration(0.02, l), 0.4, 1e-12);
  Profile p;
  plan_rest_to_rest(0.0, 2.0, l, p);
  EXPECT_EQ(p.segments().size(), 7u);
  EXPECT_EQ(p.end().p, 2.0);
}

TEST(RestToRest, TrapezoidWhenJerkInfinite) {
  const Limits l{2.0, 4.0, std::numeric_limits<double>::infinity()};
  Profile p;
  plan_rest_to_rest(1.0, 11.0, l, p);
  EXPECT_NEAR(p.duration(), 10.0 / 2.0 + 2.0 / 4.0, 1e-12);
  EXPECT_EQ(p.segments().size(), 3u);
  const Sampled s = sample_profile(p, p.duration());
  expect_within(s, l, false);
  EXPECT_NEAR(p.sample(0.25).v, 1.0, 1e-12);  // a = 4 from t = 0
  plan_rest_to_rest(0.0, 0.25, l, p);         // triangle: vp = sqrt(d A) = 1
  EXPECT_NEAR(p.duration(), 0.5, 1e-12);
}

// A reachable state: somewhere along a random rest-to-rest or velocity profile.
State random_state(std::mt19937_64& rng, const Limits& l) {
  std::uniform_real_distribution<double> pos(-100.0, 100.0), frac(0.0, 1.0);
  Profile p;
  if (frac(rng) < 0.7) {
    plan_rest_to_rest(pos(rng), pos(rng), l, p);
  } else {
    State s{pos(rng), 0, 0, 0};
    plan_velocity(s, (2 * frac(rng) - 1) * l.velocity, l, p);
  }
  return p.sample(frac(rng) * p.duration());
}

TEST(Replan, NewTargetWhileMovingRespectsLimitsAndEndsExactly) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-100.0, 100.0), frac(0.0, 1.0);
  for (int i = 0; i < 3000; ++i) {
    const Limits l = random_limits(rng, i % 5 != 0);
    const State s = random_state(rng, l);
    // Half the targets near the braking point, to hit the "decelerating, target just ahead" branch.
    const double sp = stop_position(s, l);
    const double target = i % 2 ? pos(rng) : sp + (frac(rng) - 0.5) * 0.2 * std::fabs(sp - s.p);
    Profile p;
    plan_position(s, target, l, p);
    SCOPED_TRACE(testing::Message() << "case " << i << " p " << s.p << " v " << s.v << " a " << s.a << " -> "
                                    << target);
    ASSERT_TRUE(std::isfinite(p.duration()));
    if (p.duration() > 80.0) continue;
    const Sampled smp = sample_profile(p, p.duration());
    expect_within(smp, l, true);
    const State end = p.sample(p.duration() + kDt);
    EXPECT_EQ(end.p, target);
    EXPECT_EQ(end.v, 0.0);
    // Continuous at the start: the new profile starts in the old state.
    const State st = p.sample(0.0);
    EXPECT_EQ(st.p, s.p);
    EXPECT_EQ(st.v, s.v);
    EXPECT_EQ(st.a, s.a);
    // The profile is continuous: no jump between consecutive samples beyond V dt.
    std::size_t h = 0;
    double prev = p.sample(0.0, h).p;
    for (double t = kDt; t < p.duration() + kDt; t += kDt) {
      const double now = p.sample(t, h).p;
      ASSERT_LE(std::fabs(now - prev), l.velocity * kDt * (1 + 1e-9) + 1e-12);
      prev = now;
    }
  }
}

TEST(Replan, LowerLimitsWhileMovingEnterThemUnderTheOldOnes) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pos(-100.0, 100.0), k(0.1, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const Limits old_l = random_limits(rng, true);
    const State s = random_state(rng, old_l);
    const Limits new_l{old_l.velocity * k(rng), old_l.acceleration * k(rng), old_l.jerk * k(rng)};
    Profile p;
    const double target = pos(rng);
    if (i % 2)
      plan_position(s, target, new_l, old_l, p);
    else
      plan_velocity(s, (k(rng) - 0.55) * 2 * new_l.velocity, new_l, old_l, p);
    SCOPED_TRACE(testing::Message() << "case " << i);
    // Never beyond the old limits; once the acceleration is back inside the new limit and the
    // velocity too, never beyond the new ones again.
    std::size_t h = 0;
    bool inside = false;
    State prev = p.sample(0.0, h);
    for (double t = kDt; t < p.duration() + 2 * kDt; t += kDt) {
      const State st = p.sample(t, h);
      ASSERT_LE(std::fabs(st.v), old_l.velocity * (1 + 1e-9));
      ASSERT_LE(std::fabs(st.a), old_l.acceleration * (1 + 1e-9));
      ASSERT_LE(std::fabs(st.a - prev.a) / kDt, old_l.jerk * (1 + 1e-6));
      if (inside) {
        ASSERT_LE(std::fabs(st.v), new_l.velocity * (1 + 1e-9));
        ASSERT_LE(std::fabs(st.a), new_l.acceleration * (1 + 1e-9));
      }
      if (std::fabs(st.a) <= 1e-9 && std::fabs(st.v) <= new_l.velocity * (1 + 1e-9)) inside = true;
      prev = st;
    }
    if (i % 2) {
      EXPECT_EQ(p.end().p, target);
    }
  }
}

TEST(Replan, TargetJustBeyondTheBrakingPointSlowsWithoutStopping) {
  const Limits l{1.0, 2.0, 10.0};
  Profile decel;
  plan_rest_to_rest(0.0, 3.0, l, decel);
  const State s = decel.sample(decel.duration() - 0.4);  // braking: v > 0, a < 0
  ASSERT_GT(s.v, 0.0);
  ASSERT_LT(s.a, 0.0);
  const double target = 3.05;  // a little beyond where it would stop
  Profile p;
  plan_position(s, target, l, p);
  EXPECT_EQ(p.end().p, target);
  const Sampled smp = sample_profile(p, p.duration());
  expect_within(smp, l);
  for (double t = kDt; t < p.duration() - kDt; t += kDt) ASSERT_GT(p.sample(t).v, 0.0) << t;  // never stops on the way
  // Faster than braking to rest and starting again.
  Profile stop_and_go;
  plan_velocity(s, 0.0, l, stop_and_go);
  EXPECT_LT(p.duration(), stop_and_go.duration() + rest_to_rest_duration(target - stop_and_go.end().p, l));
}

TEST(Replan, FromRestEqualsTimeOptimal) {
  const Limits l{1.0, 2.0, 10.0};
  Profile a, b;
  plan_position(State{1.0, 0, 0, 0}, 4.0, l, a);
  plan_rest_to_rest(1.0, 4.0, l, b);
  EXPECT_DOUBLE_EQ(a.duration(), b.duration());
}

TEST(Replan, ReversalBrakesThenReturns) {
  const Limits l{1.0, 2.0, 10.0};
  const State s{0.0, 1.0, 0.0, 0.0};  // cruising forward at V
  Profile p;
  plan_position(s, -1.0, l, p);  // target behind
  const Sampled smp = sample_profile(p, p.duration());
  expect_within(smp, l);
  double max_p = 0;
  for (double t = 0; t < p.duration(); t += kDt) max_p = std::max(max_p, p.sample(t).p);
  // Reverses without stopping at a = 0 first, so it turns no later than the braking point.
  EXPECT_LE(max_p, stop_position(s, l) + 1e-12);
  EXPECT_GT(max_p, 0.3);
  EXPECT_EQ(p.end().p, -1.0);
}

TEST(Stop, FromAnyStateWithinLimits) {
  std::mt19937_64 rng(99);
  for (int i = 0; i < 2000; ++i) {
    const Limits l = random_limits(rng, i % 3 != 0);
    const State s = random_state(rng, l);
    Profile p;
    plan_velocity(s, 0.0, l, p);
    const Sampled smp = sample_profile(p, p.duration());
    expect_within(smp, l);
    EXPECT_EQ(p.sample(p.duration() + 1.0).v, 0.0);
    EXPECT_NEAR(p.end().p, stop_position(s, l), 1e-9 * std::max(1.0, std::fabs(s.p)));
    // A stop never reverses: velocity keeps its sign (or reaches zero).
    for (double t = 0; t < p.duration(); t += kDt) ASSERT_GE(p.sample(t).v * s.v, -1e-12);
  }
}

TEST(Stop, WithHigherDecelerationIsShorter) {
  const Limits l{1.0, 1.0, 10.0};
  const Limits q{1.0, 5.0, 50.0};
  const State s{0.0, 1.0, 0.0, 0.0};
  EXPECT_LT(stop_position(s, q), stop_position(s, l));
}

TEST(Velocity, RampsToVelocityAndCruises) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> frac(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const Limits l = random_limits(rng, i % 4 != 0);
    const State s = random_state(rng, l);
    const double v = frac(rng) * l.velocity;
    Profile p;
    plan_velocity(s, v, l, p);
    const Sampled smp = sample_profile(p, p.duration() + 0.01);
    expect_within(smp, l);
    EXPECT_EQ(p.sample(p.duration() + 2.0).v, v);
    EXPECT_EQ(p.sample(p.duration() + 2.0).a, 0.0);
  }
}

TEST(Velocity, ReducedLimitsBringAccelerationBackInside) {
  const Limits fast{10.0, 10.0, 100.0};
  const Limits slow{10.0, 2.0, 100.0};
  Profile a;
  plan_velocity(State{0, 0, 0, 0}, 10.0, fast, a);
  const State s = a.sample(0.2);  // a = 10 > 2
  ASSERT_GT(s.a, 2.0);
  Profile p;
  plan_velocity(s, 0.0, slow, p);
  double prev_a = s.a;
  for (double t = 0; t < p.duration() + kDt; t += kDt) {
    const State st = p.sample(t);
    EXPECT_LE(std::fabs(st.a), std::max(std::fabs(prev_a), slow.acceleration) + 1e-9);
    prev_a = st.a;
  }
  EXPECT_EQ(p.end().v, 0.0);
}

}  // namespace
}  // namespace hil::motion
