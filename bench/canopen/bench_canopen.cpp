// SPDX-License-Identifier: MIT
// CANopen speed goals (run with --benchmark_format=json):
//  * SDO expedited round trips per second, client and server on the in-process virtual bus
//    (goal > 200 000/s);
//  * segmented and block transfer throughput (bytes/s);
//  * one 1 kHz cycle with 32 CiA 402 axes: SYNC, 64 RPDOs + 64 TPDOs, master images, drives'
//    read/write and the 32 simulated nodes (goal < 10 % of one core = 100 µs per 1 ms cycle).
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "hil/can/virtual_bus.hpp"
#include "hil/canopen/eds.hpp"
#include "hil/canopen/sdo_client.hpp"
#include "hil/canopen/sdo_server.hpp"
#include "hil/cia402/cia402_drive.hpp"
#include "hil/cia402/layout.hpp"
#include "hil/mocks/cia402_node.hpp"

using namespace std::chrono_literals;
namespace co = hil::canopen;

namespace {

struct SdoPair {
  hil::VirtualClock clock;
  hil::can::VirtualBus bus{clock};
  std::unique_ptr<hil::can::VirtualChannel> cch = bus.attach("client");
  std::unique_ptr<hil::can::VirtualChannel> sch = bus.attach("server");
  co::ObjectDictionary od;
  std::unique_ptr<co::SdoServer> server;
  std::unique_ptr<co::SdoClient> client;
  explicit SdoPair(co::SdoClientOptions o = {}) {
    co::Variable v;
    v.index = 0x1018;
    v.sub = 1;
    v.type = co::DataType::unsigned32;
    v.access = co::Access::ro;
    v.value = {0x11, 0x0A, 0, 0};
    od.add(v);
    co::Variable d;
    d.index = 0x2000;
    d.type = co::DataType::domain;
    d.access = co::Access::rw;
    d.value.assign(4096, 0x5A);
    od.add(d);
    od.set_max_value_size(1 << 20);
    server = std::make_unique<co::SdoServer>(od, 2, [this](const hil::can::Frame& f) { (void)sch->send(f); });
    client = std::make_unique<co::SdoClient>(
        2, [this](const hil::can::Frame& f) { (void)cch->send(f); }, o);
    sch->set_receive_handler([this](const hil::can::Frame& f, hil::TimePoint t) { server->on_frame(f, t); });
    cch->set_receive_handler([this](const hil::can::Frame& f, hil::TimePoint t) { client->on_frame(f, t); });
  }
};

void BM_SdoExpeditedRoundTrip(benchmark::State& state) {
  SdoPair p;
  bool done = false;
  for (auto _ : state) {
    done = false;
    p.client->async_upload(0x1018, 1, p.clock.now(), [&](std::error_code, std::vector<std::uint8_t>) { done = true; });
    p.bus.deliver(p.clock.now());
    if (!done) state.SkipWithError("round trip did not complete");
  }
  state.counters["round_trips_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SdoExpeditedRoundTrip);

void BM_SdoUploadThroughput(benchmark::State& state) {
  co::SdoClientOptions o;
  o.block = state.range(0) != 0;
  o.block_threshold = 0;
  SdoPair p(o);
  std::size_t bytes = 0;
  for (auto _ : state) {
    bool done = false;
    p.client->async_upload(0x2000, 0, p.clock.now(), [&](std::error_code ec, std::vector<std::uint8_t> d) {
      done = !ec;
      bytes += d.size();
    });
    p.bus.deliver(p.clock.now());
    if (!done) state.SkipWithError("upload did not complete");
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
  state.SetLabel(o.block ? "block, 4 KiB" : "segmented, 4 KiB");
}
BENCHMARK(BM_SdoUploadThroughput)->Arg(0)->Arg(1);

void BM_SdoDownloadThroughput(benchmark::State& state) {
  co::SdoClientOptions o;
  o.block = state.range(0) != 0;
  o.block_threshold = 0;
  SdoPair p(o);
  const std::vector<std::uint8_t> payload(4096, 0xA5);
  std::size_t bytes = 0;
  for (auto _ : state) {
    bool done = false;
    p.client->async_download(0x2000, 0, payload, p.clock.now(), [&](std::error_code ec, auto) { done = !ec; });
    p.bus.deliver(p.clock.now());
    if (!done) state.SkipWithError("download did not complete");
    bytes += payload.size();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
  state.SetLabel(o.block ? "block+CRC, 4 KiB" : "segmented, 4 KiB");
}
BENCHMARK(BM_SdoDownloadThroughput)->Arg(0)->Arg(1);

void BM_SyncCycle32Axes(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  hil::VirtualClock clock;
  hil::can::VirtualBus bus{clock};
  auto mch = bus.attach("master");
  co::MasterOptions mo;
  mo.sync_period = 1ms;
  hil::cia402::Network net(*mch, mo);
  std::vector<std::unique_ptr<hil::can::VirtualChannel>> chans;
  std::vector<std::unique_ptr<hil::mocks::Cia402Node>> nodes;
  std::vector<std::unique_ptr<hil::cia402::Cia402Drive>> drives;
  for (int i = 1; i <= count; ++i) {
    const auto id = static_cast<co::NodeId>(i);
    hil::can::ParticipantOptions po;
    po.filters = hil::mocks::predefined_filters(id);
    chans.push_back(bus.attach("n", po));
    nodes.push_back(std::make_unique<hil::mocks::Cia402Node>(*chans.back(), hil::mocks::Cia402NodeOptions{.node = id}));
    auto eds = co::parse_eds(hil::mocks::cia402_node_eds(), "eds", id);
    hil::cia402::AxisOptions ao;
    ao.node = id;
    net.master().add_node(hil::cia402::make_axis_node_config(*eds, ao));
    drives.push_back(std::make_unique<hil::cia402::Cia402Drive>(net, id, hil::cia402::DriveOptions{}));
    drives.back()->request(hil::DriveRequest::enable);
  }
  for (auto& n : nodes) n->start(clock.now());
  net.start(clock.now());
  hil::CycleTime cycle;
  std::int64_t k = 0;
  hil::DriveCommand cmd;
  auto run_cycle = [&] {
    clock.advance(1ms);
    cycle.now = clock.now();
    net.step(cycle.now);
    bus.deliver(cycle.now);
    for (auto& d : drives) d->read(cycle);
    cmd.position_inc = (k++ % 2000) * 10;
    for (auto& d : drives) d->write(cycle, cmd);
    for (auto& n : nodes) n->step(cycle.now);
    bus.deliver(cycle.now);
  };
  for (int i = 0; i < 200; ++i) run_cycle();  // boot and enable
  for (auto& d : drives)
    if (d->feedback().state != hil::DriveState::operation_enabled) state.SkipWithError("axes not enabled");
  for (auto _ : state) run_cycle();
  state.counters["cycle_us"] = benchmark::Counter(static_cast<double>(state.iterations()) * 1e-6,
                                                  benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["cpu_percent_at_1kHz"] = benchmark::Counter(static_cast<double>(state.iterations()) * 1e-5,
                                                             benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["frames_per_cycle"] = static_cast<double>(bus.stats().delivered) / static_cast<double>(k);
}
BENCHMARK(BM_SyncCycle32Axes)->Arg(8)->Arg(32)->Unit(benchmark::kMicrosecond);

}  // namespace
