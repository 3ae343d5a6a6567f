// SPDX-License-Identifier: MIT
// Interop: Wireshark's own dissectors (tshark) read the pcap bytes we write and decode CANopen
// from them ("Decode As" CANopen). Skips with a reason when tshark is not installed.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "hil/can/pcap.hpp"
#include "subprocess.hpp"

namespace can = hil::can;

namespace {

TEST(PcapWireshark, TsharkDecodesOurCaptureAsCanAndCanopen) {
  if (::access("/usr/bin/tshark", X_OK) != 0) GTEST_SKIP() << "tshark is not installed (apt install tshark)";
  const auto path = std::filesystem::temp_directory_path() / ("hil-can-" + std::to_string(::getpid()) + ".pcap");
  {
    std::ofstream out(path, std::ios::binary);
    const auto header = can::pcap::make_global_header();
    out.write(reinterpret_cast<const char*>(header.data()), header.size());
    const std::vector<can::Frame> frames = {
        can::make_frame(0x000, {0x01, 0x00}),                          // NMT start all
        can::make_frame(0x080, {}),                                    // SYNC
        can::make_frame(0x602, {0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0}),  // SDO upload request
        can::make_frame(0x705, {0x05}),                                // heartbeat operational
        can::make_remote_frame(0x705, 1),                              // node guarding RTR
        can::make_extended_frame(0x1F334455, std::vector<std::uint8_t>{0x11, 0x22}),
    };
    std::uint32_t usec = 0;
    for (const auto& f : frames) {
      const auto rec = can::pcap::make_record(f, {1700000000, usec++});
      out.write(reinterpret_cast<const char*>(rec.data()), rec.size());
    }
  }
  can::test::Subprocess canopen({"/usr/bin/tshark", "-r", path.string(), "-d", "can.subdissector,canopen"});
  EXPECT_EQ(canopen.wait(std::chrono::seconds(60)), 0) << canopen.output();
  const auto& text = canopen.output();
  EXPECT_NE(text.find("NMT: Start remote node"), std::string::npos) << text;
  EXPECT_NE(text.find("SYNC"), std::string::npos) << text;
  EXPECT_NE(text.find("Initiate upload request"), std::string::npos) << text;
  EXPECT_NE(text.find("Operational"), std::string::npos) << text;
  can::test::Subprocess fields({"/usr/bin/tshark", "-r", path.string(), "-T", "fields", "-e", "can.id", "-e",
                                "can.flags.xtd", "-e", "can.flags.rtr", "-e", "can.len"});
  EXPECT_EQ(fields.wait(std::chrono::seconds(60)), 0) << fields.output();
  EXPECT_NE(fields.output().find("1797\t0\t1\t1"), std::string::npos) << fields.output();       // 0x705 RTR
  EXPECT_NE(fields.output().find("523453525\t1\t0\t2"), std::string::npos) << fields.output();  // 29-bit
  std::filesystem::remove(path);
}

}  // namespace
