// SPDX-License-Identifier: MIT
// Serial transfer benchmarks (CLM1.4 client against the CLM emulator):
//  - BM_Clm14Paced: a full 3000-line program and a full parameter set, sent (`hilbridge download`) with
//    confirmation, over an in-process line paced like a UART on the virtual clock: every byte
//    costs (start + data + parity + stop bits) / baud in each direction. Counters: the line's
//    physical limit (all bytes on the wire x bits/char / baud), the modelled transfer time, and
//    line_fraction = limit / modelled time (1.0 = the stack never leaves the line idle).
//  - BM_Clm14Pty: the same over a real pty pair with the emulator on its own thread (a pty has
//    no baud pacing): wall time, and the equivalent bit rate the software sustains.
// Run: bench_serial --benchmark_format=json
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <thread>

#include "hil/mocks/legacy/clm14_line.hpp"
#include "hil/serial/clm14/client.hpp"
#include "hil/serial/clm14/item_devices.hpp"
#include "hil/serial/item_transfer.hpp"
#include "hil/serial/linux/ports.hpp"
#include "hil/serial/memory_line.hpp"
#include "hil/serial/serial_stream.hpp"

using namespace hil::serial;
using namespace hil::mocks::legacy;

namespace {

std::shared_ptr<const clm14::DeviceData> data() {
  static auto d = clm14::load_device_data();
  return *d;
}

std::vector<Item> full_program() {
  std::vector<Item> items;
  for (int i = 0; i < 3000; ++i) {
    const char* text = i % 3 == 0 ? "POI 1    +123456.789 123" : i % 3 == 1 ? "AEA Q1.00.3 1" : "WAI 00.500";
    items.push_back(Item{fmt::format("{:04d}", i), text});
  }
  return items;
}

std::vector<Item> full_parameters() {
  std::vector<Item> items;
  for (const auto& n : data()->parameter_numbers(4)) items.push_back(Item{n, data()->parameter_default(n)});
  return items;
}

struct PacedRig {
  hil::VirtualClock clock;
  MemoryLinePair mem = make_memory_line(&clock);
  Clm14Line line{data(), 0, 4};
  LineFormat format;
  std::unique_ptr<SerialStream> client;
  std::uint64_t wire_chars = 0;
  std::uint64_t request_chars = 0;

  explicit PacedRig(LineFormat f) : format(f) {
    client = std::make_unique<SerialStream>(std::move(mem.a), f, Discipline{}, clock);
    auto* dev = mem.b.get();
    *mem.a_to_b = [this, dev](std::vector<std::uint8_t>& bytes) {
      wire_chars += bytes.size();
      request_chars += bytes.size();
      clock.advance(format.line_time(bytes.size()));  // the request occupies the line
      const std::string out = line.on_bytes(bytes, clock.now());
      bytes.clear();
      if (out.empty()) return;
      wire_chars += out.size();
      clock.advance(format.line_time(out.size()));  // then the reply
      (void)dev->write(std::span(reinterpret_cast<const std::uint8_t*>(out.data()), out.size()),
                       std::chrono::seconds(1));
    };
    line.set_mode(ClmMode::parameter);
  }
};

void run_paced(benchmark::State& state, bool program) {
  const auto items = program ? full_program() : full_parameters();
  LineFormat f = *parse_char_format("8N1");
  f.baud = static_cast<std::uint32_t>(state.range(0));
  double modelled_s = 0, limit_s = 0;
  std::uint64_t chars = 0, request = 0;
  for (auto _ : state) {
    PacedRig rig(f);
    clm14::Client c(*rig.client, rig.clock, clm14::ClientOptions{});
    clm14::ProgramDevice prog(c);
    clm14::ParameterDevice par(c);
    ItemDevice& dev = program ? static_cast<ItemDevice&>(prog) : par;
    const auto t0 = rig.clock.now();
    auto rep = send_items(dev, items, 0, {}, nullptr);
    if (!rep.ok()) state.SkipWithError(rep.describe().c_str());
    modelled_s = hil::to_seconds(rig.clock.now() - t0);
    limit_s = hil::to_seconds(f.line_time(rig.wire_chars));
    chars = rig.wire_chars;
    request = rig.request_chars;
  }
  state.counters["request_share"] = static_cast<double>(request) / static_cast<double>(chars);
  state.counters["items"] = static_cast<double>(items.size());
  state.counters["wire_chars"] = static_cast<double>(chars);
  state.counters["line_limit_s"] = limit_s;
  state.counters["modelled_s"] = modelled_s;
  state.counters["line_fraction"] = limit_s / modelled_s;
}

void BM_Clm14PacedProgram(benchmark::State& s) {
  run_paced(s, true);
}
void BM_Clm14PacedParameters(benchmark::State& s) {
  run_paced(s, false);
}
BENCHMARK(BM_Clm14PacedProgram)->Arg(9600)->Arg(115200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Clm14PacedParameters)->Arg(9600)->Arg(115200)->Unit(benchmark::kMillisecond);

void BM_Clm14PtyProgram(benchmark::State& state) {
  const auto items = full_program();
  hil::SteadyClock clock;
  LineFormat f = *parse_char_format("8N1");
  f.baud = 115200;
  Clm14Line line(data(), 0, 4);
  auto pty = linux_io::PtyEndpoint::create();
  SerialStream device(pty->take_master(), f, Discipline{}, clock);
  EndpointHost host(line, device, clock);
  std::thread t([&] { host.run(); });
  auto client_stream = linux_io::open_tty(pty->slave_path(), f, clock);
  clm14::Client c(**client_stream, clock, clm14::ClientOptions{});
  clm14::ProgramDevice prog(c);
  std::uint64_t chars_before = (*client_stream)->written() + (*client_stream)->received();
  for (auto _ : state) {
    auto rep = send_items(prog, items, 0, {}, nullptr);
    if (!rep.ok()) state.SkipWithError(rep.describe().c_str());
  }
  const std::uint64_t chars = (*client_stream)->written() + (*client_stream)->received() - chars_before;
  host.stop();
  t.join();
  state.counters["chars_per_s"] = benchmark::Counter(static_cast<double>(chars), benchmark::Counter::kIsRate);
  state.counters["equiv_baud_8N1"] = benchmark::Counter(static_cast<double>(chars) * 10.0, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Clm14PtyProgram)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

}  // namespace
