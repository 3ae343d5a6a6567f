// SPDX-License-Identifier: MIT
// SocketCAN on a real kernel (label `kernel`; run inside tests/vm/run-in-kernel.sh). Every test
// skips with a reason when vcan0 does not exist. Peers: a second raw socket, a second process,
// can-utils cansend/candump and python3-can's socketcan interface.
#include <gtest/gtest.h>

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>
#include <sys/utsname.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>

#include <asio/io_context.hpp>

#include <asio/executor_work_guard.hpp>
#include <thread>

#include "hil/can/candump.hpp"
#include "hil/can/io/socketcand_channel.hpp"
#include "hil/can/io/socketcand_server.hpp"
#include "hil/can/linux/socketcan_channel.hpp"
#include "hub_fixture.hpp"
#include "subprocess.hpp"

namespace can = hil::can;
using can::socketcan::SocketCanChannel;
using can::socketcan::SocketCanOptions;
using can::test::Subprocess;

namespace {

constexpr const char* kIf = "vcan0";

bool have_vcan0() {
  return ::if_nametoindex(kIf) != 0;
}

#define REQUIRE_VCAN0()                                                                                       \
  if (!have_vcan0())                                                                                          \
  GTEST_SKIP() << "vcan0 does not exist (run inside tests/vm/run-in-kernel.sh, or: modprobe vcan && ip link " \
                  "add dev vcan0 type vcan && ip link set up vcan0)"

class KernelCan : public ::testing::Test {
 protected:
  std::unique_ptr<SocketCanChannel> open(SocketCanOptions o = {}) {
    std::string diag;
    auto ch = SocketCanChannel::open(io.get_executor(), clock, kIf, std::move(o), &diag);
    EXPECT_TRUE(ch.has_value()) << diag;
    return ch ? std::move(*ch) : nullptr;
  }
  template <class P>
  bool run_until(P pred, std::chrono::seconds limit = std::chrono::seconds(10)) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (!pred()) {
      if (std::chrono::steady_clock::now() > end) return false;
      io.run_one_for(std::chrono::milliseconds(20));
      io.restart();
    }
    return true;
  }
  hil::SteadyClock clock;
  asio::io_context io;
};

TEST_F(KernelCan, TwoSocketsExchangeDataAndRemoteFrames) {
  REQUIRE_VCAN0();
  auto a = open();
  auto b = open();
  ASSERT_TRUE(a && b);
  std::vector<can::Frame> rx_b;
  b->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { rx_b.push_back(f); });
  std::vector<can::Frame> rx_a;
  a->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { rx_a.push_back(f); });
  const std::vector<can::Frame> frames = {
      can::make_frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF}), can::make_frame(0x080, {}),
      can::make_extended_frame(0x1ABCDEF0, std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6, 7, 8}),
      can::make_remote_frame(0x705, 1)};
  for (const auto& f : frames) ASSERT_FALSE(a->send(f));
  ASSERT_TRUE(run_until([&] { return rx_b.size() == frames.size(); }));
  EXPECT_EQ(rx_b, frames);
  EXPECT_TRUE(rx_a.empty()) << "no own frames without receive_own";
  EXPECT_EQ(a->stats().tx_frames, frames.size());
}

TEST_F(KernelCan, ReceiveOwnAndKernelFilters) {
  REQUIRE_VCAN0();
  SocketCanOptions own;
  own.receive_own = true;
  auto a = open(own);
  SocketCanOptions filtered;
  filtered.filters.filters = {can::Filter::exact(0x181)};
  auto b = open(filtered);
  std::vector<can::Frame> rx_a, rx_b;
  a->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { rx_a.push_back(f); });
  b->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { rx_b.push_back(f); });
  ASSERT_FALSE(a->send(can::make_frame(0x182, {1})));
  ASSERT_FALSE(a->send(can::make_frame(0x181, {2})));
  ASSERT_TRUE(run_until([&] { return rx_a.size() == 2 && rx_b.size() == 1; }));
  EXPECT_EQ(rx_b[0], can::make_frame(0x181, {2}));
}

