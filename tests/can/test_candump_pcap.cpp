// SPDX-License-Identifier: MIT
// can-utils text forms (cansend spec, candump -l lines) and the pcap bytes of CAN captures.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "hil/can/candump.hpp"
#include "hil/can/pcap.hpp"

namespace can = hil::can;
namespace cd = hil::can::candump;

namespace {

TEST(CandumpSpec, ParsesCansendSyntax) {
  EXPECT_EQ(cd::parse_frame_spec("123#DEADBEEF").value(), can::make_frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF}));
  EXPECT_EQ(cd::parse_frame_spec("080#").value(), can::make_frame(0x080, {}));
  EXPECT_EQ(cd::parse_frame_spec("5A1#11.22.33.44.55.66.77.88").value(),
            can::make_frame(0x5A1, {0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77, 0x88}));
  auto ext = cd::parse_frame_spec("1F334455#1122334455667788").value();
  EXPECT_TRUE(ext.extended);
  EXPECT_EQ(ext.id, 0x1F334455u);
  auto rtr = cd::parse_frame_spec("705#R").value();
  EXPECT_TRUE(rtr.rtr);
  EXPECT_EQ(rtr.dlc, 0);
  EXPECT_EQ(cd::parse_frame_spec("705#R1").value(), can::make_remote_frame(0x705, 1));
  auto err = cd::parse_frame_spec("20000040#0000000000000000").value();
  EXPECT_TRUE(err.error);
  EXPECT_EQ(err.id, can::error_class::bus_off);
}

TEST(CandumpSpec, RejectsBadSpecsWithTheRightCode) {
  const std::pair<const char*, cd::ParseErrc> cases[] = {
      {"123DEADBEEF", cd::ParseErrc::missing_separator},
      {"12#00", cd::ParseErrc::bad_id},
      {"1234#00", cd::ParseErrc::bad_id},
      {"800#00", cd::ParseErrc::bad_id},
      {"G23#00", cd::ParseErrc::bad_id},
      {"4FFFFFFF#00", cd::ParseErrc::bad_id},
      {"123#0", cd::ParseErrc::bad_data},
      {"123#001122334455667788", cd::ParseErrc::bad_data},
      {"123#XY", cd::ParseErrc::bad_data},
      {"123#R9", cd::ParseErrc::bad_rtr_length},
      {"123#R12", cd::ParseErrc::bad_rtr_length},
      {"123##1DEAD", cd::ParseErrc::fd_not_supported},
      {"123#1122_5", cd::ParseErrc::bad_data},
  };
  for (const auto& [text, code] : cases) {
    auto r = cd::parse_frame_spec(text);
    ASSERT_FALSE(r) << text;
    EXPECT_EQ(r.error(), cd::make_error_code(code)) << text << ": " << r.error().message();
  }
}

TEST(CandumpLog, ParsesAndFormatsLogLines) {
  auto r = cd::parse_log_line("(1700000000.123456) can0 123#DEADBEEF\n").value();
  EXPECT_EQ(r.time, (can::socketcand::Timestamp{1700000000, 123456}));
  EXPECT_EQ(r.interface, "can0");
  EXPECT_EQ(r.frame, can::make_frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF}));
  std::string s;
  cd::format_log_line(s, r);
  EXPECT_EQ(s, "(1700000000.123456) can0 123#DEADBEEF");
  EXPECT_TRUE(cd::parse_log_line("(1.5) vcan0 7E5#R T").has_value());
  EXPECT_EQ(cd::parse_log_line("(1.5) vcan0 7E5#R T").value().time.usec, 500000u);
  EXPECT_EQ(cd::parse_log_line("1.5 vcan0 123#").error(), cd::make_error_code(cd::ParseErrc::bad_timestamp));
  EXPECT_EQ(cd::parse_log_line("(1.a) vcan0 123#").error(), cd::make_error_code(cd::ParseErrc::bad_timestamp));
  EXPECT_EQ(cd::parse_log_line("(1.5)vcan0 123#").error(), cd::make_error_code(cd::ParseErrc::bad_interface));
  EXPECT_EQ(cd::parse_log_line("(1.5) vcan0").error(), cd::make_error_code(cd::ParseErrc::bad_interface));
  EXPECT_EQ(cd::parse_log_line("(1.5) vcan0 123# extra").error(), cd::make_error_code(cd::ParseErrc::trailing_garbage));
}

