// SPDX-License-Identifier: MIT
// SocketCAN channel without a CAN kernel: an adopted AF_UNIX SOCK_SEQPACKET socketpair carries
// struct can_frame records, so frame layout, error-frame decoding, EAGAIN back-pressure and the
// ENOBUFS retry path (write fault injected on the Nth call) run on every machine.
#include <gtest/gtest.h>

#include <linux/can.h>
#include <linux/can/error.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <asio/io_context.hpp>

#include "hil/can/error_frame.hpp"
#include "hil/can/linux/socketcan_channel.hpp"

namespace can = hil::can;
using can::socketcan::SocketCanChannel;
using can::socketcan::SocketCanOptions;

namespace {

class SocketCanPair : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_EQ(::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, fds_), 0); }
  void TearDown() override {
    if (fds_[1] >= 0) ::close(fds_[1]);
  }
  std::unique_ptr<SocketCanChannel> adopt(SocketCanOptions o = {}) {
    auto ch = SocketCanChannel::adopt(io.get_executor(), clock, fds_[0], "pair0", std::move(o), false);
    EXPECT_TRUE(ch.has_value());
    fds_[0] = -1;
    return ch ? std::move(*ch) : nullptr;
  }
  void peer_write(const can_frame& k) { ASSERT_EQ(::write(fds_[1], &k, sizeof k), static_cast<ssize_t>(sizeof k)); }
  bool peer_read(can_frame& k) { return ::recv(fds_[1], &k, sizeof k, MSG_DONTWAIT) == static_cast<ssize_t>(sizeof k); }
  /// Run the io_context until `pred` holds (bounded by 5 s of real time).
  template <class P>
  bool run_until(P pred) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (!pred()) {
      if (std::chrono::steady_clock::now() > end) return false;
      io.run_one_for(std::chrono::milliseconds(50));
      io.restart();
    }
    return true;
  }

  hil::VirtualClock clock;
  asio::io_context io;
  int fds_[2] = {-1, -1};
};

TEST_F(SocketCanPair, SendsKernelLayoutWithFlags) {
  auto ch = adopt();
  ASSERT_FALSE(ch->send(can::make_frame(0x123, {0xDE, 0xAD})));
  ASSERT_FALSE(ch->send(can::make_extended_frame(0x1ABCDEF0, std::vector<std::uint8_t>{1})));
  ASSERT_FALSE(ch->send(can::make_remote_frame(0x705, 1)));
  can_frame k{};
  ASSERT_TRUE(peer_read(k));
  EXPECT_EQ(k.can_id, 0x123u);
  EXPECT_EQ(k.can_dlc, 2);
  EXPECT_EQ(k.data[0], 0xDE);
  ASSERT_TRUE(peer_read(k));
  EXPECT_EQ(k.can_id, CAN_EFF_FLAG | 0x1ABCDEF0u);
  ASSERT_TRUE(peer_read(k));
  EXPECT_EQ(k.can_id, CAN_RTR_FLAG | 0x705u);
  EXPECT_EQ(k.can_dlc, 1);
  EXPECT_EQ(ch->stats().tx_frames, 3u);
}

TEST_F(SocketCanPair, ReceivesFramesWithClockTime) {
  auto ch = adopt();
  std::vector<can::Frame> rx;
  std::vector<hil::TimePoint> times;
  ch->set_receive_handler([&](const can::Frame& f, hil::TimePoint t) {
    rx.push_back(f);
    times.push_back(t);
  });
  clock.advance(std::chrono::milliseconds(7));
  can_frame k{};
  k.can_id = 0x181;
  k.can_dlc = 3;
  k.data[0] = 1, k.data[1] = 2, k.data[2] = 3;
  peer_write(k);
  k = {};
  k.can_id = CAN_RTR_FLAG | CAN_EFF_FLAG | 0x1234;
  k.can_dlc = 4;
  peer_write(k);
  ASSERT_TRUE(run_until([&] { return rx.size() == 2; }));
  EXPECT_EQ(rx[0], can::make_frame(0x181, {1, 2, 3}));
  EXPECT_TRUE(rx[1].rtr && rx[1].extended);
  EXPECT_EQ(rx[1].id, 0x1234u);
  EXPECT_EQ(rx[1].dlc, 4);
  EXPECT_EQ(times[0], hil::TimePoint{std::chrono::milliseconds(7)});
  EXPECT_EQ(ch->stats().rx_frames, 2u);
}

TEST_F(SocketCanPair, ErrorFramesDriveStateStatsAndEvents) {
  auto ch = adopt();
  std::vector<can::BusState> states;
  std::vector<can::Frame> rx;
  ch->set_state_handler([&](can::BusState s) { states.push_back(s); });
  ch->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { rx.push_back(f); });
  can_frame k{};
  k.can_id = CAN_ERR_FLAG | CAN_ERR_CRTL;
  k.can_dlc = CAN_ERR_DLC;
  k.data[1] = CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_RX_OVERFLOW;
  peer_write(k);
  k = {};
  k.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF;
  k.can_dlc = CAN_ERR_DLC;
  peer_write(k);
  ASSERT_TRUE(run_until([&] { return rx.size() == 2; }));
  EXPECT_EQ(states, (std::vector<can::BusState>{can::BusState::error_passive, can::BusState::bus_off}));
  auto st = ch->socketcan_stats();
  EXPECT_EQ(st.channel.error_frames, 2u);
  EXPECT_TRUE(st.channel.bus_off);
  EXPECT_EQ(st.controller_rx_overflows, 1u);
  EXPECT_EQ(can::describe_error_frame(rx[0]), "error-passive, rx-overflow");
  EXPECT_EQ(ch->send(can::make_frame(1, {})), std::make_error_code(std::errc::network_down)) << "bus-off refuses";
  k = {};
  k.can_id = CAN_ERR_FLAG | CAN_ERR_RESTARTED;
  k.can_dlc = CAN_ERR_DLC;
  peer_write(k);
  ASSERT_TRUE(run_until([&] { return rx.size() == 3; }));
  EXPECT_EQ(states.back(), can::BusState::error_active);
  EXPECT_FALSE(ch->send(can::make_frame(1, {})));
}