TEST_F(KernelCan, ErrorFramesReachTheErrorFilterAndDriveState) {
  REQUIRE_VCAN0();
  auto watcher = open();  // default options: every error class
  std::vector<can::BusState> states;
  watcher->set_state_handler([&](can::BusState s) { states.push_back(s); });
  std::vector<can::Frame> rx;
  watcher->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { rx.push_back(f); });
  // vcan has no controller: inject error frames from a plain raw socket (the kernel routes frames
  // with CAN_ERR_FLAG to the sockets whose CAN_RAW_ERR_FILTER selects their class).
  const int s = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  ASSERT_GE(s, 0);
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(::if_nametoindex(kIf));
  ASSERT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  can_frame k{};
  k.can_id = CAN_ERR_FLAG | CAN_ERR_CRTL;
  k.can_dlc = CAN_ERR_DLC;
  k.data[1] = CAN_ERR_CRTL_TX_WARNING;
  ASSERT_EQ(::write(s, &k, sizeof k), static_cast<ssize_t>(sizeof k));
  k = {};
  k.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF;
  k.can_dlc = CAN_ERR_DLC;
  ASSERT_EQ(::write(s, &k, sizeof k), static_cast<ssize_t>(sizeof k));
  ASSERT_TRUE(run_until([&] { return rx.size() == 2; }));
  EXPECT_EQ(states, (std::vector<can::BusState>{can::BusState::error_warning, can::BusState::bus_off}));
  EXPECT_TRUE(watcher->stats().bus_off);
  EXPECT_EQ(watcher->send(can::make_frame(1, {})), std::make_error_code(std::errc::network_down));
  k = {};
  k.can_id = CAN_ERR_FLAG | CAN_ERR_RESTARTED;
  k.can_dlc = CAN_ERR_DLC;
  ASSERT_EQ(::write(s, &k, sizeof k), static_cast<ssize_t>(sizeof k));
  ASSERT_TRUE(run_until([&] { return rx.size() == 3; }));
  EXPECT_FALSE(watcher->stats().bus_off);
  ::close(s);
}

TEST_F(KernelCan, FloodIsBoundedAndAccountedFor) {
  REQUIRE_VCAN0();
  SocketCanOptions tx_opts;
  tx_opts.sndbuf_bytes = 1024;  // the kernel doubles it; a few frames in flight at most
  tx_opts.tx_queue_capacity = 64;
  auto tx = open(tx_opts);
  auto rx = open();
  std::uint64_t received = 0;
  rx->set_receive_handler([&](const can::Frame&, hil::TimePoint) { ++received; });
  std::uint64_t accepted = 0, refused = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto ec = tx->send(can::make_frame(0x321, {static_cast<std::uint8_t>(i)}));
    if (!ec)
      ++accepted;
    else if (ec == std::errc::no_buffer_space)
      ++refused;
    else
      FAIL() << ec.message();
    if (i % 256 == 0) io.poll(), io.restart();
  }
  ASSERT_TRUE(run_until([&] { return tx->tx_queued() == 0; }));
  const auto st = tx->socketcan_stats();
  EXPECT_EQ(accepted + refused, 20000u);
  EXPECT_EQ(st.channel.tx_frames + st.tx_errors, accepted);
  EXPECT_EQ(st.channel.tx_dropped, refused);
  EXPECT_LE(st.tx_queue_high_water, 64u);
  ASSERT_TRUE(run_until([&] { return received + rx->stats().rx_overruns >= st.channel.tx_frames; }))
      << "received " << received << " overruns " << rx->stats().rx_overruns << " sent " << st.channel.tx_frames;
  RecordProperty("eagain", static_cast<int>(st.eagain));
  RecordProperty("enobufs", static_cast<int>(st.enobufs));
}

