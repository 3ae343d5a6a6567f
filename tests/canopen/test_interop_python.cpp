// SPDX-License-Identifier: MIT
// Interop: an independent CANopen master written with Debian's python3-can (socketcand
// interface) exchanges NMT, SDO (expedited, segmented, aborts, PDO remapping) and PDO traffic
// with our simulated CiA 402 node through our socketcand hub; the script checks every byte.
#include <gtest/gtest.h>

#include "../can/hub_fixture.hpp"
#include "../can/subprocess.hpp"
#include "hil/mocks/cia402_node.hpp"

namespace can = hil::can;

TEST(CanopenInterop, PythonCanMasterAgainstSimulatedNode) {
  if (!can::test::python_has("can.interfaces.socketcand"))
    GTEST_SKIP()
        << "/usr/bin/python3 with python3-can's socketcand interface is not installed (apt install python3-can)";
  can::test::Hub hub;
  std::unique_ptr<can::VirtualChannel> channel;
  std::unique_ptr<hil::mocks::Cia402Node> node;
  std::unique_ptr<can::test::Ticker> ticker;
  hub.run([&] {
    channel = hub.bus.attach("node5");
    node = std::make_unique<hil::mocks::Cia402Node>(*channel, hil::mocks::Cia402NodeOptions{.node = 5});
    node->start(hub.clock.now());
    ticker =
        std::make_unique<can::test::Ticker>(hub.io, std::chrono::milliseconds(1), [&] { node->step(hub.clock.now()); });
    ticker->start();
    return 0;
  });
  can::test::Subprocess py({"/usr/bin/python3", std::string(HIL_TEST_SOURCE_DIR) + "/canopen_peer.py", "127.0.0.1",
                            std::to_string(hub.port()), "can0", "5"});
  ASSERT_TRUE(py.started());
  EXPECT_EQ(py.wait(std::chrono::seconds(120)), 0) << py.output();
  EXPECT_NE(py.output().find("DONE"), std::string::npos) << py.output();
  hub.run([&] {
    ticker.reset();  // stops first: no step of a destroyed node
    node.reset();
    channel.reset();
    return 0;
  });
}

// python-can sends at once after connect(): the hub (with `hilbridge can hub`'s default join hold)
// must deliver the node's answer every time, on a bus busy with a SYNC every millisecond.
TEST(CanopenInterop, PythonCanSdoRightAfterConnectIsAnsweredFiftyTimes) {
  if (!can::test::python_has("can.interfaces.socketcand"))
    GTEST_SKIP()
        << "/usr/bin/python3 with python3-can's socketcand interface is not installed (apt install python3-can)";
  can::socketcand::ServerOptions options;
  options.join_hold = std::chrono::milliseconds(50);  // `hilbridge can hub --join-hold-ms` default
  can::test::Hub hub(options);
  std::unique_ptr<can::VirtualChannel> channel;
  std::unique_ptr<can::VirtualChannel> sync_source;
  std::unique_ptr<hil::mocks::Cia402Node> node;
  std::unique_ptr<can::test::Ticker> ticker;
  hub.run([&] {
    channel = hub.bus.attach("node5");
    sync_source = hub.bus.attach("sync");
    node = std::make_unique<hil::mocks::Cia402Node>(*channel, hil::mocks::Cia402NodeOptions{.node = 5});
    node->start(hub.clock.now());
    ticker = std::make_unique<can::test::Ticker>(hub.io, std::chrono::milliseconds(1), [&] {
      (void)sync_source->send(can::make_frame(0x080, {}));
      node->step(hub.clock.now());
    });
    ticker->start();
    return 0;
  });
  can::test::Subprocess py({"/usr/bin/python3", std::string(HIL_TEST_SOURCE_DIR) + "/sdo_at_connect.py", "127.0.0.1",
                            std::to_string(hub.port()), "can0", "5", "50"});
  ASSERT_TRUE(py.started());
  EXPECT_EQ(py.wait(std::chrono::seconds(120)), 0) << py.output();
  EXPECT_NE(py.output().find("DONE 50 rounds"), std::string::npos) << py.output();
  const auto stats = hub.run([&] { return hub.server->stats(); });
  EXPECT_EQ(stats.dropped_slow_client, 0u);
  // Late rounds (the machine was busy) are repeated: one accepted connection per round made.
  const auto at = py.output().rfind("CONNECTIONS ");
  ASSERT_NE(at, std::string::npos) << py.output();
  EXPECT_EQ(stats.accepted, std::stoul(py.output().substr(at + 12)));
  EXPECT_GE(stats.accepted, 50u);
  hub.run([&] {
    ticker.reset();
    node.reset();
    sync_source.reset();
    channel.reset();
    return 0;
  });
}

// A python-canopen-style master (python-can only, the BaseNode402 sequence) against
// `hilbridge emulate cia402 --eds` (a process) over our hub: NMT start/stop/start with TPDOs
// after every start, the walk to Operation Enabled, a profile-position move.
TEST(CanopenInterop, BaseNode402SequenceAgainstEmulateWithTheUsersEds) {
  if (!can::test::python_has("can.interfaces.socketcand"))
    GTEST_SKIP()
        << "/usr/bin/python3 with python3-can's socketcand interface is not installed (apt install python3-can)";
  can::socketcand::ServerOptions options;
  options.join_hold = std::chrono::milliseconds(50);
  can::test::Hub hub(options);
  const std::string bus = "socketcand://127.0.0.1:" + std::to_string(hub.port()) + "/can0";
  can::test::Subprocess emulate({HIL_BIN, "emulate", "cia402", "--bus", bus, "--node", "5", "--eds",
                                 std::string(HIL_TEST_SOURCE_DIR) + "/corpus/v01_no_603f.eds", "--duration", "100"});
  ASSERT_TRUE(emulate.started());
  ASSERT_TRUE(emulate.wait_for_line("node 5 up", std::chrono::seconds(30))) << emulate.output();
  EXPECT_NE(emulate.output().find("from " + std::string(HIL_TEST_SOURCE_DIR) + "/corpus/v01_no_603f.eds"),
            std::string::npos)
      << emulate.output();
  can::test::Subprocess py({"/usr/bin/python3", std::string(HIL_TEST_SOURCE_DIR) + "/basenode402_peer.py", "127.0.0.1",
                            std::to_string(hub.port()), "can0", "5"});
  ASSERT_TRUE(py.started());
  EXPECT_EQ(py.wait(std::chrono::seconds(120)), 0) << py.output() << "\nemulate:\n" << emulate.output();
  const auto out = py.output();
  for (const char* line : {"OK statusword TPDO after the first start", "OK no TPDOs while stopped",
                           "OK statusword TPDO after the second start", "OK OPERATION ENABLED",
                           "OK modes of operation display = 1 (PP)", "target reached", "DONE"})
    EXPECT_NE(out.find(line), std::string::npos) << line << "\n" << out;
}
