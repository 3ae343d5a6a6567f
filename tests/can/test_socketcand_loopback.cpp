// SPDX-License-Identifier: MIT
// socketcand end to end in one process over loopback TCP: our client channel against our hub
// (server + virtual bus on real time), exact wire bytes from a raw TCP peer, and robustness
// against garbage, overlong elements and clients that vanish mid-element.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <thread>

#include <asio/connect.hpp>
#include <asio/read.hpp>
#include <asio/write.hpp>

#include "hil/can/io/socketcand_channel.hpp"
#include "hub_fixture.hpp"

namespace can = hil::can;
namespace sc = hil::can::socketcand;
using can::test::Hub;
using can::test::Inbox;

namespace {

std::unique_ptr<sc::SocketcandChannel> connect(Hub& hub, const std::string& bus = "can0") {
  std::string diag;
  auto ch = sc::SocketcandChannel::connect(hub.io.get_executor(), hub.clock, "127.0.0.1", hub.port(), bus, {}, &diag);
  EXPECT_TRUE(ch.has_value()) << diag;
  return ch ? std::move(*ch) : nullptr;
}

TEST(SocketcandLoopback, ClientsAndLocalNodeShareTheBus) {
  Hub hub;
  Inbox local_rx, a_rx, b_rx;
  auto local = hub.run([&] {
    auto ch = hub.bus.attach("local");
    ch->set_receive_handler(local_rx.handler());
    return ch;
  });
  auto a = connect(hub);
  auto b = connect(hub);
  ASSERT_TRUE(a && b);
  a->set_receive_handler(a_rx.handler());  // before any traffic: the io thread has not delivered yet
  b->set_receive_handler(b_rx.handler());
  EXPECT_EQ(hub.run([&] { return hub.bus.participant_count(); }), 3u);

  const auto f1 = can::make_frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF});
  ASSERT_FALSE(a->send(f1));
  auto got_local = local_rx.wait_for(1);
  auto got_b = b_rx.wait_for(1);
  ASSERT_EQ(got_local.size(), 1u);
  ASSERT_EQ(got_b.size(), 1u);
  EXPECT_EQ(got_local[0], f1);
  EXPECT_EQ(got_b[0], f1);

  const auto sync = can::make_frame(0x080, {});
  const auto ext = can::make_extended_frame(0x1ABCDEF0, std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6, 7, 8});
  hub.run([&] {
    EXPECT_FALSE(local->send(sync));
    EXPECT_FALSE(local->send(ext));
  });
  auto got_a = a_rx.wait_for(2);
  got_b = b_rx.wait_for(3);
  ASSERT_EQ(got_a.size(), 2u);
  EXPECT_EQ(got_a[0], sync);
  EXPECT_EQ(got_a[1], ext);
  ASSERT_EQ(got_b.size(), 3u);
  EXPECT_EQ(got_b[2], ext);
  EXPECT_TRUE(a_rx.snapshot().size() == 2u) << "a must not receive its own frame";
  EXPECT_EQ(a->stats().tx_frames, 1u);
  EXPECT_EQ(b->stats().rx_frames, 3u);
  EXPECT_EQ(a->send(can::make_remote_frame(0x705, 1)), std::make_error_code(std::errc::operation_not_supported));
  hub.run([&] { local.reset(); });
}

TEST(SocketcandLoopback, UnknownBusIsRefusedWithADiagnostic) {
  Hub hub;
  std::string diag;
  auto ch =
      sc::SocketcandChannel::connect(hub.io.get_executor(), hub.clock, "127.0.0.1", hub.port(), "can7", {}, &diag);
  ASSERT_FALSE(ch.has_value());
  EXPECT_EQ(ch.error(), std::make_error_code(std::errc::no_such_device));
  EXPECT_NE(diag.find("could not open bus"), std::string::npos) << diag;
  EXPECT_EQ(hub.run([&] { return hub.server->stats().bus_open_failures; }), 1u);
}

TEST(SocketcandLoopback, ConnectionRefusedIsReported) {
  asio::io_context io;
  hil::SteadyClock clock;
  std::string diag;
  // Port 1 on loopback: nothing listens there in a test environment.
  auto ch = sc::SocketcandChannel::connect(io.get_executor(), clock, "127.0.0.1", 1, "can0", {}, &diag);
  ASSERT_FALSE(ch.has_value());
  EXPECT_NE(diag.find("connect failed"), std::string::npos) << diag;
}