/// Make vcan1 slow: a token-bucket qdisc (64 kbit/s, 8 frames of queue) so the kernel answers
/// ENOBUFS like a real controller with a full txqueuelen. sch_tbf is a module in Debian's kernel;
/// under tests/vm/run-in-kernel.sh it is loaded from the harness's module cache.
std::optional<std::string> make_vcan1_slow() {
  if (::access("/usr/sbin/tc", X_OK) != 0) return "tc (iproute2) is not installed";
  auto tbf = [] {
    Subprocess tc({"/usr/sbin/tc", "qdisc", "replace", "dev", "vcan1", "root", "tbf", "rate", "64kbit", "burst", "64",
                   "limit", "128"});
    return tc.wait() == 0;
  };
  if (tbf()) return std::nullopt;
  utsname u{};
  ::uname(&u);
  const char* cache_env = std::getenv("HIL_VM_CACHE");
  const std::string cache = cache_env ? cache_env : "/var/cache/hilbridge-vm";
  const std::string ko = cache + "/" + u.release + "/lib/modules/" + u.release + "/kernel/net/sched/sch_tbf.ko";
  if (::access(ko.c_str(), R_OK) == 0) {
    Subprocess insmod({"/usr/sbin/insmod", ko});
    (void)insmod.wait();
    if (tbf()) return std::nullopt;
  }
  return "cannot install a tbf qdisc on vcan1 (needs root and sch_tbf)";
}

TEST_F(KernelCan, EnobufsFromAFullInterfaceQueueIsRetriedNotSpun) {
  if (::if_nametoindex("vcan1") == 0) GTEST_SKIP() << "vcan1 does not exist (run inside tests/vm/run-in-kernel.sh)";
  if (auto why = make_vcan1_slow()) GTEST_SKIP() << *why;
  struct Restore {
    ~Restore() {
      Subprocess tc({"/usr/sbin/tc", "qdisc", "del", "dev", "vcan1", "root"});
      (void)tc.wait();
    }
  } restore;
  auto open1 = [&](SocketCanOptions o) {
    std::string diag;
    auto ch = SocketCanChannel::open(io.get_executor(), clock, "vcan1", std::move(o), &diag);
    EXPECT_TRUE(ch.has_value()) << diag;
    return ch ? std::move(*ch) : nullptr;
  };
  SocketCanOptions tx_opts;
  tx_opts.tx_queue_capacity = 64;
  auto tx = open1(tx_opts);
  auto rx = open1({});
  ASSERT_TRUE(tx && rx);
  std::vector<int> order;
  rx->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { order.push_back(f.data[0] | (f.data[1] << 8)); });
  std::uint64_t accepted = 0, refused = 0;
  for (int i = 0; i < 400; ++i) {
    const auto ec = tx->send(
        can::make_frame(0x321, {static_cast<std::uint8_t>(accepted), static_cast<std::uint8_t>(accepted >> 8)}));
    if (!ec)
      ++accepted;
    else if (ec == std::errc::no_buffer_space)
      ++refused;
    else
      FAIL() << ec.message();
  }
  EXPECT_GT(refused, 0u) << "the bounded user-space queue must refuse a flood";
  ASSERT_TRUE(run_until([&] { return tx->tx_queued() == 0 && order.size() == accepted; }, std::chrono::seconds(20)))
      << "queued " << tx->tx_queued() << " received " << order.size() << " of " << accepted;
  const auto st = tx->socketcan_stats();
  EXPECT_GT(st.enobufs, 0u) << "the tbf qdisc should have answered ENOBUFS";
  EXPECT_LT(st.enobufs, 2000u) << "retries are paced by the back-off timer, not spun";
  EXPECT_EQ(st.channel.tx_frames, accepted);
  EXPECT_EQ(st.channel.tx_dropped, refused);
  for (std::size_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], static_cast<int>(i)) << "order broken at " << i;
  RecordProperty("enobufs", static_cast<int>(st.enobufs));
  RecordProperty("eagain", static_cast<int>(st.eagain));
}

