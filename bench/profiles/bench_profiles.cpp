// SPDX-License-Identifier: MIT
// Speed of the profile engine: value codecs (per value), parameter-set parse + validate (per set),
// profile loading (per file). Run: bench_profiles --benchmark_format=json
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

#include "hil/profiles/bcd.hpp"
#include "hil/profiles/decimal_text.hpp"
#include "hil/profiles/loader.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/validation.hpp"
#include "hil/profiles/wire.hpp"

namespace hp = hil::profiles;

namespace {

std::string read(const std::string& f) {
  std::ifstream in(std::string(HIL_TEST_DATA) + "/" + f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void BM_BcdRoundTrip(benchmark::State& st) {
  const hp::BcdFormat f{8, hp::BcdSign::bit31};
  std::int64_t v = -24537;
  for (auto _ : st) {
    auto w = hp::make_bcd(v, f);
    auto back = hp::parse_bcd(*w, f);
    benchmark::DoNotOptimize(back);
    v = (v + 7919) % 79999999;
  }
}
BENCHMARK(BM_BcdRoundTrip);

void BM_DecimalTextRoundTrip(benchmark::State& st) {
  const auto f = *hp::DecimalTextFormat::parse("+6.3");
  hp::Decimal d{123456789, 3};
  for (auto _ : st) {
    auto t = hp::make_decimal_text(d, f);
    auto back = hp::parse_decimal_text(*t, f);
    benchmark::DoNotOptimize(back);
  }
}
BENCHMARK(BM_DecimalTextRoundTrip);

void BM_ClmTelegramDecodeEncode(benchmark::State& st) {
  auto p = *hp::find_profile("clm14");
  const auto& v = p->resolve("A112")->spec->variants.front();
  for (auto _ : st) {
    auto value = hp::decode_wire(*p, v, "03000 10.0");
    auto img = hp::encode_value(*p, v, *value);
    benchmark::DoNotOptimize(img);
  }
}
BENCHMARK(BM_ClmTelegramDecodeEncode);

void BM_ParseAndValidate(benchmark::State& st, const char* device, const char* file) {
  auto p = *hp::find_profile(device);
  auto parser = hp::make_parameter_set_parser(p);
  const auto text = read(file);
  std::size_t n = 0;
  for (auto _ : st) {
    auto r = parser->parse(text);
    auto problems = hp::validate(*p, r.set);
    n = r.set.entries.size();
    benchmark::DoNotOptimize(problems);
  }
  st.counters["parameters"] = static_cast<double>(n);
}
BENCHMARK_CAPTURE(BM_ParseAndValidate, clm14_72, "clm14", "clm14_manual_defaults.txt");
BENCHMARK_CAPTURE(BM_ParseAndValidate, wf725_44, "wf725-726", "wf725_valid.txt");
BENCHMARK_CAPTURE(BM_ParseAndValidate, ip247_70words, "ip247", "ip247_manual_md.txt");
BENCHMARK_CAPTURE(BM_ParseAndValidate, elg_tape, "sinumerik-elg", "elg_valid.tape");
BENCHMARK_CAPTURE(BM_ParseAndValidate, amk_fipw, "amkasyn-sf", "amk_fipw_printing_mark.txt");

void BM_LoadProfile(benchmark::State& st) {
  const auto dirs = hp::profile_search_path();
  for (auto _ : st) {
    auto p = hp::load_profile(dirs.back() / "clm14.yaml");
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_LoadProfile)->Unit(benchmark::kMillisecond);

}  // namespace
