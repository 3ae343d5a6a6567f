// SPDX-License-Identifier: MIT
// Property tests of the step planner (fixed seed): exact step counts, no timing rule ever broken,
// first interval 1/f_ss, absolute targets hit exactly, backlash on reversal, ramp = formula.
#include <cmath>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "hil/stepdir/ip247_ramp.hpp"
#include "hil/stepdir/step_planner.hpp"
#include "hil/stepdir/verifier.hpp"

using namespace hil::stepdir;
using hil::gpio::Edge;

namespace {

struct Rig {
  StepTiming timing;
  std::shared_ptr<const Ip247Ramp> ramp;
};

Rig make_setup(double fmax, double fss, double a, int pulse_us = 2, Polarity pol = Polarity::positive_edge,
               std::int64_t setup_ns = 5'000, std::int64_t hold_ns = 5'000) {
  auto t = make_ip247_timing(pulse_us, PulseRounding::up, fmax, pol, setup_ns, hold_ns);
  EXPECT_TRUE(t.has_value());
  auto r = Ip247Ramp::make({fmax, fss, a}, t->min_period_ns());
  if (!r) {
    ADD_FAILURE() << "ramp rejected: MD error " << static_cast<int>(r.error()) << " fmax " << fmax << " fss " << fss
                  << " a " << a;
    r = Ip247Ramp::make({5'000, 200, 50'000}, t->min_period_ns());
  }
  return {*t, std::make_shared<const Ip247Ramp>(std::move(*r))};
}

Rig random_setup(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> fmax_d(500.0, 100'000.0);
  const double fmax = fmax_d(rng);
  std::uniform_real_distribution<double> fss_d(1.0, std::min(fmax * 0.5, 10'000.0));
  const double fss = fss_d(rng);
  const double big_f = (fmax - fss) / 0.95;
  std::uniform_real_distribution<double> tau_d(std::max(0.005, big_f / 2.5e6), 0.3);  // keep moves short in time
  const double a = big_f / tau_d(rng);
  const int max_pulse = std::clamp(static_cast<int>(5e5 / fmax) - 1, 1, 31);
  std::uniform_int_distribution<int> pulse_d(1, max_pulse);
  std::bernoulli_distribution neg(0.5);
  std::uniform_int_distribution<std::int64_t> setup_d(0, 200'000);
  const int pulse = pulse_d(rng);
  const Polarity pol = neg(rng) ? Polarity::negative_edge : Polarity::positive_edge;
  const std::int64_t setup = setup_d(rng), hold = setup_d(rng);
  return make_setup(fmax, fss, a, pulse, pol, setup, hold);
}

}  // namespace

TEST(StepPlanner, RandomMovesStepCountEqualsDistanceAndNoRuleBroken) {
  std::mt19937_64 rng(0x1247);
  for (int trial = 0; trial < 60; ++trial) {
    Rig s = random_setup(rng);
    std::uniform_int_distribution<std::int64_t> bl_d(0, 20);
    StepPlanner p(s.timing, s.ramp, bl_d(rng));
    std::vector<Edge> edges;
    std::uniform_int_distribution<std::int64_t> dist_d(-3000, 3000);
    std::int64_t expected = 0;
    std::int64_t now = 0;
    for (int move = 0; move < 4; ++move) {
      const std::int64_t target = dist_d(rng);
      std::uniform_real_distribution<double> fv(1.0, s.ramp->params().f_max_hz * 1.2);
      p.move_to(target, fv(rng));
      // Plan in 1 ms windows, the way the drive does.
      while (p.moving() || p.position() != target) {
        now += 1'000'000;
        p.plan(now - 1'000'000, now, edges);
        ASSERT_LT(now, 3'600'000'000'000) << "move never finished";
      }
      expected = target;
      EXPECT_EQ(p.position(), target);
    }
    VerifyStats st;
    auto v = verify_edges(edges, s.timing, p.motor_position(), {}, &st);
    ASSERT_FALSE(v) << "trial " << trial << ": " << v->describe();
    // Every step on the wire is either a position step or a backlash step.
    EXPECT_EQ(static_cast<std::uint64_t>(st.steps_forward + st.steps_backward), p.steps_total());
    EXPECT_EQ(p.position(), expected);
  }
}

TEST(StepPlanner, FirstIntervalIsOneOverFss) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 30; ++trial) {
    Rig s = random_setup(rng);
    StepPlanner p(s.timing, s.ramp);
    std::vector<Edge> edges;
    p.move_to(500, s.ramp->params().f_max_hz);
    p.plan(0, plan_forever_ns, edges);
    VerifyStats st;
    ASSERT_FALSE(verify_edges(edges, s.timing, 500, {}, &st));
    EXPECT_EQ(st.first_interval_ns, static_cast<std::int64_t>(std::ceil(1e9 / s.ramp->params().f_ss_hz)));
  }
}

TEST(StepPlanner, AbsoluteTargetHitExactlyWhenRetargetedMidMove) {
  std::mt19937_64 rng(99);
  for (int trial = 0; trial < 40; ++trial) {
    Rig s = random_setup(rng);
    StepPlanner p(s.timing, s.ramp);
    std::vector<Edge> edges;
    std::uniform_int_distribution<std::int64_t> dist_d(-5000, 5000);
    std::uniform_int_distribution<int> cycles_d(1, 40);
    std::int64_t now = 0;
    std::int64_t target = 0;
    for (int k = 0; k < 5; ++k) {
      target = dist_d(rng);
      p.move_to(target, s.ramp->params().f_max_hz);
      const int cycles = cycles_d(rng);
      for (int c = 0; c < cycles; ++c, now += 1'000'000) p.plan(now, now + 1'000'000, edges);
    }
    p.plan(now, plan_forever_ns, edges);
    EXPECT_EQ(p.position(), target);
    EXPECT_FALSE(p.moving());
    auto v = verify_edges(edges, s.timing, target);
    ASSERT_FALSE(v) << v->describe();
  }
}

TEST(StepPlanner, ExponentialProfileMatchesFormulaAtSampledTimes) {
  // Manual example MD: fmax 5 kHz, fss 200 Hz, a = 50 Hz/ms.
  Rig s = make_setup(5'000, 200, 50'000, 30);
  const auto& r = *s.ramp;
  EXPECT_NEAR(r.big_f_hz(), (5000.0 - 200.0) / 0.95, 1e-9);
  EXPECT_NEAR(r.tau_s(), r.big_f_hz() / 50'000.0, 1e-12);
  StepPlanner p(s.timing, s.ramp);
  std::vector<Edge> edges;
  p.move_to(100'000, 5'000);
  p.plan(0, plan_forever_ns, edges);
  std::vector<std::int64_t> rises;
  for (const auto& e : edges) {
    if (e.line == 0 && e.level) rises.push_back(e.t_ns);
  }
  ASSERT_EQ(rises.size(), 100'000U);
  // Instantaneous frequency of each interval during acceleration = f(t) at the interval's start.
  for (std::size_t k = 0; k + 1 < rises.size(); k += 37) {
    const double t = static_cast<double>(rises[k]) * 1e-9;
    if (t > r.time_to_frequency(4'999.0)) break;
    const double f_formula = r.frequency_at(t);
    const double f_seen = 1e9 / static_cast<double>(rises[k + 1] - rises[k]);
    EXPECT_NEAR(f_seen, f_formula, f_formula * 1e-4 + 0.01) << "step " << k << " at t=" << t;
  }
  // Steps to reach f_v compare with the manual's distance integral (Euler vs. integral: < 0.5 %).
  const double t_v = r.time_to_frequency(4'000.0);
  const double s_formula = r.distance_steps(t_v);
  std::size_t k = 0;
  while (k + 1 < rises.size() && 1e9 / static_cast<double>(rises[k + 1] - rises[k]) < 4'000.0) ++k;
  EXPECT_NEAR(static_cast<double>(k), s_formula, s_formula * 0.005 + 2);
  // The deceleration mirrors the acceleration interval by interval.
  const std::size_t n = rises.size();
  for (std::size_t i = 0; i < 3000; ++i) {
    EXPECT_EQ(rises[i + 1] - rises[i], rises[n - 1 - i] - rises[n - 2 - i]) << i;
  }
}

TEST(StepPlanner, ShortMoveNeverReachesSpeedAndIsSymmetric) {
  Rig s = make_setup(5'000, 200, 50'000, 30);
  StepPlanner p(s.timing, s.ramp);
  std::vector<Edge> edges;
  p.move_to(41, 5'000);
  p.plan(0, plan_forever_ns, edges);
  std::vector<std::int64_t> iv;
  std::int64_t last = -1;
  for (const auto& e : edges) {
    if (e.line == 0 && e.level) {
      if (last >= 0) iv.push_back(e.t_ns - last);
      last = e.t_ns;
    }
  }
  ASSERT_EQ(iv.size(), 40U);
  for (std::size_t i = 0; i < iv.size(); ++i) EXPECT_EQ(iv[i], iv[iv.size() - 1 - i]);
  EXPECT_GT(iv[19], s.ramp->interval_ns(s.ramp->table().size()));  // peak below fmax
  EXPECT_EQ(iv[19], s.ramp->interval_ns(19));                      // braking point at the middle
}

TEST(StepPlanner, BacklashAddedOnReversalWithoutChangingPosition) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    Rig s = random_setup(rng);
    std::uniform_int_distribution<std::int64_t> bl_d(1, 50);
    const std::int64_t bl = bl_d(rng);
    StepPlanner p(s.timing, s.ramp, bl);
    std::vector<Edge> edges;
    p.move_to(300, 1e6);  // first move: direction unknown, no backlash
    p.plan(0, plan_forever_ns, edges);
    EXPECT_EQ(p.backlash_steps_total(), 0U);
    EXPECT_EQ(p.motor_position(), 300);
    p.move_to(100, 1e6);  // reversal
    p.plan(0, plan_forever_ns, edges);
    EXPECT_EQ(p.position(), 100);
    EXPECT_EQ(p.backlash_steps_total(), static_cast<std::uint64_t>(bl));
    EXPECT_EQ(p.motor_position(), 300 - 200 - bl);
    p.move_to(150, 1e6);  // reversal again
    p.plan(0, plan_forever_ns, edges);
    p.move_to(400, 1e6);  // same direction: no backlash
    p.plan(0, plan_forever_ns, edges);
    EXPECT_EQ(p.position(), 400);
    EXPECT_EQ(p.backlash_steps_total(), static_cast<std::uint64_t>(2 * bl));
    auto v = verify_edges(edges, s.timing, p.motor_position());
    ASSERT_FALSE(v) << v->describe();
  }
}

TEST(StepPlanner, FollowModeTracksCommandExactlyAndCarriesLag) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    Rig s = random_setup(rng);
    StepPlanner p(s.timing, s.ramp, trial % 3);
    p.set_mode(PlannerMode::follow);
    std::vector<Edge> edges;
    // A sine position command sampled per 1 ms cycle, amplitude exceeding fmax at times (lag).
    const double amp = 2.0 * s.ramp->params().f_max_hz * 0.002 * 30;
    std::int64_t now = 0;
    std::int64_t cmd = 0;
    bool lagged = false;
    for (int c = 0; c < 400; ++c, now += 1'000'000) {
      cmd = static_cast<std::int64_t>(std::llround(amp * std::sin(c * 0.02)));
      p.follow(cmd);
      lagged |= p.plan(now, now + 1'000'000, edges) == PlanStatus::lagging;
    }
    for (int c = 0; c < 100000 && p.position() != cmd; ++c, now += 1'000'000) p.plan(now, now + 1'000'000, edges);
    EXPECT_EQ(p.position(), cmd);
    auto v = verify_edges(edges, s.timing, p.motor_position());
    ASSERT_FALSE(v) << v->describe();
    (void)lagged;
  }
}

TEST(StepPlanner, FollowModeReportsLagWhenCommandExceedsFmax) {
  Rig s = make_setup(1'000, 100, 10'000, 30);
  StepPlanner p(s.timing, s.ramp);
  p.set_mode(PlannerMode::follow);
  std::vector<Edge> edges;
  p.follow(10);  // 10 steps in 1 ms = 10 kHz > 1 kHz
  EXPECT_EQ(p.plan(0, 1'000'000, edges), PlanStatus::lagging);
  EXPECT_LT(p.position(), 10);
  std::int64_t now = 1'000'000;
  while (p.position() != 10) {
    p.plan(now, now + 1'000'000, edges);
    now += 1'000'000;
  }
  EXPECT_FALSE(verify_edges(edges, s.timing, 10));
}

TEST(StepPlanner, HaltBrakesAlongTheRamp) {
  Rig s = make_setup(5'000, 200, 50'000, 30);
  StepPlanner p(s.timing, s.ramp);
  std::vector<Edge> edges;
  p.move_to(1'000'000, 5'000);
  p.plan(0, 200'000'000, edges);  // 200 ms into the acceleration
  const auto pos = p.position();
  p.halt();
  p.plan(200'000'000, plan_forever_ns, edges);
  EXPECT_FALSE(p.moving());
  EXPECT_GT(p.position(), pos);
  EXPECT_LT(p.position(), 2 * pos + 2);  // mirrored: braking distance about the distance accelerated
  EXPECT_FALSE(verify_edges(edges, s.timing, p.position()));
}

TEST(Ip247Ramp, RejectsBadMachineDataWithMdErrors) {
  EXPECT_EQ(Ip247Ramp::make({200'000, 200, 50'000}, 1).error(), Ip247MdError::max_frequency);
  EXPECT_EQ(Ip247Ramp::make({5'000, 20'000, 50'000}, 1).error(), Ip247MdError::start_stop_frequency);
  EXPECT_EQ(Ip247Ramp::make({5'000, 200, 10}, 1).error(), Ip247MdError::frequency_increase);
  // tau = F/a > 2.6 s
  EXPECT_EQ(Ip247Ramp::make({100'000, 200, 30'000}, 1).error(), Ip247MdError::frequency_increase);
  EXPECT_EQ(Ip247Ramp::make({1'000, 1'000, 50'000}, 1).error(), Ip247MdError::ramp_generation);
  EXPECT_EQ(quantise_pulse_us(0, PulseRounding::up).error(), Ip247MdError::pulse_duration);
  EXPECT_EQ(*quantise_pulse_us(5, PulseRounding::up), 6'000);
  EXPECT_EQ(*quantise_pulse_us(5, PulseRounding::down), 4'000);
  EXPECT_EQ(*quantise_pulse_us(1, PulseRounding::down), 2'000);
  // t_p <= half the period of fmax: 100 kHz allows at most 5 us -> 6 us (rounded up) is rejected.
  EXPECT_EQ(make_ip247_timing(5, PulseRounding::up, 100'000, Polarity::positive_edge, 0, 0).error(),
            Ip247MdError::pulse_duration);
  EXPECT_TRUE(make_ip247_timing(5, PulseRounding::down, 100'000, Polarity::positive_edge, 0, 0).has_value());
}

TEST(Ip247Ramp, DerivedExampleBrakingDistance) {
  // Digest §8 item 27: fmax 30 kHz, fss 1 kHz, a = 100 Hz/ms -> F = 30526.3 Hz, tau = 305.26 ms,
  // max braking distance (t_v = 3 tau) about 20 017 pulses.
  auto r = Ip247Ramp::make({30'000, 1'000, 100'000}, 1);
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->big_f_hz(), 30526.3, 0.1);
  EXPECT_NEAR(r->tau_s(), 0.30526, 1e-4);
  EXPECT_NEAR(r->distance_steps(3 * r->tau_s()), 20017, 2);
}
