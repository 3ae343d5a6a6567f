// SPDX-License-Identifier: MIT
// Bus URLs: parsing table, canonical round trip, and make_channel for each backend.
#include <gtest/gtest.h>

#include "hil/can/bus_url.hpp"
#include "hil/can/io/make_channel.hpp"
#include "hub_fixture.hpp"

namespace can = hil::can;
using Kind = can::BusUrl::Kind;

namespace {

TEST(BusUrl, ParsesEveryForm) {
  struct Case {
    const char* text;
    can::BusUrl expected;
  };
  const Case cases[] = {
      {"vcan0", {Kind::socketcan, "vcan0", "", 29536}},
      {"can0", {Kind::socketcan, "can0", "", 29536}},
      {"socketcan:my-can.1", {Kind::socketcan, "my-can.1", "", 29536}},
      {"socketcand://127.0.0.1:29536/can0", {Kind::socketcand, "can0", "127.0.0.1", 29536}},
      {"socketcand://gateway.local/vcan1", {Kind::socketcand, "vcan1", "gateway.local", 29536}},
      {"socketcand://[::1]:4000/can0", {Kind::socketcand, "can0", "::1", 4000}},
      {"virtual:plant", {Kind::virtual_bus, "plant", "", 29536}},
  };
  for (const auto& c : cases) {
    auto u = can::parse_bus_url(c.text);
    ASSERT_TRUE(u) << c.text << ": " << u.error();
    EXPECT_EQ(*u, c.expected) << c.text;
    auto again = can::parse_bus_url(u->to_string());
    ASSERT_TRUE(again) << u->to_string();
    EXPECT_EQ(*again, *u);
  }
}

TEST(BusUrl, RejectsWithSentencesThatSayWhatIsAccepted) {
  const std::pair<const char*, const char*> cases[] = {
      {"", "expected an interface name"},
      {"averyveryverylongname0", "expected an interface name"},
      {"vcan 0", "expected an interface name"},
      {"tcp://x/can0", "unknown scheme"},
      {"socketcand://127.0.0.1:29536", "missing /BUS"},
      {"socketcand://127.0.0.1:0/can0", "port must be"},
      {"socketcand://127.0.0.1:70000/can0", "port must be"},
      {"socketcand://127.0.0.1:/can0", "empty port"},
      {"socketcand:///can0", "missing host"},
      {"socketcand://[::1/can0", "unterminated"},
      {"socketcand://::1:29536/can0", "brackets"},
      // Found by fuzzing: a '[' inside the brackets made a URL that to_string() could not write back.
      {"socketcand://[[0]/1", "characters no host"},
      {"socketcand://[%0]/vn2", "characters no host"},
      {"socketcand://ho st:1/can0", "characters no host"},
      {"socketcand://h/abcdefghijklmnopq", "bus name"},
      {"virtual:", "virtual bus name"},
      {"socketcan:", "interface name"},
  };
  for (const auto& [text, needle] : cases) {
    auto u = can::parse_bus_url(text);
    ASSERT_FALSE(u) << text;
    EXPECT_NE(u.error().find(needle), std::string::npos) << text << " -> " << u.error();
    EXPECT_NE(u.error().find(std::string("'") + text + "'"), std::string::npos) << u.error();
  }
}

TEST(MakeChannel, VirtualBusesAreSharedByName) {
  hil::VirtualClock clock;
  asio::io_context io;
  can::VirtualBusRegistry registry(clock);
  can::ChannelRequest req{io.get_executor(), clock, &registry, "a"};
  auto a = can::make_channel("virtual:plant", req);
  req.participant = "b";
  auto b = can::make_channel("virtual:plant", req);
  auto other = can::make_channel("virtual:other", req);
  ASSERT_TRUE(a && b && other);
  std::vector<can::Frame> rx_b, rx_other;
  (*b)->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { rx_b.push_back(f); });
  (*other)->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { rx_other.push_back(f); });
  ASSERT_FALSE((*a)->send(can::make_frame(0x1, {1})));
  registry.get("plant").deliver(clock.now());
  registry.get("other").deliver(clock.now());
  EXPECT_EQ(rx_b.size(), 1u);
  EXPECT_TRUE(rx_other.empty());
  EXPECT_EQ((*a)->name(), "a");
  can::ChannelRequest no_registry{io.get_executor(), clock};
  auto refused = can::make_channel("virtual:plant", no_registry);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("virtual:plant"), std::string::npos);
}

TEST(MakeChannel, SocketcandAndSocketcanErrorsCarryDiagnostics) {
  can::test::Hub hub;
  can::ChannelRequest req{hub.io.get_executor(), hub.clock};
  auto ch = can::make_channel("socketcand://127.0.0.1:" + std::to_string(hub.port()) + "/can0", req);
  ASSERT_TRUE(ch) << ch.error().message;
  EXPECT_EQ(hub.run([&] { return hub.bus.participant_count(); }), 1u);
  auto wrong = can::make_channel("socketcand://127.0.0.1:" + std::to_string(hub.port()) + "/can9", req);
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.error().message.find("could not open bus"), std::string::npos) << wrong.error().message;
  auto bad = can::make_channel("socketcand://127.0.0.1", req);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, std::errc::invalid_argument);
  auto missing = can::make_channel("hilnocan3", req);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("hilnocan3"), std::string::npos) << missing.error().message;
  hub.run([&] { ch->reset(); });
}

}  // namespace
