// SPDX-License-Identifier: MIT
// The `hilbridge` CANopen commands as a user runs them, against our simulated node behind our
// socketcand hub (no kernel needed): canopen sdo read/write with types and abort codes, nmt, scan.
#include <gtest/gtest.h>

#include "../can/hub_fixture.hpp"
#include "../can/subprocess.hpp"
#include "hil/mocks/cia402_node.hpp"

namespace can = hil::can;

namespace {

struct CliFixture : ::testing::Test {
  can::test::Hub hub;
  std::vector<std::unique_ptr<can::VirtualChannel>> channels;
  std::vector<std::unique_ptr<hil::mocks::Cia402Node>> nodes;
  std::unique_ptr<can::test::Ticker> ticker;
  void SetUp() override {
    hub.run([&] {
      for (int id : {5, 9}) {
        channels.push_back(hub.bus.attach("node" + std::to_string(id)));
        nodes.push_back(std::make_unique<hil::mocks::Cia402Node>(
            *channels.back(), hil::mocks::Cia402NodeOptions{.node = static_cast<hil::canopen::NodeId>(id)}));
        nodes.back()->start(hub.clock.now());
      }
      ticker = std::make_unique<can::test::Ticker>(hub.io, std::chrono::milliseconds(1), [&] {
        for (auto& n : nodes) n->step(hub.clock.now());
      });
      ticker->start();
      return 0;
    });
  }
  void TearDown() override {
    hub.run([&] {
      ticker.reset();  // stops first: no step of a destroyed node
      nodes.clear();
      channels.clear();
      return 0;
    });
  }
  std::string bus() const { return "socketcand://127.0.0.1:" + std::to_string(hub.port()) + "/can0"; }
  std::pair<int, std::string> cli(std::vector<std::string> args) {
    args.insert(args.begin(), HIL_BIN);
    can::test::Subprocess p(args);
    const int rc = p.wait(std::chrono::seconds(30));
    return {rc, p.output()};
  }
};

}  // namespace

TEST_F(CliFixture, SdoReadWriteTypesAndAborts) {
  auto [rc, out] = cli({"canopen", "sdo", "read", "--bus", bus(), "5", "0x1018:1", "--type", "x32"});
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("0x00000A11"), std::string::npos) << out;
  std::tie(rc, out) = cli({"canopen", "sdo", "read", "--bus", bus(), "5", "1008:0", "--type", "vs"});
  EXPECT_NE(out.find("hilbridge simulated CiA 402 drive"), std::string::npos) << out;
  std::tie(rc, out) = cli({"canopen", "sdo", "read", "--bus", bus(), "5", "1008", "--type", "vs", "--block"});
  EXPECT_NE(out.find("hilbridge simulated CiA 402 drive"), std::string::npos) << "block upload: " << out;
  std::tie(rc, out) = cli({"canopen", "sdo", "write", "--bus", bus(), "5", "0x607A:0", "-123456", "--type", "i32"});
  EXPECT_EQ(rc, 0) << out;
  std::tie(rc, out) = cli({"canopen", "sdo", "read", "--bus", bus(), "5", "0x607A:0", "--type", "i32"});
  EXPECT_NE(out.find("-123456"), std::string::npos) << out;
  std::tie(rc, out) = cli({"canopen", "sdo", "write", "--bus", bus(), "5", "0x1000:0", "1", "--type", "u32"});
  EXPECT_EQ(rc, 1);
  EXPECT_NE(out.find("0x06010002"), std::string::npos) << out;
  std::tie(rc, out) = cli({"canopen", "sdo", "read", "--bus", bus(), "5", "0x1018:9"});
  EXPECT_EQ(rc, 1);
  EXPECT_NE(out.find("0x06090011 Sub-index does not exist"), std::string::npos) << out;
  std::tie(rc, out) = cli({"canopen", "sdo", "read", "--bus", bus(), "42", "0x1000:0", "--timeout", "50ms"});
  EXPECT_EQ(rc, 1);
  EXPECT_NE(out.find("0x05040000"), std::string::npos) << "absent node: SDO timeout\n" << out;
  std::tie(rc, out) = cli({"canopen", "sdo", "write", "--bus", bus(), "5", "0x6060:0", "300", "--type", "i8"});
  EXPECT_EQ(rc, 2);
  EXPECT_NE(out.find("outside -128..127"), std::string::npos) << out;
  std::tie(rc, out) = cli({"canopen", "sdo", "read", "--bus", bus(), "5", "zz:1"});
  EXPECT_EQ(rc, 2);
  EXPECT_NE(out.find("expected INDEX:SUB"), std::string::npos) << out;
}

