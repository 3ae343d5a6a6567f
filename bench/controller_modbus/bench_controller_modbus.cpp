// SPDX-License-Identifier: MIT
// The cycle-thread cost of a Modbus I/O link (IoSource read + IoSink write of one controller
// cycle): on the simulated terminal with a poll and changed outputs in every cycle (the worst
// case: table copies under the server's mutex), and on the libmodbus worker bus against the
// simulated terminal served on loopback TCP (the cycle thread only copies under the lock).
#include <benchmark/benchmark.h>

#include "hil/controllers/modbus_io_link.hpp"
#include "hil/controllers/modbus_io_sim_bus.hpp"
#include "hil/controllers/modbus_io_tcp_bus.hpp"

namespace {

using namespace hil;
using namespace hil::controllers;

// `bits` inputs (half discrete inputs, half coils 0..) and `bits` outputs (coils from 1000).
ModbusIoLinkConfig make_config(int bits) {
  ModbusIoLinkConfig c;
  for (int i = 0; i < bits; ++i) {
    const auto a = static_cast<std::uint16_t>(i / 2);
    const auto space = i % 2 == 0 ? modbus::BitSpace::discrete_input : modbus::BitSpace::coil;
    c.inputs.push_back(
        {{space, a}, BitAddress{IoArea::input, static_cast<std::uint32_t>(i / 8), static_cast<std::uint8_t>(i % 8)}});
    c.outputs.push_back(
        {{modbus::BitSpace::coil, static_cast<std::uint16_t>(1000 + i)},
         BitAddress{IoArea::output, static_cast<std::uint32_t>(i / 8), static_cast<std::uint8_t>(i % 8)}});
  }
  c.stale_after = std::chrono::seconds(10);
  return c;
}

void run_cycles(benchmark::State& state, ModbusIoLink& link, int bits) {
  IoImage image{IoLayout{{static_cast<std::uint32_t>(bits / 8 + 1), static_cast<std::uint32_t>(bits / 8 + 1), 1, 0}}};
  image.attach(static_cast<IoSource&>(link));
  image.attach(static_cast<IoSink&>(link));
  TimePoint now{};
  bool level = false;
  for (auto _ : state) {
    image.read_inputs(now);
    level = !level;
    for (int i = 0; i < bits; ++i)
      image.set(BitAddress{IoArea::output, static_cast<std::uint32_t>(i / 8), static_cast<std::uint8_t>(i % 8)}, level);
    image.write_outputs(now);
    now += std::chrono::milliseconds(1);
  }
  benchmark::DoNotOptimize(image.bytes(IoArea::input).data());
}

void BM_ModbusIoLinkSimCycle(benchmark::State& state) {
  const int bits = static_cast<int>(state.range(0));
  auto c = make_config(bits);
  auto plans = make_io_plans(c);
  SimTerminalOptions t;
  t.coils = 2000;
  auto bus = SimModbusIoBus::create(t, plans->reads, plans->writes,
                                    SimModbusIoBusConfig{std::chrono::milliseconds(1), std::chrono::milliseconds(100)});
  ModbusIoLink link(c, std::move(*plans), std::move(*bus));
  run_cycles(state, link, bits);
}
BENCHMARK(BM_ModbusIoLinkSimCycle)->Arg(8)->Arg(64)->Arg(512)->Unit(benchmark::kNanosecond);

void BM_ModbusIoLinkTcpCycle(benchmark::State& state) {
  const int bits = static_cast<int>(state.range(0));
  mocks::ModbusDriveServer server(mocks::IoTerminal{mocks::IoTerminalConfig{2000, 64}}, mocks::ModbusServerConfig{});
  if (server.start()) {
    state.SkipWithError("cannot start the simulated terminal");
    return;
  }
  auto c = make_config(bits);
  auto plans = make_io_plans(c);
  SteadyClock clock;
  TcpModbusIoBusConfig tc;
  tc.port = server.port();
  tc.poll = std::chrono::milliseconds(1);
  auto bus = std::make_unique<TcpModbusIoBus>(tc, plans->reads, plans->writes, clock);
  ModbusIoLink link(c, std::move(*plans), std::move(bus));
  run_cycles(state, link, bits);
}
BENCHMARK(BM_ModbusIoLinkTcpCycle)->Arg(8)->Arg(64)->Unit(benchmark::kNanosecond);

}  // namespace
