// SPDX-License-Identifier: MIT
// Real kernel (label `kernel`): hilbridge's CANopen master and the simulated CiA 402 node in
// separate processes over vcan0 — `hilbridge emulate cia402` as the node, `hilbridge sdo`,
// `hilbridge scan` and `hilbridge run` (scenario with `bus: vcan0`) as the master.
// Skips when vcan0 does not exist (run it inside tests/vm/run-in-kernel.sh).
#include <gtest/gtest.h>

#include <net/if.h>

#include "../can/subprocess.hpp"

namespace {

bool have_vcan0() {
  return ::if_nametoindex("vcan0") != 0;
}

std::pair<int, std::string> cli(std::vector<std::string> args, std::chrono::seconds limit = std::chrono::seconds(60)) {
  args.insert(args.begin(), HIL_BIN);
  hil::can::test::Subprocess p(args);
  const int rc = p.wait(limit);
  return {rc, p.output()};
}

}  // namespace

TEST(CanopenKernel, MasterAndNodeInSeparateProcessesOverVcan0) {
  if (!have_vcan0())
    GTEST_SKIP()
        << "vcan0 does not exist (run inside tests/vm/run-in-kernel.sh, or: modprobe vcan && ip link add dev vcan0 "
           "type vcan && ip link set up vcan0)";
  hil::can::test::Subprocess node({HIL_BIN, "emulate", "cia402", "--bus", "vcan0", "--node", "5", "--duration", "60s"});
  ASSERT_TRUE(node.started());
  ASSERT_TRUE(node.wait_for_line("node 5 up", std::chrono::seconds(30))) << node.output();

  auto [rc, out] =
      cli({"canopen", "sdo", "read", "--bus", "vcan0", "5", "0x1018:2", "--type", "x32", "--timeout", "2s"});
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("0x00000402"), std::string::npos) << out;
  std::tie(rc, out) =
      cli({"canopen", "sdo", "read", "--bus", "vcan0", "5", "0x1008:0", "--type", "vs", "--block", "--timeout", "2s"});
  EXPECT_NE(out.find("hilbridge simulated CiA 402 drive"), std::string::npos) << out;
  std::tie(rc, out) = cli({"canopen", "scan", "--bus", "vcan0", "--timeout", "1s"});
  EXPECT_NE(out.find("   5  0x00020192   0x00000A11"), std::string::npos) << out;
  std::tie(rc, out) = cli({"run", HIL_SCENARIO}, std::chrono::seconds(120));
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("result: OK"), std::string::npos) << out;
  EXPECT_NE(out.find("1 of 1 node(s) started"), std::string::npos) << out;
  node.terminate();
}