TEST(CandumpLog, RoundTripsRandomRecords) {
  std::mt19937 rng(42);
  for (int i = 0; i < 2000; ++i) {
    cd::LogRecord r;
    r.time = {static_cast<std::int64_t>(rng() % 2000000000u), static_cast<std::uint32_t>(rng() % 1000000)};
    r.interface = (rng() & 1) ? "can0" : "vcan1";
    const auto kind = rng() % 4;
    r.frame.extended = kind == 1;
    r.frame.rtr = kind == 2;
    r.frame.error = kind == 3;
    r.frame.id =
        static_cast<std::uint32_t>(rng()) & (r.frame.extended || r.frame.error ? can::eff_mask : can::sff_mask);
    r.frame.dlc = r.frame.error ? 8 : static_cast<std::uint8_t>(rng() % 9);
    if (!r.frame.rtr)
      for (int k = 0; k < r.frame.dlc; ++k)
        r.frame.data[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(rng());
    std::string s;
    cd::format_log_line(s, r);
    auto back = cd::parse_log_line(s);
    ASSERT_TRUE(back) << s << ": " << back.error().message();
    EXPECT_EQ(*back, r) << s;
  }
}

TEST(Pcap, GlobalHeaderIsLibpcapWithLinktype227) {
  const auto h = can::pcap::make_global_header();
  const std::vector<std::uint8_t> expected = {0xD4, 0xC3, 0xB2, 0xA1, 0x02, 0x00, 0x04, 0x00, 0,    0,    0,    0,
                                              0,    0,    0,    0,    0xFF, 0xFF, 0x00, 0x00, 0xE3, 0x00, 0x00, 0x00};
  EXPECT_EQ(std::vector<std::uint8_t>(h.begin(), h.end()), expected);
}

TEST(Pcap, RecordHasBigEndianCanIdWithFlags) {
  const auto r = can::pcap::make_record(can::make_frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF}), {1700000000, 123456});
  const std::vector<std::uint8_t> expected = {0x00, 0xF1, 0x53, 0x65,                 // 1700000000 LE
                                              0x40, 0xE2, 0x01, 0x00,                 // 123456 LE
                                              0x10, 0,    0,    0,    0x10, 0, 0, 0,  // incl/orig length 16
                                              0x00, 0x00, 0x01, 0x23,                 // can_id BE
                                              0x04, 0x00, 0x00, 0x00,                 // len, flags, reserved
                                              0xDE, 0xAD, 0xBE, 0xEF, 0,    0, 0, 0};
  EXPECT_EQ(std::vector<std::uint8_t>(r.begin(), r.end()), expected);
  const auto ext = can::pcap::make_record(can::make_extended_frame(0x1ABCDEF0, std::vector<std::uint8_t>{}), {});
  EXPECT_EQ(ext[16], 0x80 | 0x1A);  // CAN_EFF_FLAG
  EXPECT_EQ(ext[17], 0xBC);
  EXPECT_EQ(ext[19], 0xF0);
  const auto rtr = can::pcap::make_record(can::make_remote_frame(0x705, 1), {});
  EXPECT_EQ(rtr[16], 0x40);  // CAN_RTR_FLAG
  EXPECT_EQ(rtr[18], 0x07);
  EXPECT_EQ(rtr[19], 0x05);
  EXPECT_EQ(rtr[20], 1);
  const auto err = can::pcap::make_record(can::make_error_frame(can::error_class::bus_off), {});
  EXPECT_EQ(err[16], 0x20);  // CAN_ERR_FLAG
  EXPECT_EQ(err[19], 0x40);
  EXPECT_EQ(err[20], 8);
}

}  // namespace