TEST_F(SocketCanPair, ErrorFramesCanStayOutOfTheReceivePath) {
  SocketCanOptions o;
  o.deliver_error_frames = false;
  auto ch = adopt(o);
  std::size_t rx = 0;
  ch->set_receive_handler([&](const can::Frame&, hil::TimePoint) { ++rx; });
  can_frame k{};
  k.can_id = CAN_ERR_FLAG | CAN_ERR_ACK;
  k.can_dlc = CAN_ERR_DLC;
  peer_write(k);
  k = {};
  k.can_id = 0x100;
  peer_write(k);
  ASSERT_TRUE(run_until([&] { return rx == 1; }));
  EXPECT_EQ(ch->socketcan_stats().no_ack, 1u);
}

TEST_F(SocketCanPair, EagainBackPressureQueuesBoundedAndDrainsOnWritability) {
  const int small = 4096;
  ASSERT_EQ(::setsockopt(fds_[0], SOL_SOCKET, SO_SNDBUF, &small, sizeof small), 0);
  SocketCanOptions o;
  o.tx_queue_capacity = 16;
  auto ch = adopt(o);
  std::size_t accepted = 0;
  std::error_code last;
  for (int i = 0; i < 10000 && !last; ++i) {
    last = ch->send(can::make_frame(0x200, {static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(i >> 8)}));
    if (!last) ++accepted;
  }
  EXPECT_EQ(last, std::make_error_code(std::errc::no_buffer_space));
  EXPECT_EQ(ch->tx_queued(), 16u);
  auto st = ch->socketcan_stats();
  EXPECT_GE(st.eagain, 1u);
  EXPECT_EQ(st.channel.tx_dropped, 1u);
  // The peer reads everything; the queue drains on writability and order is kept.
  std::size_t received = 0;
  bool in_order = true;
  ASSERT_TRUE(run_until([&] {
    can_frame k{};
    while (peer_read(k)) {
      in_order = in_order && (k.data[0] | (k.data[1] << 8)) == static_cast<int>(received & 0xFFFF);
      ++received;
    }
    return received == accepted;
  })) << "received "
      << received << " of " << accepted;
  EXPECT_TRUE(in_order);
  EXPECT_EQ(ch->tx_queued(), 0u);
  EXPECT_EQ(ch->stats().tx_frames, accepted);
}

TEST_F(SocketCanPair, EnobufsIsRetriedAfterBackoffInOrder) {
  SocketCanOptions o;
  int calls = 0;
  o.write_fn = [&calls](int fd, const void* d, std::size_t n) -> ssize_t {
    ++calls;
    if (calls >= 2 && calls <= 4) {
      errno = ENOBUFS;
      return -1;
    }
    return ::write(fd, d, n);
  };
  o.enobufs_backoff_min = std::chrono::microseconds(100);
  auto ch = adopt(o);
  for (std::uint8_t i = 0; i < 5; ++i) ASSERT_FALSE(ch->send(can::make_frame(0x300, {i})));
  EXPECT_EQ(ch->tx_queued(), 4u);
  std::vector<int> order;
  ASSERT_TRUE(run_until([&] {
    can_frame k{};
    while (peer_read(k)) order.push_back(k.data[0]);
    return order.size() == 5;
  }));
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
  const auto st = ch->socketcan_stats();
  EXPECT_EQ(st.enobufs, 3u);
  EXPECT_EQ(st.channel.tx_frames, 5u);
  EXPECT_EQ(calls, 8);  // 5 successes + 3 refusals: retries were paced, not spun
}

TEST_F(SocketCanPair, HardWriteErrorsAreReturnedAndCounted) {
  SocketCanOptions o;
  o.write_fn = [](int, const void*, std::size_t) -> ssize_t {
    errno = ENETDOWN;
    return -1;
  };
  auto ch = adopt(o);
  EXPECT_EQ(ch->send(can::make_frame(1, {})), std::make_error_code(std::errc::network_down));
  EXPECT_EQ(ch->socketcan_stats().tx_errors, 1u);
}

TEST(SocketCanOpen, MissingInterfaceOrKernelSupportGivesADiagnostic) {
  asio::io_context io;
  hil::VirtualClock clock;
  std::string diag;
  auto ch = SocketCanChannel::open(io.get_executor(), clock, "hilnocan7", {}, &diag);
  ASSERT_FALSE(ch.has_value());
  EXPECT_TRUE(ch.error() == std::errc::no_such_device || ch.error() == std::errc::address_family_not_supported)
      << ch.error().message();
  EXPECT_NE(diag.find("hilnocan7"), std::string::npos) << diag;
  EXPECT_TRUE(diag.find("ip link add") != std::string::npos || diag.find("modprobe") != std::string::npos) << diag;
  EXPECT_FALSE(SocketCanChannel::open(io.get_executor(), clock, "", {}, &diag).has_value());
}

}  // namespace