TEST_F(KernelCan, TwoProcessesOnOneInterface) {
  REQUIRE_VCAN0();
  auto rx = open();
  std::vector<can::Frame> got;
  rx->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { got.push_back(f); });
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    asio::io_context cio;
    hil::SteadyClock cclock;
    auto ch = SocketCanChannel::open(cio.get_executor(), cclock, kIf);
    if (!ch) ::_exit(3);
    for (std::uint8_t i = 0; i < 50; ++i)
      if ((*ch)->send(can::make_frame(0x400, {i}))) ::_exit(4);
    for (int k = 0; k < 500 && (*ch)->tx_queued() > 0; ++k) cio.run_one_for(std::chrono::milliseconds(10));
    ::_exit((*ch)->tx_queued() == 0 ? 0 : 5);
  }
  ASSERT_TRUE(run_until([&] { return got.size() == 50; })) << got.size();
  int st = 0;
  ASSERT_EQ(::waitpid(child, &st, 0), child);
  EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0);
  for (std::uint8_t i = 0; i < 50; ++i) EXPECT_EQ(got[i], can::make_frame(0x400, {i}));
}

TEST_F(KernelCan, CanUtilsAreIndependentPeers) {
  REQUIRE_VCAN0();
  if (::access("/usr/bin/cansend", X_OK) != 0 || ::access("/usr/bin/candump", X_OK) != 0)
    GTEST_SKIP() << "can-utils (cansend, candump) not installed (apt install can-utils)";
  auto ch = open();
  std::vector<can::Frame> got;
  ch->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { got.push_back(f); });
  // candump sees what we send; its -L lines parse with our candump parser.
  Subprocess dump({"/usr/bin/candump", "-L", "-n", "3", kIf});
  ASSERT_TRUE(dump.started());
  // candump has no "ready" output: retry the first frame until candump's line shows up.
  const auto first = can::make_frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF});
  std::optional<std::string> line;
  for (int attempt = 0; attempt < 50 && !line; ++attempt) {
    ASSERT_FALSE(ch->send(first));
    line = dump.read_line(std::chrono::milliseconds(100));
  }
  ASSERT_TRUE(line) << dump.output();
  auto rec = can::candump::parse_log_line(*line);
  ASSERT_TRUE(rec) << *line;
  EXPECT_EQ(rec->interface, kIf);
  EXPECT_EQ(rec->frame, first);
  ASSERT_FALSE(ch->send(can::make_extended_frame(0x1F334455, std::vector<std::uint8_t>{0x11, 0x22})));
  ASSERT_FALSE(ch->send(can::make_remote_frame(0x705, 1)));
  std::vector<can::Frame> dumped;
  while (auto l = dump.read_line(std::chrono::seconds(5))) {
    if (auto r = can::candump::parse_log_line(*l)) dumped.push_back(r->frame);
  }
  ASSERT_GE(dumped.size(), 2u) << dump.output();
  EXPECT_EQ(dumped[dumped.size() - 2], can::make_extended_frame(0x1F334455, std::vector<std::uint8_t>{0x11, 0x22}));
  EXPECT_EQ(dumped.back(), can::make_remote_frame(0x705, 1));
  // cansend's frames reach us.
  Subprocess send1({"/usr/bin/cansend", kIf, "5A1#11.22.33"});
  EXPECT_EQ(send1.wait(), 0) << send1.output();
  Subprocess send2({"/usr/bin/cansend", kIf, "12345678#R"});
  EXPECT_EQ(send2.wait(), 0) << send2.output();
  ASSERT_TRUE(run_until([&] { return got.size() >= 2; }));
  EXPECT_EQ(got[got.size() - 2], can::make_frame(0x5A1, {0x11, 0x22, 0x33}));
  EXPECT_TRUE(got.back().rtr && got.back().extended);
  EXPECT_EQ(got.back().id, 0x12345678u);
}

