// SPDX-License-Identifier: MIT
// ELG speed goal (issue 17; run: bench_elg --benchmark_format=json):
//   one ELG cycle, coupled with diagonal feed (B, Z and Y all moving)   < 100 ns
// The gearbox is coupled once before the timed loop; every iteration is one Gearbox::step with the
// axes advanced as a hobbing machine moves them (hob B at 500 rpm, Z and Y feeding), C at its set
// value, following-error monitoring on: the linkage evaluation with exact 128-bit quotients, the
// monitoring and the signal edges, as the controller runs them every cycle.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "hil/controllers/elg/gearbox.hpp"

namespace {

using namespace hil::controllers::elg;

void BM_ElgCycleDiagonalFeed(benchmark::State& state) {
  GearboxConfig config;
  config.md.n00 = 18000;
  config.md.n02 = 180000;
  Gearbox g(config);
  GearInput in;
  in.z0 = 1;
  in.z2 = 37;
  in.ud_z = *Decimal5::parse("8.18511");
  in.ud_y = *Decimal5::parse("38.14484");
  if (!g.set_input(in)) state.SkipWithError("input rejected");
  AxisFeedback axes;
  Signals s;
  s.fe_monitor = true;
  s.compute = true;
  g.step(s, axes);
  s.compute = false;
  g.step(s, axes);
  s.gearing_on = true;
  g.step(s, axes);
  if (!g.status().coupled) state.SkipWithError("did not couple");
  // Per 2 ms cycle: B at 500 rpm = 150 kHz x 4 = 600 counts, Z 1 mm/min and Y 0.5 mm/min in 0.5 um.
  for (auto _ : state) {
    axes.b += 600;
    axes.z += 1;
    axes.y += (axes.b & 1024) != 0 ? 1 : 0;
    axes.c = g.status().c_set;
    const GearboxStatus& st = g.step(s, axes);
    benchmark::DoNotOptimize(st.c_set);
  }
  if (!g.alarms().empty()) state.SkipWithError("alarm during the run");
}
BENCHMARK(BM_ElgCycleDiagonalFeed);

}  // namespace
