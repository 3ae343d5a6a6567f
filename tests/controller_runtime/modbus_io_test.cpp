// SPDX-License-Identifier: MIT
// The Modbus I/O link: the pure bit plan; the link on the simulated terminal on virtual time
// (polling, write on change, a terminal that stops answering, absent addresses, stale data);
// the libmodbus worker bus against the simulated terminal served over loopback TCP.
#include <gtest/gtest.h>

#include <functional>
#include <thread>

#include <fmt/format.h>

#include "hil/controllers/modbus_io_link.hpp"
#include "hil/controllers/modbus_io_sim_bus.hpp"
#include "hil/controllers/modbus_io_tcp_bus.hpp"
#include "hil/modbus/bit_plan.hpp"

namespace hil::controllers {
namespace {

using modbus::BitRef;
using modbus::BitSpace;
using std::chrono::milliseconds;

TEST(ModbusBitPlan, GroupsConsecutiveAddressesPerTableWithoutBridgingGaps) {
  const std::vector<BitRef> bits = {{BitSpace::discrete_input, 3}, {BitSpace::coil, 7}, {BitSpace::discrete_input, 1},
                                    {BitSpace::discrete_input, 2}, {BitSpace::coil, 9}, {BitSpace::discrete_input, 2}};
  const auto plan = modbus::make_bit_plan(bits, false);
  ASSERT_TRUE(plan) << plan.error();
  ASSERT_EQ(plan->blocks.size(), 3u);  // coil 7, coil 9 (gap not bridged), DI 1..3
  EXPECT_EQ(plan->blocks[0].first, 7);
  EXPECT_EQ(plan->blocks[1].first, 9);
  EXPECT_EQ(plan->blocks[2].space, BitSpace::discrete_input);
  EXPECT_EQ(plan->blocks[2].first, 1);
  EXPECT_EQ(plan->blocks[2].count, 3);
  EXPECT_EQ(plan->bits, 5u);
  EXPECT_EQ(plan->slots, (std::vector<std::size_t>{4, 0, 2, 3, 1, 3}));
}

TEST(ModbusBitPlan, SplitsAtTheProtocolLimitsAndRefusesBadWrites) {
  std::vector<BitRef> many;
  for (std::uint32_t a = 0; a < 4100; ++a) many.push_back({BitSpace::coil, static_cast<std::uint16_t>(a)});
  const auto reads = modbus::make_bit_plan(many, false);
  ASSERT_TRUE(reads);
  ASSERT_EQ(reads->blocks.size(), 3u);
  EXPECT_EQ(reads->blocks[0].count, 2000);
  EXPECT_EQ(reads->blocks[2].count, 100);
  const auto writes = modbus::make_bit_plan(many, true);
  ASSERT_TRUE(writes);
  EXPECT_EQ(writes->blocks[0].count, 1968);
  const std::vector<BitRef> dup = {{BitSpace::coil, 4}, {BitSpace::coil, 4}};
  EXPECT_EQ(modbus::make_bit_plan(dup, true).error(), "coil 4 is written twice");
  const std::vector<BitRef> di = {{BitSpace::discrete_input, 4}};
  EXPECT_NE(modbus::make_bit_plan(di, true).error().find("cannot be written"), std::string::npos);
}

constexpr BitAddress kStart{IoArea::input, 0, 0};
constexpr BitAddress kStop{IoArea::input, 0, 1};
constexpr BitAddress kOk{IoArea::input, 0, 7};
constexpr BitAddress kLamp{IoArea::output, 0, 0};
constexpr BitAddress kBrake{IoArea::output, 0, 1};

ModbusIoLinkConfig config() {
  ModbusIoLinkConfig c;
  c.name = "io_links[0]";
  c.inputs = {{{BitSpace::discrete_input, 0}, kStart}, {{BitSpace::coil, 3}, kStop}};
  c.outputs = {{{BitSpace::coil, 16}, kLamp}, {{BitSpace::coil, 17}, kBrake}};
  c.stale_after = milliseconds(120);
  c.status_bit = kOk;
  return c;
}

// One link on the simulated terminal, stepped like a controller on a 1 ms cycle.
struct SimRig {
  explicit SimRig(ModbusIoLinkConfig c = config(), SimModbusIoBusConfig bc = {}) {
    auto plans = make_io_plans(c);
    EXPECT_TRUE(plans) << plans.error();
    auto server = std::make_unique<mocks::ModbusDriveServer>(mocks::IoTerminal{}, mocks::ModbusServerConfig{});
    auto b = std::make_unique<SimModbusIoBus>(std::move(server), plans->reads, plans->writes, bc);
    bus = b.get();
    link = std::make_unique<ModbusIoLink>(std::move(c), std::move(*plans), std::move(b));
    image.attach(static_cast<IoSource&>(*link));
    image.attach(static_cast<IoSink&>(*link));
  }
  void cycle() {
    image.read_inputs(now);
    image.write_outputs(now);
    now += milliseconds(1);
  }
  void run(milliseconds d) {
    for (auto end = now + d; now < end;) cycle();
  }
  template <class Fn>
  decltype(auto) terminal(Fn&& fn) {
    return bus->server().with_terminal(std::forward<Fn>(fn));
  }
  IoImage image{IoLayout{{2, 2, 2, 0}}};
  SimModbusIoBus* bus = nullptr;
  std::unique_ptr<ModbusIoLink> link;
  TimePoint now{};
};

TEST(ModbusIoLinkSim, InputsFollowTheTerminalAtThePollPeriod) {
  SimRig r;
  r.cycle();  // t = 0: the first poll
  EXPECT_TRUE(r.link->healthy());
  EXPECT_TRUE(r.image.get(kOk));
  EXPECT_FALSE(r.image.get(kStart));
  r.terminal([](mocks::IoTerminal& t) {
    t.set_discrete_input(0, true);
    t.set_coil(3, true);  // a coil read as an input (FC 1)
  });
  r.run(milliseconds(9));  // t = 1..9 ms: no poll yet (10 ms period)
  EXPECT_FALSE(r.image.get(kStart));
  r.cycle();  // t = 10 ms
  EXPECT_TRUE(r.image.get(kStart));
  EXPECT_TRUE(r.image.get(kStop));
  EXPECT_TRUE(r.image.rising(kStart));
  EXPECT_EQ(r.link->status().polls, 2u);
  EXPECT_FALSE(r.link->fault());
}

TEST(ModbusIoLinkSim, OutputsAreWrittenOnChangeOnly) {
  SimRig r;
  r.cycle();
  r.image.set(kLamp, true);
  r.cycle();
  EXPECT_TRUE(r.terminal([](mocks::IoTerminal& t) { return t.coil(16); }));
  // A peer clears the coil; the link does not write it again while its output bit is unchanged.
  r.terminal([](mocks::IoTerminal& t) { t.set_coil(16, false); });
  r.run(milliseconds(50));
  EXPECT_FALSE(r.terminal([](mocks::IoTerminal& t) { return t.coil(16); }));
  r.image.set(kLamp, false);
  r.image.set(kBrake, true);
  r.cycle();
  EXPECT_TRUE(r.terminal([](mocks::IoTerminal& t) { return t.coil(17); }));
}

TEST(ModbusIoLinkSim, ATerminalThatStopsAnsweringFaultsAndItsInputsReadZero) {
  SimRig r;
  r.terminal([](mocks::IoTerminal& t) { t.set_discrete_input(0, true); });
  r.run(milliseconds(20));
  ASSERT_TRUE(r.image.get(kStart));
  r.bus->set_answering(false);  // t = 20 ms; the next poll starts at 20 ms and is never answered
  r.run(milliseconds(100));     // up to 119 ms: within the response timeout, the last value stands
  EXPECT_TRUE(r.image.get(kStart));
  EXPECT_TRUE(r.link->healthy());
  r.cycle();  // t = 120 ms: the poll of t = 20 ms timed out
  EXPECT_FALSE(r.link->healthy());
  EXPECT_FALSE(r.image.get(kStart)) << "a stale input must not keep its value";
  EXPECT_FALSE(r.image.get(kOk));
  ASSERT_TRUE(r.link->fault());
  EXPECT_EQ(r.link->fault().code, modbus::make_error_code(modbus::ModbusError::timeout));
  EXPECT_NE(r.link->fault().text.find("io_links[0] (simulated terminal)"), std::string::npos) << r.link->fault().text;
  EXPECT_EQ(r.link->fault_count(), 1u);
  // Outputs given while it is down reach the terminal when it answers again (all blocks anew).
  r.image.set(kLamp, true);
  r.run(milliseconds(200));
  EXPECT_FALSE(r.terminal([](mocks::IoTerminal& t) { return t.coil(16); }));
  r.terminal([](mocks::IoTerminal& t) { t.set_coil(17, true); });  // lost state: the link writes 0 again
  r.bus->set_answering(true);
  r.run(milliseconds(120));
  EXPECT_TRUE(r.link->healthy());
  EXPECT_TRUE(r.image.get(kStart));
  EXPECT_TRUE(r.terminal([](mocks::IoTerminal& t) { return t.coil(16); }));
  EXPECT_FALSE(r.terminal([](mocks::IoTerminal& t) { return t.coil(17); }));
  EXPECT_TRUE(r.link->fault()) << "latched until reset()";
  EXPECT_EQ(r.link->fault_count(), 1u);
  r.link->reset();
  EXPECT_FALSE(r.link->fault());
}

TEST(ModbusIoLinkSim, DataOlderThanStaleAfterIsNotValid) {
  auto c = config();
  c.stale_after = milliseconds(30);
  SimRig r(c, SimModbusIoBusConfig{.poll = milliseconds(50), .response_timeout = milliseconds(100)});
  r.terminal([](mocks::IoTerminal& t) { t.set_discrete_input(0, true); });
  r.run(milliseconds(31));
  EXPECT_TRUE(r.image.get(kStart));
  r.cycle();  // t = 31 ms: the t = 0 poll is 31 ms old
  EXPECT_FALSE(r.image.get(kStart));
  EXPECT_EQ(r.link->fault().code, modbus::make_error_code(modbus::ModbusError::timeout));
  EXPECT_NE(r.link->fault().text.find("no answered poll for 31 ms"), std::string::npos) << r.link->fault().text;
}

TEST(ModbusIoLinkSim, AnAddressTheTerminalLacksIsExceptionTwo) {
  auto c = config();
  c.inputs.push_back({{BitSpace::discrete_input, 64}, BitAddress{IoArea::input, 1, 0}});  // terminal: 0..63
  SimRig r(c);
  r.cycle();
  EXPECT_FALSE(r.link->healthy());
  EXPECT_EQ(r.link->fault().code, modbus::make_error_code(modbus::ModbusError::illegal_data_address));
  EXPECT_NE(r.link->fault().text.find("illegal data address"), std::string::npos) << r.link->fault().text;
}

bool wait_until(const std::function<bool()>& pred, milliseconds limit = milliseconds(3000)) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(milliseconds(1));  // the worker runs on real time
  }
  return pred();
}