/// A raw TCP peer with bounded reads (the io thread of the hub serves the other end).
class RawPeer {
 public:
  explicit RawPeer(std::uint16_t port) { sock_.connect({asio::ip::make_address("127.0.0.1"), port}); }
  void send(std::string_view s) { asio::write(sock_, asio::buffer(s)); }
  /// Read until `count` elements arrived (bounded by the hub answering; test timeout otherwise).
  std::vector<std::string> read_elements(std::size_t count) {
    std::vector<std::string> out;
    sc::ElementSplitter::Item item;
    while (out.size() < count) {
      while (out.size() < count && splitter_.next(item))
        if (!item.error) out.emplace_back(item.element);
      if (out.size() >= count) break;
      std::array<char, 512> buf;
      std::error_code ec;
      const auto n = sock_.read_some(asio::buffer(buf), ec);
      if (ec) break;
      splitter_.feed(std::string_view(buf.data(), n));
    }
    return out;
  }
  void close() { sock_.close(); }

 private:
  asio::io_context io_;
  asio::ip::tcp::socket sock_{io_};
  sc::ElementSplitter splitter_;
};

TEST(SocketcandLoopback, WireBytesMatchTheDaemon) {
  sc::ServerOptions options;
  options.to_wire_time = [](hil::TimePoint) { return sc::Timestamp{1700000000, 123}; };
  Hub hub(options);
  Inbox local_rx;
  auto local = hub.run([&] {
    auto ch = hub.bus.attach("local");
    ch->set_receive_handler(local_rx.handler());
    return ch;
  });
  RawPeer peer(hub.port());
  EXPECT_EQ(peer.read_elements(1), std::vector<std::string>{"< hi >"});
  peer.send("< open can0 >");
  EXPECT_EQ(peer.read_elements(1), std::vector<std::string>{"< ok >"});
  peer.send("< rawmode >");
  EXPECT_EQ(peer.read_elements(1), std::vector<std::string>{"< ok >"});
  peer.send("< send 601 8 40 18 10 1 0 0 0 0 >< send 80 0  >");  // concatenated, python-style unpadded
  auto rx = local_rx.wait_for(2);
  ASSERT_EQ(rx.size(), 2u);
  EXPECT_EQ(rx[0], can::make_frame(0x601, {0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0}));
  EXPECT_EQ(rx[1], can::make_frame(0x080, {}));
  hub.run([&] {
    EXPECT_FALSE(local->send(can::make_frame(0x581, {0x43, 0x18, 0x10, 0x01, 0x04, 0, 0, 0})));
    EXPECT_FALSE(local->send(can::make_frame(0x080, {})));
    EXPECT_FALSE(local->send(can::make_remote_frame(0x705, 1)));  // not representable: dropped
    EXPECT_FALSE(local->send(can::make_extended_frame(0x18FF0001, std::vector<std::uint8_t>{0xAA})));
  });
  EXPECT_EQ(peer.read_elements(3),
            (std::vector<std::string>{"< frame 581 1700000000.000123 4318100104000000 >",
                                      "< frame 080 1700000000.000123  >", "< frame 18FF0001 1700000000.000123 AA >"}));
  EXPECT_EQ(hub.run([&] { return hub.server->stats().rtr_not_forwarded; }), 1u);
  peer.send("< echo >");
  EXPECT_EQ(peer.read_elements(1), std::vector<std::string>{"< echo >"});
  hub.run([&] { local.reset(); });
}

TEST(SocketcandLoopback, SurvivesGarbageAndClientsVanishingMidElement) {
  Hub hub;
  Inbox local_rx;
  auto local = hub.run([&] {
    auto ch = hub.bus.attach("local");
    ch->set_receive_handler(local_rx.handler());
    return ch;
  });
  {
    RawPeer peer(hub.port());
    EXPECT_EQ(peer.read_elements(1), std::vector<std::string>{"< hi >"});
    peer.send("< send 123 1 00 >");  // before open
    auto e = peer.read_elements(1);
    ASSERT_EQ(e.size(), 1u);
    EXPECT_NE(e[0].find("open a bus first"), std::string::npos) << e[0];
    peer.send("\x01\x02garbage< open can0 >");
    EXPECT_EQ(peer.read_elements(1), std::vector<std::string>{"< ok >"});
    peer.send("< rawmode >< send 12G 1 00 >< bogus >< send 123 2 00 >< add 1 >");
    e = peer.read_elements(5);
    ASSERT_EQ(e.size(), 5u);
    EXPECT_EQ(e[0], "< ok >");
    EXPECT_NE(e[1].find("bad CAN id"), std::string::npos) << e[1];
    EXPECT_NE(e[2].find("unknown command"), std::string::npos) << e[2];
    EXPECT_NE(e[3].find("bad data"), std::string::npos) << e[3];
    EXPECT_NE(e[4].find("not supported"), std::string::npos) << e[4];
    peer.send("<" + std::string(1000, 'x'));
    e = peer.read_elements(1);
    ASSERT_EQ(e.size(), 1u);
    EXPECT_NE(e[0].find("too long"), std::string::npos) << e[0];
    peer.send("> < send 7FF 1 5A >");
    EXPECT_EQ(local_rx.wait_for(1).size(), 1u);
    peer.send("< send 123 4 de ad");  // vanish mid-element
    peer.close();
  }
  // The hub keeps serving: a fresh client works and the vanished one left the bus.
  auto c = connect(hub);
  ASSERT_TRUE(c);
  ASSERT_FALSE(c->send(can::make_frame(0x100, {1})));
  auto rx = local_rx.wait_for(2);
  ASSERT_EQ(rx.size(), 2u);
  EXPECT_EQ(rx[0], can::make_frame(0x7FF, {0x5A}));
  EXPECT_EQ(rx[1], can::make_frame(0x100, {1}));
  const auto stats = hub.run([&] { return hub.server->stats(); });
  EXPECT_GE(stats.protocol_errors, 6u);
  EXPECT_EQ(stats.accepted, 2u);
  EXPECT_EQ(stats.active, 1u);
  EXPECT_EQ(hub.run([&] { return hub.bus.participant_count(); }), 2u);
  hub.run([&] { local.reset(); });
}

