// SPDX-License-Identifier: MIT
// `hilbridge can` end to end, as a user runs it: a hub on a free port, dump with --log and
// --pcap, send in cansend syntax, replay of the written log; pcap bytes checked field by field.
#include <gtest/gtest.h>

#include <signal.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "hil/can/candump.hpp"
#include "subprocess.hpp"

namespace can = hil::can;
using can::test::Subprocess;

namespace {

const std::string hilbridge = HIL_BINARY;

std::vector<std::uint8_t> read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t le32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) | (static_cast<std::uint32_t>(b[at + 3]) << 24);
}
std::uint32_t be32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (static_cast<std::uint32_t>(b[at]) << 24) | (b[at + 1] << 16) | (b[at + 2] << 8) | b[at + 3];
}

class CanCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("hil-can-cli-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    hub_ = std::make_unique<Subprocess>(
        std::vector<std::string>{hilbridge, "can", "hub", "--listen", "127.0.0.1:0", "--join-hold", "0ms"});
    auto line = hub_->wait_for_line("connect with");
    ASSERT_TRUE(line) << hub_->output();
    const auto at = line->find("socketcand://");
    ASSERT_NE(at, std::string::npos);
    url_ = line->substr(at, line->find(' ', at) - at);
  }
  void TearDown() override {
    hub_->terminate();
    EXPECT_EQ(hub_->wait(), 0) << hub_->output();
    std::filesystem::remove_all(dir_);
  }
  std::filesystem::path dir_;
  std::unique_ptr<Subprocess> hub_;
  std::string url_;
};

TEST_F(CanCli, DumpSendPcapAndReplay) {
  const auto log = dir_ / "dump.log";
  const auto pcap = dir_ / "dump.pcap";
  Subprocess dump({hilbridge, "can", "dump", "--bus", url_, "-n", "3", "--log", log.string(), "--pcap", pcap.string()});
  ASSERT_TRUE(dump.wait_for_line("listening on")) << dump.output();
  // The dump client is connected once it printed; sending now cannot race its handshake.
  Subprocess send({hilbridge, "can", "send", "--bus", url_, "123#DEADBEEF", "080#", "1F334455#11.22"});
  EXPECT_EQ(send.wait(), 0) << send.output();
  EXPECT_EQ(dump.wait(), 0) << dump.output();

  std::vector<can::candump::LogRecord> records;
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);) {
    auto r = can::candump::parse_log_line(line);
    ASSERT_TRUE(r) << line;
    records.push_back(*r);
  }
  ASSERT_EQ(records.size(), 3u) << dump.output();
  EXPECT_EQ(records[0].interface, "can0");
  EXPECT_EQ(can::candump::format_frame_spec(records[0].frame), "123#DEADBEEF");
  EXPECT_EQ(can::candump::format_frame_spec(records[1].frame), "080#");
  EXPECT_EQ(can::candump::format_frame_spec(records[2].frame), "1F334455#1122");
  EXPECT_NE(dump.output().find(") can0 123#DEADBEEF"), std::string::npos) << dump.output();

  const auto bytes = read_file(pcap);
  ASSERT_EQ(bytes.size(), 24u + 3u * 32u);
  EXPECT_EQ(le32(bytes, 0), 0xA1B2C3D4u);
  EXPECT_EQ(le32(bytes, 20), 227u);  // LINKTYPE_CAN_SOCKETCAN
  EXPECT_EQ(le32(bytes, 24), static_cast<std::uint32_t>(records[0].time.sec));
  EXPECT_EQ(le32(bytes, 28), records[0].time.usec);
  EXPECT_EQ(le32(bytes, 32), 16u);
  EXPECT_EQ(be32(bytes, 40), 0x123u);
  EXPECT_EQ(bytes[44], 4);
  EXPECT_EQ(be32(bytes, 48), 0xDEADBEEFu);
  EXPECT_EQ(be32(bytes, 24 + 2 * 32 + 16), 0x80000000u | 0x1F334455u);  // CAN_EFF_FLAG, big-endian

  // The log replays onto the bus (as fast as possible) and a second dump sees the same frames.
  Subprocess dump2({hilbridge, "can", "dump", "--bus", url_, "-n", "3"});
  ASSERT_TRUE(dump2.wait_for_line("listening on")) << dump2.output();
  Subprocess replay({hilbridge, "can", "replay", "--bus", url_, "--speed", "0", log.string()});
  EXPECT_EQ(replay.wait(), 0) << replay.output();
  EXPECT_EQ(dump2.wait(), 0) << dump2.output();
  EXPECT_NE(dump2.output().find(") can0 1F334455#1122"), std::string::npos) << dump2.output();
}

TEST_F(CanCli, BadInputGetsClearErrors) {
  Subprocess bad_frame({hilbridge, "can", "send", "--bus", url_, "123#00", "12#00"});
  EXPECT_EQ(bad_frame.wait(), 2);
  EXPECT_NE(bad_frame.output().find("frame 2 '12#00': bad CAN id"), std::string::npos) << bad_frame.output();
  Subprocess bad_url({hilbridge, "can", "dump", "--bus", "socketcand://127.0.0.1"});
  EXPECT_EQ(bad_url.wait(), 2);
  EXPECT_NE(bad_url.output().find("missing /BUS"), std::string::npos) << bad_url.output();
  // A bus the server cannot open: the checked thing failed, 1 (docs/cli.md, "Exit codes").
  Subprocess bad_bus({hilbridge, "can", "send", "--bus", url_.substr(0, url_.rfind('/')) + "/nope", "123#00"});
  EXPECT_EQ(bad_bus.wait(), 1);
  EXPECT_NE(bad_bus.output().find("could not open bus"), std::string::npos) << bad_bus.output();
  const auto bad_log = dir_ / "bad.log";
  std::ofstream(bad_log) << "(1.000000) can0 123#00\n(2.000000) can0 123#0\n";
  Subprocess replay({hilbridge, "can", "replay", "--bus", url_, bad_log.string()});
  EXPECT_EQ(replay.wait(), 2);
  EXPECT_NE(replay.output().find("bad.log:2: bad data"), std::string::npos) << replay.output();
  Subprocess listen({hilbridge, "can", "hub", "--listen", "localhost"});
  EXPECT_EQ(listen.wait(), 2);
  EXPECT_NE(listen.output().find("expected HOST:PORT"), std::string::npos) << listen.output();
}

}  // namespace
