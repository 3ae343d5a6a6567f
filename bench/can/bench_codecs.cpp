// SPDX-License-Identifier: MIT
// socketcand and candump codec throughput: elements (or lines) per second through the stream
// splitter + parser, and through the formatter. bytes_per_second is wire text.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "hil/can/candump.hpp"
#include "hil/can/socketcand.hpp"

namespace {

namespace sc = hil::can::socketcand;

std::string make_stream(int n) {
  std::string s;
  for (int i = 0; i < n; ++i) {
    auto f = hil::can::make_frame(0x180u + static_cast<std::uint32_t>(i % 127),
                                  {static_cast<std::uint8_t>(i), 2, 3, 4, 5, 6, 7, 8});
    (void)sc::format_rx_frame(s, f, {1700000000 + i / 1000, static_cast<std::uint32_t>(i % 1000000)});
  }
  return s;
}

void BM_SocketcandParseStream(benchmark::State& state) {
  const std::string stream = make_stream(1024);
  std::uint64_t frames = 0;
  for (auto _ : state) {
    sc::ElementSplitter splitter;
    // TCP-sized reads.
    for (std::size_t off = 0; off < stream.size(); off += 1448) {
      splitter.feed(std::string_view(stream).substr(off, 1448));
      sc::ElementSplitter::Item item;
      while (splitter.next(item)) {
        auto e = sc::parse_element(item.element);
        if (e && std::holds_alternative<sc::RxFrame>(*e)) ++frames;
      }
    }
  }
  benchmark::DoNotOptimize(frames);
  state.SetItemsProcessed(state.iterations() * 1024);
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(stream.size()));
}
BENCHMARK(BM_SocketcandParseStream);

void BM_SocketcandFormatRx(benchmark::State& state) {
  std::string out;
  out.reserve(64 * 1024);
  auto f = hil::can::make_frame(0x181, {1, 2, 3, 4, 5, 6, 7, 8});
  for (auto _ : state) {
    out.clear();
    for (int i = 0; i < 1024; ++i) {
      f.data[0] = static_cast<std::uint8_t>(i);
      (void)sc::format_rx_frame(out, f, {1700000000, static_cast<std::uint32_t>(i)});
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * 1024);
}
BENCHMARK(BM_SocketcandFormatRx);

void BM_SocketcandParseSend(benchmark::State& state) {
  const std::string el = "< send 601 8 40 18 10 1 0 0 0 0 >";
  for (auto _ : state) {
    auto e = sc::parse_element(el);
    benchmark::DoNotOptimize(e);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SocketcandParseSend);

void BM_CandumpParseLine(benchmark::State& state) {
  const std::string line = "(1700000000.123456) can0 1F334455#1122334455667788";
  for (auto _ : state) {
    auto r = hil::can::candump::parse_log_line(line);
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CandumpParseLine);

}  // namespace