TEST_F(KernelCan, PythonCanSocketcanIsAnIndependentPeer) {
  REQUIRE_VCAN0();
  if (!can::test::python_has("can.interfaces.socketcan"))
    GTEST_SKIP()
        << "/usr/bin/python3 with python3-can (socketcan interface) is not installed (apt install python3-can)";
  auto ch = open();
  std::vector<can::Frame> got;
  ch->set_receive_handler([&](const can::Frame& f, hil::TimePoint) { got.push_back(f); });
  const std::vector<can::Frame> frames = {can::make_frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF}),
                                          can::make_extended_frame(0x18FF0010, std::vector<std::uint8_t>{1, 2, 3}),
                                          can::make_remote_frame(0x701, 1)};
  Subprocess py({"/usr/bin/python3", std::string(HIL_TEST_SOURCE_DIR) + "/socketcan_peer.py", kIf,
                 std::to_string(frames.size())});
  ASSERT_TRUE(py.wait_for_line("READY", std::chrono::seconds(90))) << py.output();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    ASSERT_FALSE(ch->send(frames[i]));
    // Python under QEMU TCG is slow (tens of seconds for its first recv): generous bound.
    ASSERT_TRUE(run_until([&] { return got.size() >= i + 1; }, std::chrono::seconds(90))) << py.output();
    can::Frame expected = frames[i];
    expected.id += 1;
    if (expected.rtr) {
      expected.rtr = false;
      expected.dlc = 1;
      expected.data = {0x55};
    } else {
      std::reverse(expected.data.begin(), expected.data.begin() + expected.dlc);
    }
    EXPECT_EQ(got[i], expected) << i;
  }
  ASSERT_TRUE(run_until([&] { return got.size() == frames.size() + 1; }, std::chrono::seconds(90))) << py.output();
  EXPECT_EQ(got.back(), can::make_frame(0x7FF, {'P', 'Y'}));
  EXPECT_EQ(py.wait(std::chrono::seconds(30)), 0) << py.output();
  EXPECT_NE(py.output().find("RX 701#R ext=0"), std::string::npos) << py.output();
}

TEST(KernelCanBridge, SocketcandHubBridgesVcan0) {
  REQUIRE_VCAN0();
  // `hilbridge can hub --bridge vcan0` in-process: each socketcand client gets its own raw socket.
  asio::io_context io;
  hil::SteadyClock clock;
  auto work = asio::make_work_guard(io);
  can::socketcand::Server server(
      io.get_executor(), clock,
      [&](std::string_view name, const std::string&) -> std::expected<std::unique_ptr<can::Channel>, std::error_code> {
        if (name != kIf) return std::unexpected(std::make_error_code(std::errc::no_such_device));
        auto ch = SocketCanChannel::open(io.get_executor(), clock, kIf);
        if (!ch) return std::unexpected(ch.error());
        return std::unique_ptr<can::Channel>(std::move(*ch));
      });
  ASSERT_FALSE(server.listen({asio::ip::make_address("127.0.0.1"), 0}));
  can::test::Inbox local_rx, client_rx;
  auto local = SocketCanChannel::open(io.get_executor(), clock, kIf);
  ASSERT_TRUE(local);
  (*local)->set_receive_handler(local_rx.handler());
  std::thread runner([&] { io.run(); });
  std::string diag;
  auto client = can::socketcand::SocketcandChannel::connect(io.get_executor(), clock, "127.0.0.1",
                                                            server.local_endpoint().port(), kIf, {}, &diag);
  ASSERT_TRUE(client) << diag;
  (*client)->set_receive_handler(client_rx.handler());
  ASSERT_FALSE((*client)->send(can::make_frame(0x601, {0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0})));
  auto got = local_rx.wait_for(1, std::chrono::seconds(10));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], can::make_frame(0x601, {0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0}));
  std::promise<std::error_code> sent;
  asio::post(io, [&] {
    sent.set_value((*local)->send(can::make_extended_frame(0x18FF0001, std::vector<std::uint8_t>{0xAA})));
  });
  EXPECT_FALSE(sent.get_future().get());
  auto back = client_rx.wait_for(1, std::chrono::seconds(10));
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0], can::make_extended_frame(0x18FF0001, std::vector<std::uint8_t>{0xAA}));
  std::promise<void> done;
  asio::post(io, [&] {
    client->reset();
    local->reset();
    server.close();
    done.set_value();
  });
  done.get_future().wait();
  work.reset();
  io.stop();
  runner.join();
}

}  // namespace