TEST_F(CliFixture, NmtAndScan) {
  auto [rc, out] = cli({"canopen", "nmt", "stop", "--bus", bus(), "5"});
  EXPECT_EQ(rc, 0) << out;
  std::tie(rc, out) = cli({"canopen", "sdo", "read", "--bus", bus(), "5", "0x1000:0", "--timeout", "50ms"});
  EXPECT_EQ(rc, 1) << "a stopped node serves no SDO\n" << out;
  std::tie(rc, out) = cli({"canopen", "nmt", "preop", "--bus", bus(), "all"});
  EXPECT_EQ(rc, 0) << out;
  std::tie(rc, out) = cli({"canopen", "scan", "--bus", bus(), "--timeout", "100ms"});
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("   5  0x00020192   0x00000A11  0x00000402  0x00010000"), std::string::npos) << out;
  EXPECT_NE(out.find("   9  0x00020192"), std::string::npos) << out;
  EXPECT_NE(out.find("2 node(s) answered"), std::string::npos) << out;
  std::tie(rc, out) = cli({"canopen", "nmt", "start", "--bus", bus(), "128"});
  EXPECT_EQ(rc, 2) << out;
}

namespace {
std::pair<int, std::string> run_cli(std::vector<std::string> args) {
  args.insert(args.begin(), HIL_BIN);
  can::test::Subprocess p(args);
  const int rc = p.wait(std::chrono::seconds(30));
  return {rc, p.output()};
}
}  // namespace

// `hilbridge canopen eds check` on every file of the regression corpus: drives are usable (exit 0) and
// say what the master will do; the I/O module is refused naming the missing CiA 402 objects.
TEST(EdsCli, CheckEveryCorpusFile) {
  const std::string dir = HIL_CANOPEN_CORPUS_DIR;
  for (const auto* file :
       {"v01_no_603f.eds", "v02_fixed_pdo.eds", "v03_pp_hm_only.eds", "v04_four_entries.eds", "v05_16bit.eds",
        "v06_manufacturer.eds", "v07_pdo_params.dcf", "v08_nodeid_cobs.eds", "v09_compact.eds", "v10_mixed_case.eds",
        "v11_comments.eds", "v12_one_pdo.eds", "v13_guarding_only.eds"}) {
    auto [rc, out] = run_cli({"canopen", "eds", "check", dir + "/" + file});
    EXPECT_EQ(rc, 0) << file << "\n" << out;
    EXPECT_NE(out.find("identity: vendor 0x00000100 'Corpus Motion'"), std::string::npos) << out;
    EXPECT_NE(out.find("axis (node"), std::string::npos) << out;
    EXPECT_NE(out.find("TPDO1"), std::string::npos) << out;
  }
  auto [rc, out] = run_cli({"canopen", "eds", "check", dir + "/v01_no_603f.eds", "--mode", "csp"});
  EXPECT_NE(out.find("0x603F error code: not in the EDS, left out"), std::string::npos) << out;
  EXPECT_NE(out.find("warnings: 0"), std::string::npos) << out;
  std::tie(rc, out) = run_cli({"canopen", "eds", "check", dir + "/v03_pp_hm_only.eds"});
  EXPECT_NE(out.find("axis (node 1, mode csp): not usable: 0x6502 supported drive modes = 0x00000021 (PP, HM)"),
            std::string::npos)
      << out;
  std::tie(rc, out) = run_cli({"canopen", "eds", "check", dir + "/v07_pdo_params.dcf"});
  EXPECT_NE(out.find("file: " + dir + "/v07_pdo_params.dcf (DCF)"), std::string::npos) << out;
  EXPECT_NE(out.find("axis (node 3, mode csp): ok"), std::string::npos) << "the DCF's NodeID\n" << out;
  std::tie(rc, out) = run_cli({"canopen", "eds", "check", dir + "/v11_comments.eds"});
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("v11_comments.eds:"), std::string::npos) << "warnings name the file\n" << out;
  std::tie(rc, out) = run_cli({"canopen", "eds", "check", dir + "/v14_io_module.eds"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("the EDS lacks 0x6040 controlword, 0x6041 statusword"), std::string::npos) << out;
  std::tie(rc, out) = run_cli({"canopen", "eds", "show", dir + "/v06_manufacturer.eds", "--mode", "pp", "--json"});
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("\"usable_as_axis\": true"), std::string::npos) << out;
  EXPECT_NE(out.find("\"pp\": {\"ok\": true"), std::string::npos) << out;
  std::tie(rc, out) = run_cli({"canopen", "eds", "show", dir + "/v06_manufacturer.eds"});
  EXPECT_NE(out.find("0x2000:0   Motor type"), std::string::npos) << out;
  std::tie(rc, out) = run_cli({"canopen", "eds", "check", "/nonexistent.eds"});
  EXPECT_EQ(rc, 2) << out;
}