// Both ends real: the libmodbus worker bus against the simulated terminal on loopback TCP.
TEST(ModbusIoLinkTcp, ReadsWritesAndSurvivesAServerRestart) {
  mocks::ModbusDriveServer server(mocks::IoTerminal{}, mocks::ModbusServerConfig{});
  ASSERT_FALSE(server.start());
  auto c = config();
  c.stale_after = milliseconds(300);
  auto plans = make_io_plans(c);
  ASSERT_TRUE(plans);
  SteadyClock clock;
  TcpModbusIoBusConfig tc{.host = "127.0.0.1",
                          .port = server.port(),
                          .unit = 1,
                          .poll = milliseconds(5),
                          .response_timeout = milliseconds(100),
                          .backoff_min = milliseconds(20),
                          .backoff_max = milliseconds(100)};
  auto b = std::make_unique<TcpModbusIoBus>(tc, plans->reads, plans->writes, clock);
  TcpModbusIoBus* bus = b.get();
  EXPECT_EQ(bus->describe(), fmt::format("tcp://127.0.0.1:{} unit 1", server.port()));
  ModbusIoLink link(c, std::move(*plans), std::move(b));
  IoImage image{IoLayout{{2, 2, 2, 0}}};
  image.attach(static_cast<IoSource&>(link));
  image.attach(static_cast<IoSink&>(link));
  TimePoint now{};
  const auto cycle = [&] {
    image.read_inputs(now);
    image.write_outputs(now);
    now += milliseconds(1);
  };
  server.with_terminal([](mocks::IoTerminal& t) { t.set_discrete_input(0, true); });
  image.set(kBrake, true);
  ASSERT_TRUE(wait_until([&] {
    cycle();
    return image.get(kStart);
  }));
  EXPECT_TRUE(link.healthy());
  EXPECT_TRUE(image.get(kOk));
  ASSERT_TRUE(wait_until([&] { return server.with_terminal([](mocks::IoTerminal& t) { return t.coil(17); }); }));
  image.set(kLamp, true);
  cycle();
  ASSERT_TRUE(wait_until([&] { return server.with_terminal([](mocks::IoTerminal& t) { return t.coil(16); }); }));
  // The worker counts a request after its answer, which may come after the coil changed on the
  // server: take the count once it has stood still for 20 ms.
  auto requests = bus->stats().write_requests;
  for (int tries = 0; tries < 100; ++tries) {
    std::this_thread::sleep_for(milliseconds(20));
    const auto again = bus->stats().write_requests;
    if (again == requests) break;
    requests = again;
  }
  for (int i = 0; i < 20; ++i) cycle();  // unchanged outputs: nothing more is written
  std::this_thread::sleep_for(milliseconds(20));
  EXPECT_EQ(bus->stats().write_requests, requests);

  server.stop();  // the terminal goes away: connection lost, then connect refused
  ASSERT_TRUE(wait_until([&] {
    cycle();
    return !link.healthy();
  }));
  EXPECT_FALSE(image.get(kStart));
  EXPECT_FALSE(image.get(kOk));
  ASSERT_TRUE(link.fault());
  EXPECT_STREQ(link.fault().code.category().name(), "modbus");
  EXPECT_GE(link.fault().code.value(), 0x101);
  ASSERT_FALSE(server.start());  // same port
  ASSERT_TRUE(wait_until([&] {
    cycle();
    return link.healthy();
  }));
  EXPECT_TRUE(image.get(kStart));
  EXPECT_EQ(link.fault_count(), 1u);
  EXPECT_GE(bus->stats().connects, 2u);
}

}  // namespace
}  // namespace hil::controllers
