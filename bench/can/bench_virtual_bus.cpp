// SPDX-License-Identifier: MIT
// Virtual bus throughput: frames/s through send() + deliver() with N participants (each frame
// fans out to N-1 receive handlers). items_per_second = frames put on the bus.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "hil/can/virtual_bus.hpp"

namespace {

void BM_VirtualBusFanOut(benchmark::State& state) {
  const auto participants = static_cast<int>(state.range(0));
  const auto batch = static_cast<int>(state.range(1));
  hil::VirtualClock clock;
  hil::can::VirtualBus bus(clock, "bench");
  std::vector<std::unique_ptr<hil::can::VirtualChannel>> nodes;
  std::uint64_t received = 0;
  for (int i = 0; i < participants; ++i) {
    nodes.push_back(bus.attach("n" + std::to_string(i)));
    nodes.back()->set_receive_handler([&received](const hil::can::Frame& f, hil::TimePoint) { received += f.dlc; });
  }
  auto frame = hil::can::make_frame(0x181, {1, 2, 3, 4, 5, 6, 7, 8});
  for (auto _ : state) {
    for (int k = 0; k < batch; ++k) {
      frame.id = 0x180u + static_cast<std::uint32_t>(k % 127);
      (void)nodes[static_cast<std::size_t>(k % participants)]->send(frame);
    }
    clock.advance(std::chrono::microseconds(100));
    bus.deliver(clock.now());
  }
  benchmark::DoNotOptimize(received);
  state.SetItemsProcessed(state.iterations() * batch);
  state.counters["receptions_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * batch * (participants - 1)), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_VirtualBusFanOut)->Args({2, 64})->Args({9, 64})->Args({33, 64});

/// The same with id filters on every receiver (a CANopen node listens to a handful of COB-IDs).
void BM_VirtualBusFiltered(benchmark::State& state) {
  const auto participants = static_cast<int>(state.range(0));
  hil::VirtualClock clock;
  hil::can::VirtualBus bus(clock, "bench");
  std::vector<std::unique_ptr<hil::can::VirtualChannel>> nodes;
  std::uint64_t received = 0;
  for (int i = 0; i < participants; ++i) {
    const auto node_id = static_cast<std::uint32_t>(i + 1);
    hil::can::FilterSet fs{.filters = {hil::can::Filter::exact(0x000), hil::can::Filter::exact(0x080),
                                       hil::can::Filter::exact(0x200 + node_id),
                                       hil::can::Filter::exact(0x600 + node_id)}};
    nodes.push_back(bus.attach("n" + std::to_string(i), {.filters = fs}));
    nodes.back()->set_receive_handler([&received](const hil::can::Frame& f, hil::TimePoint) { received += f.dlc; });
  }
  auto frame = hil::can::make_frame(0x201, {1, 2, 3, 4, 5, 6, 7, 8});
  for (auto _ : state) {
    for (int k = 0; k < 64; ++k) {
      frame.id = 0x200u + static_cast<std::uint32_t>(k % participants) + 1;
      (void)nodes[0]->send(frame);
    }
    clock.advance(std::chrono::microseconds(100));
    bus.deliver(clock.now());
  }
  benchmark::DoNotOptimize(received);
  state.SetItemsProcessed(state.iterations() * 64);
}
BENCHMARK(BM_VirtualBusFiltered)->Arg(2)->Arg(33);

}  // namespace