TEST(SocketcandLoopback, JoinHoldQueuesFramesUntilTheClientSpeaksAndDropsNone) {
  sc::ServerOptions options;
  options.join_hold = std::chrono::hours(1);
  Hub hub(options);
  Inbox local_rx;
  auto local = hub.run([&] {
    auto ch = hub.bus.attach("local");
    ch->set_receive_handler(local_rx.handler());
    return ch;
  });
  Inbox rx;
  auto a = connect(hub);
  ASSERT_TRUE(a);
  a->set_receive_handler(rx.handler());
  hub.run([&] {
    EXPECT_FALSE(local->send(can::make_frame(0x80, {})));
    EXPECT_FALSE(local->send(can::make_frame(0x705, {0x7F})));
  });
  // Bounded wait for the bus to deliver: both frames are queued for the joining client.
  for (int i = 0; i < 2000 && hub.run([&] { return hub.server->stats().held_at_join; }) < 2; ++i) {
  }
  EXPECT_EQ(hub.run([&] { return hub.server->stats().held_at_join; }), 2u);
  EXPECT_TRUE(rx.snapshot().empty());
  // The client's first element proves it read its `< ok >`: the held frames follow, in order.
  ASSERT_FALSE(a->send(can::make_frame(0x605, {0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0})));
  auto got = rx.wait_for(2);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0], can::make_frame(0x80, {}));
  EXPECT_EQ(got[1], can::make_frame(0x705, {0x7F}));
  EXPECT_EQ(local_rx.wait_for(1).size(), 1u);
  const auto stats = hub.run([&] { return hub.server->stats(); });
  EXPECT_EQ(stats.dropped_slow_client, 0u);
  hub.run([&] { local.reset(); });
}

TEST(SocketcandLoopback, JoinHoldEndsAfterItsTimeForASilentClient) {
  sc::ServerOptions options;
  options.join_hold = std::chrono::milliseconds(20);
  Hub hub(options);
  auto local = hub.run([&] { return hub.bus.attach("local"); });
  Inbox rx;
  auto a = connect(hub);
  ASSERT_TRUE(a);
  a->set_receive_handler(rx.handler());
  hub.run([&] { EXPECT_FALSE(local->send(can::make_frame(0x80, {}))); });
  auto got = rx.wait_for(1);  // bounded (5 s); the hold ends after 20 ms without a word from the client
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], can::make_frame(0x80, {}));
  hub.run([&] { local.reset(); });
}

TEST(SocketcandLoopback, ClientMayBeDestroyedFromAnotherThreadWhileFramesArrive) {
  Hub hub;
  auto local = hub.run([&] { return hub.bus.attach("local"); });
  for (int round = 0; round < 5; ++round) {
    auto a = connect(hub);
    ASSERT_TRUE(a);
    std::atomic<int> seen{0};
    a->set_receive_handler([&seen](const can::Frame&, hil::TimePoint) { ++seen; });
    hub.run([&] {
      for (int i = 0; i < 2000; ++i) (void)local->send(can::make_frame(0x181, {static_cast<std::uint8_t>(i)}));
    });
    while (seen.load() == 0) std::this_thread::yield();  // bounded by the ctest timeout
    a.reset();                                           // test thread, while the io thread is delivering
    const int after = seen.load();
    hub.run([] {});  // let the io thread run any handler that was still queued
    EXPECT_EQ(seen.load(), after) << "no handler may run after the destructor returned";
  }
  hub.run([&] { local.reset(); });
}

TEST(SocketcandLoopback, ClientSeesServerDisconnectAsNetworkDown) {
  auto hub = std::make_unique<Hub>();
  auto a = connect(*hub);
  ASSERT_TRUE(a);
  hub->run([&] { hub->server->close(); });
  // Bounded wait for the close to propagate through the io thread.
  for (int i = 0; i < 500 && a->connected(); ++i) hub->run([] {});
  EXPECT_FALSE(a->connected());
  EXPECT_EQ(a->send(can::make_frame(1, {})), std::make_error_code(std::errc::network_down));
  hub->run([&] { a.reset(); });
}

}  // namespace
