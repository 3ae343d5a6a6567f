// SPDX-License-Identifier: MIT
// AMKASYN SF speed (issue 16; run: bench_amkasyn --benchmark_format=json):
//   one SF cycle with 8 active SFs (2 VARSYNC, CAM, BINEA, DFKT, 2 DCOPY, ECOPY);
//   one SF cycle with 8 active SFs of the other types (FGEN -> XFIPW link, FIPW, REGL, IMES, EPOS,
//   APSF running a 12-statement FB, SIDIFF)
#include <benchmark/benchmark.h>

#include "hil/controllers/amkasyn/sf_runtime.hpp"

namespace {

using namespace hil::controllers::amkasyn;

DataBlock init(int type, int n, int src_a, int src_o, int sink_a, int sink_o, int in_mask, int in_byte, int out_mask,
               int out_byte, int tab0 = 0) {
  DataBlock d(10);
  d.set_dr(0, static_cast<std::uint8_t>(type)).set_dl(0, static_cast<std::uint8_t>(n));
  d.set_dl(2, static_cast<std::uint8_t>(src_a)).set_dr(2, static_cast<std::uint8_t>(src_o));
  d.set_dl(3, static_cast<std::uint8_t>(sink_a)).set_dr(3, static_cast<std::uint8_t>(sink_o));
  d.set_dr(4, static_cast<std::uint8_t>(in_mask)).set_dl(4, static_cast<std::uint8_t>(in_byte));
  d.set_dr(5, static_cast<std::uint8_t>(out_mask)).set_dl(5, static_cast<std::uint8_t>(out_byte));
  d.set_dr(6, static_cast<std::uint8_t>(tab0));
  return d;
}

DataBlock cmd(int n, int fct, int ba) {
  DataBlock c(34);
  c.set_dr(0, static_cast<std::uint8_t>(n)).set_dl(0, static_cast<std::uint8_t>(fct)).set_dr(1, 1);
  c.set_dl(1, static_cast<std::uint8_t>(ba));
  return c;
}

void BM_SfCycle8Active(benchmark::State& state) {
  DbStore dbs;
  DataBlock cam(100);
  cam.set_dw(0, 10000);
  for (int k = 0; k < 4; ++k)
    cam.set_dd(static_cast<std::size_t>(32 + 8 * k), 10000 + 1000 * k)
        .set_dd(static_cast<std::size_t>(34 + 8 * k), 11000 + 1000 * k);
  dbs[56] = cam;
  DataBlock bin(40);
  bin.set_dw(0, 9);
  for (int x = 0; x < 8; ++x)
    bin.set_dd(static_cast<std::size_t>(4 + 4 * x), 2500 * (x + 1))
        .set_dr(static_cast<std::size_t>(6 + 4 * x), static_cast<std::uint8_t>(x & 3));
  dbs[16] = bin;
  DataBlock sp(20);
  sp.set_dw(0, 10);
  for (int k = 0; k < 9; ++k) sp.set_dd(static_cast<std::size_t>(2 * (k + 1)), 500 * k);
  dbs[17] = sp;
  ProcessImage im;
  SfRuntime rt(2, dbs);
  // SF0, SF1: VARSYNC from the AZ message 1 high word to AW1 / AW2.
  for (int n = 0; n < 2; ++n) {
    (void)rt.init(init(3, n, 0, 1, n + 1, 4, 1, 16, 1, 16 + n), im);
    auto c = cmd(n, 1, 0);
    c.set_dw(2, 7936).set_dw(4, 10000).set_dw(6, -10000);
    (void)rt.command(c, im);
  }
  (void)rt.init(init(12, 2, 1, 5, 0, 0, 1, 1, 1, 1, 56), im);  // CAM
  {
    auto c = cmd(2, 0, 1);
    c.set_dw(3, 2).set_dr(6, 2).set_dl(6, 2).set_dr(7, 2).set_dl(7, 2).set_dd(14, 20000);
    (void)rt.command(c, im);
  }
  (void)rt.init(init(8, 3, 2, 5, 0, 0, 0, 0, 1, 8, 16), im);  // BINEA
  {
    auto c = cmd(3, 0, 1);
    c.set_dw(3, 2).set_dw(4, 2);
    (void)rt.command(c, im);
  }
  (void)rt.init(init(4, 4, 1, 19, 3, 16, 16, 24, 16, 24, 17), im);  // DFKT
  {
    auto c = cmd(4, 0, 4);
    c.set_dw(3, 2).set_dw(4, 1).set_dw(5, 1).set_dw(6, 1000).set_dw(8, 1000).set_dw(11, 2000).set_dw(12, 4000);
    c.set_dw(14, -4000).set_dw(16, 2000).set_dw(18, -2000).set_dw(20, 1000).set_dw(22, 2).set_dw(23, 1);
    (void)rt.command(c, im);
  }
  for (int n = 5; n < 7; ++n) {  // DCOPY absolute / incremental
    (void)rt.init(init(0, n, 129, 40, 129, 44 + 4 * (n - 5), 0, 0, 0, 0), im);
    (void)rt.command(cmd(n, 1, n - 5), im);
  }
  (void)rt.init(init(0, 7, 129, 40, 64, 0, 1, 100, 1, 101), im);  // ECOPY
  {
    auto c = cmd(7, 2, 3);
    c.set_dd(2, 10000).set_dd(4, 5000);
    (void)rt.command(c, im);
  }
  int active = 0;
  for (int n = 0; n < 16; ++n) active += rt.state(n) == SfState::active ? 1 : 0;
  if (active != 8) state.SkipWithError("not all 8 SFs started");
  std::int32_t pos = 0;
  for (auto _ : state) {
    pos += 13;
    im.az[0] += 7 << 16;
    im.aw[0].position_feedback = pos;
    im.aw[1].position_feedback = pos;
    im.aw[0].message32 = 10000000;
    im.set_md(40, pos);
    rt.cycle(im);
    benchmark::DoNotOptimize(im.aw[0].swq1);
  }
}
BENCHMARK(BM_SfCycle8Active);

void BM_SfCycle8ActiveOtherTypes(benchmark::State& state) {
  DbStore dbs;
  DataBlock y(80);  // a 31-point Y table over 20000
  y.set_dw(0, 32);
  for (int i = 0; i < 31; ++i) y.set_dd(static_cast<std::size_t>(2 + 2 * i), 300 * i);
  dbs[16] = y;
  dbs[20] = DataBlock(8);
  ProcessImage im;
  SfRuntime rt(2, dbs);
  (void)rt.load_fb(10, "L ED 212\nL MD 24\n-D\nWWD\nL KD 30000\nxD\nL KF 2\n:D\nT AD 212\nL ED 212\nT MD 24\nBE\n");
  (void)rt.init(init(5, 0, 0, 0, 255, 0, 1, 10, 1, 10), im);  // FGEN -> SF link
  {
    auto c = cmd(0, 1, 0);
    c.set_dw(2, 2000).set_dw(3, 2).set_dd(4, 20000).set_dd(6, 500000);
    (void)rt.command(c, im);
  }
  (void)rt.init(init(9, 1, 255, 0, 1, 4, 0, 0, 0, 0, 16), im);  // XFIPW on FGEN's output
  {
    auto c = cmd(1, 0, 2);
    c.set_dw(3, 2).set_dw(4, 1).set_dd(8, 1).set_dd(10, 20000);
    (void)rt.command(c, im);
  }
  (void)rt.init(init(1, 2, 0, 16, 2, 4, 0, 0, 0, 0, 16), im);  // FIPW on the AZ message
  {
    auto c = cmd(2, 0, 2);
    c.set_dw(3, 2).set_dw(4, 1).set_dd(8, 1).set_dd(10, 20000);
    (void)rt.command(c, im);
  }
  (void)rt.init(init(6, 3, 1, 2, 3, 16, 0, 0, 1, 0), im);  // REGL
  {
    auto c = cmd(3, 0, 0);
    c.set_dw(3, 2).set_dw(4, 7).set_dw(6, 512).set_dw(7, 128).set_dw(8, 64).set_dd(10, 1000000).set_dw(12, 1000);
    c.set_dd(14, 1000000).set_dw(18, 100).set_dd(20, 5000000);
    (void)rt.command(c, im);
  }
  (void)rt.init(init(7, 4, 0, 18, 128, 20, 0, 0, 1, 30), im);  // IMES
  {
    auto c = cmd(4, 0, 0);
    c.set_dd(4, 1000);
    (void)rt.command(c, im);
  }
  (void)rt.init(init(11, 5, 0, 0, 4, 16, 1, 12, 1, 12), im);  // EPOS (modulo, E1 held)
  {
    auto c = cmd(5, 0, 16);
    c.set_dw(3, 2).set_dd(4, 1000).set_dd(6, 600000).set_dd(8, 100000).set_dd(10, 200000).set_dd(12, 10000);
    (void)rt.command(c, im);
  }
  (void)rt.init(init(10, 6, 0, 1, 5, 16, 1, 8, 1, 8), im);  // APSF
  {
    auto c = cmd(6, 0, 0);
    c.set_dw(4, 10).set_dw(5, 20).set_dw(6, 1);
    (void)rt.command(c, im);
  }
  (void)rt.init(init(0, 7, 0, 0, 128, 60, 0, 0, 1, 40), im);  // SIDIFF over AW1..AW8
  {
    auto c = cmd(7, 255, 0);
    c.set_dr(2, 0xFF).set_dr(3, 1);
    (void)rt.command(c, im);
  }
  int active = 0;
  for (int n = 0; n < 16; ++n) active += rt.state(n) == SfState::active ? 1 : 0;
  if (active != 8) state.SkipWithError("not all 8 SFs started");
  im.e[10] = 1;
  im.e[12] = 1;
  std::int32_t pos = 0;
  for (auto _ : state) {
    pos += 13;
    im.az[0] += 7 << 16;
    im.az[1] += 9;
    if (pos % 1000 < 13) im.az_zero[1].pulse(im.az[1]);
    for (auto& d : im.aw) {
      d.position_feedback = pos;
      d.message32 = pos % 50;
      d.message16 = static_cast<std::int16_t>(2048 + pos % 100);
    }
    rt.cycle(im);
    benchmark::DoNotOptimize(im.aw[0].swq1);
  }
}
BENCHMARK(BM_SfCycle8ActiveOtherTypes);

}  // namespace
