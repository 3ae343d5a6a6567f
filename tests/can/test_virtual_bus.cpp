// SPDX-License-Identifier: MIT
// The in-process virtual bus: delivery order and timing on the virtual clock, loopback, filters,
// bounded queues and every fault-injection action.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "hil/can/virtual_bus.hpp"

using namespace std::chrono_literals;
using hil::TimePoint;
using hil::VirtualClock;
namespace can = hil::can;

namespace {

struct Rx {
  std::vector<can::Frame> frames;
  std::vector<TimePoint> times;
  void attach(can::Channel& ch) {
    ch.set_receive_handler([this](const can::Frame& f, TimePoint t) {
      frames.push_back(f);
      times.push_back(t);
    });
  }
};

TimePoint at(std::chrono::nanoseconds d) {
  return TimePoint{d};
}

class VirtualBusTest : public ::testing::Test {
 protected:
  VirtualClock clock;
  can::VirtualBus bus{clock, "can0"};
};

TEST_F(VirtualBusTest, DeliversToAllOthersButNotTheSender) {
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  auto c = bus.attach("c");
  Rx ra, rb, rc;
  ra.attach(*a), rb.attach(*b), rc.attach(*c);
  ASSERT_FALSE(a->send(can::make_frame(0x123, {0xDE, 0xAD})));
  EXPECT_TRUE(rb.frames.empty()) << "send() must not call handlers";
  EXPECT_EQ(bus.deliver(clock.now()), 1u);
  EXPECT_TRUE(ra.frames.empty());
  ASSERT_EQ(rb.frames.size(), 1u);
  ASSERT_EQ(rc.frames.size(), 1u);
  EXPECT_EQ(rb.frames[0], can::make_frame(0x123, {0xDE, 0xAD}));
  EXPECT_EQ(a->stats().tx_frames, 1u);
  EXPECT_EQ(b->stats().rx_frames, 1u);
  EXPECT_EQ(bus.stats().receptions, 2u);
}

TEST_F(VirtualBusTest, LatencyDefersDeliveryAndStampsDueTime) {
  bus.set_latency(250us);
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  Rx rb;
  rb.attach(*b);
  clock.advance(1ms);
  ASSERT_FALSE(a->send(can::make_frame(0x1, {1})));
  EXPECT_EQ(bus.deliver(clock.now()), 0u);
  EXPECT_EQ(bus.next_due(), at(1250us));
  clock.advance(249us);
  EXPECT_EQ(bus.deliver(clock.now()), 0u);
  clock.advance(1us);
  EXPECT_EQ(bus.deliver(clock.now()), 1u);
  ASSERT_EQ(rb.times.size(), 1u);
  EXPECT_EQ(rb.times[0], at(1250us));
}

TEST_F(VirtualBusTest, LoopbackOnlyWhenAsked) {
  auto a = bus.attach("a", {.receive_own = true});
  auto b = bus.attach("b");
  Rx ra, rb;
  ra.attach(*a), rb.attach(*b);
  ASSERT_FALSE(a->send(can::make_frame(0x10, {})));
  ASSERT_FALSE(b->send(can::make_frame(0x11, {})));
  bus.deliver(clock.now());
  ASSERT_EQ(ra.frames.size(), 2u);
  EXPECT_EQ(ra.frames[0].id, 0x10u);
  EXPECT_EQ(ra.frames[1].id, 0x11u);
  ASSERT_EQ(rb.frames.size(), 1u);
  EXPECT_EQ(rb.frames[0].id, 0x10u);
}

TEST_F(VirtualBusTest, FiltersFollowCanRawSemantics) {
  auto tx = bus.attach("tx");
  auto exact = bus.attach("exact", {.filters = {.filters = {can::Filter::exact(0x181)}}});
  auto range = bus.attach("range", {.filters = {.filters = {{0x580, 0x780, false}}}});  // 0x580..0x5FF
  auto inverted = bus.attach("inv", {.filters = {.filters = {{0x700, 0x780, true}}}});
  auto none = bus.attach("none", {.filters = {.filters = {}}});
  auto joined =
      bus.attach("join", {.filters = {.filters = {{0x100, 0x700, false}, {0x001, 0x001, false}}, .join = true}});
  Rx re, rr, ri, rn, rj;
  re.attach(*exact), rr.attach(*range), ri.attach(*inverted), rn.attach(*none), rj.attach(*joined);
  for (std::uint32_t id : {0x181u, 0x182u, 0x585u, 0x705u, 0x101u}) ASSERT_FALSE(tx->send(can::make_frame(id, {0})));
  can::Frame ext = can::make_extended_frame(0x181, std::vector<std::uint8_t>{1});
  ASSERT_FALSE(tx->send(ext));
  bus.deliver(clock.now());
  auto ids = [](const Rx& r) {
    std::vector<std::uint32_t> v;
    for (const auto& f : r.frames) v.push_back(f.id);
    return v;
  };
  EXPECT_EQ(ids(re), (std::vector<std::uint32_t>{0x181}));  // not the 29-bit 0x181
  EXPECT_EQ(ids(rr), (std::vector<std::uint32_t>{0x585}));
  EXPECT_EQ(ids(ri), (std::vector<std::uint32_t>{0x181, 0x182, 0x585, 0x101, 0x181}));
  EXPECT_TRUE(rn.frames.empty());
  EXPECT_EQ(ids(rj), (std::vector<std::uint32_t>{0x181, 0x101, 0x181}));
  EXPECT_GT(bus.stats().filtered, 0u);
}

TEST_F(VirtualBusTest, ErrorFramesOnlyThroughTheErrorMask) {
  auto plain = bus.attach("plain");
  auto watcher = bus.attach("watch", {.filters = {.error_mask = can::error_class::controller}});
  Rx rp, rw;
  rp.attach(*plain), rw.attach(*watcher);
  bus.inject_error_frame(can::make_error_frame(can::error_class::controller, {0, can::controller_status::rx_passive}));
  bus.inject_error_frame(can::make_error_frame(can::error_class::no_ack));
  bus.deliver(clock.now());
  EXPECT_TRUE(rp.frames.empty());
  ASSERT_EQ(rw.frames.size(), 1u);
  EXPECT_TRUE(rw.frames[0].error);
  EXPECT_EQ(rw.frames[0].data[1], can::controller_status::rx_passive);
  EXPECT_EQ(watcher->stats().error_frames, 1u);
}

TEST_F(VirtualBusTest, OrderIsDueTimeThenSendOrderAcrossSenders) {
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  auto rx = bus.attach("rx");
  Rx r;
  r.attach(*rx);
  const auto slow = bus.inject(
      {.action = can::FaultAction::delay, .match = [](const can::Frame& f) { return f.id == 1; }, .delay = 5us});
  ASSERT_FALSE(a->send(can::make_frame(1, {})));  // due 5us
  ASSERT_FALSE(b->send(can::make_frame(2, {})));  // due 0
  clock.advance(2us);
  ASSERT_FALSE(a->send(can::make_frame(3, {})));  // due 2us
  ASSERT_FALSE(b->send(can::make_frame(4, {})));  // due 2us, after 3
  EXPECT_EQ(bus.run_until(clock, at(10us)), 4u);
  ASSERT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(r.frames[0].id, 2u);
  EXPECT_EQ(r.frames[1].id, 3u);
  EXPECT_EQ(r.frames[2].id, 4u);
  EXPECT_EQ(r.frames[3].id, 1u);
  EXPECT_EQ(r.times[3], at(5us));
  EXPECT_EQ(bus.fault_hits(slow), 1u);
  EXPECT_EQ(clock.now(), at(10us));
}

TEST_F(VirtualBusTest, HandlersMaySendAndZeroLatencyExchangesCompleteInOneCall) {
  auto master = bus.attach("master");
  auto node = bus.attach("node");
  Rx rm;
  rm.attach(*master);
  node->set_receive_handler([&](const can::Frame& f, TimePoint) {
    if (f.id == 0x602) {
      ASSERT_FALSE(node->send(can::make_frame(0x582, {0x60})));
    }
  });
  ASSERT_FALSE(master->send(can::make_frame(0x602, {0x40})));
  EXPECT_EQ(bus.deliver(clock.now()), 2u);
  ASSERT_EQ(rm.frames.size(), 1u);
  EXPECT_EQ(rm.frames[0].id, 0x582u);
}

TEST_F(VirtualBusTest, EndlessPingPongIsBoundedPerCall) {
  can::VirtualBus small(clock, "x", {.max_deliveries_per_call = 100});
  auto a = small.attach("a");
  auto b = small.attach("b");
  a->set_receive_handler([&](const can::Frame& f, TimePoint) { (void)a->send(f); });
  b->set_receive_handler([&](const can::Frame& f, TimePoint) { (void)b->send(f); });
  ASSERT_FALSE(a->send(can::make_frame(1, {})));
  EXPECT_EQ(small.deliver(clock.now()), 100u);
  EXPECT_EQ(small.stats().deliver_limit_hits, 1u);
  EXPECT_EQ(small.in_flight(), 1u);
}

TEST_F(VirtualBusTest, HandlersSeeCausalTimesUnderRunUntil) {
  bus.set_latency(100us);
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  std::vector<TimePoint> seen_clock;
  Rx ra;
  ra.attach(*a);
  b->set_receive_handler([&](const can::Frame& f, TimePoint t) {
    seen_clock.push_back(clock.now());
    EXPECT_EQ(t, clock.now());
    (void)b->send(can::make_frame(f.id + 1, {}));
  });
  ASSERT_FALSE(a->send(can::make_frame(0x100, {})));
  bus.run_until(clock, at(1ms));
  ASSERT_EQ(seen_clock.size(), 1u);
  EXPECT_EQ(seen_clock[0], at(100us));
  ASSERT_EQ(ra.times.size(), 1u);
  EXPECT_EQ(ra.times[0], at(200us));
}

TEST_F(VirtualBusTest, DropNthMatchingFrameOnly) {
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  Rx rb;
  rb.attach(*b);
  const auto id = bus.inject(
      {.action = can::FaultAction::drop, .match = [](const can::Frame& f) { return f.id == 0x181; }, .nth = 2});
  for (std::uint8_t i = 0; i < 4; ++i) {
    ASSERT_FALSE(a->send(can::make_frame(0x181, {i})));
    ASSERT_FALSE(a->send(can::make_frame(0x281, {i})));
  }
  bus.deliver(clock.now());
  ASSERT_EQ(rb.frames.size(), 7u);
  std::vector<std::uint8_t> seq181;
  for (const auto& f : rb.frames)
    if (f.id == 0x181) seq181.push_back(f.data[0]);
  EXPECT_EQ(seq181, (std::vector<std::uint8_t>{0, 2, 3}));
  EXPECT_EQ(bus.fault_hits(id), 1u);
  EXPECT_EQ(bus.stats().dropped, 1u);
}

TEST_F(VirtualBusTest, DropWithTimesLimitThenExpires) {
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  Rx rb;
  rb.attach(*b);
  bus.inject({.action = can::FaultAction::drop, .times = 2});
  for (std::uint8_t i = 0; i < 4; ++i) ASSERT_FALSE(a->send(can::make_frame(0x1, {i})));
  bus.deliver(clock.now());
  ASSERT_EQ(rb.frames.size(), 2u);
  EXPECT_EQ(rb.frames[0].data[0], 2);
}

TEST_F(VirtualBusTest, DuplicateDeliversCopiesRightAfter) {
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  Rx rb;
  rb.attach(*b);
  bus.inject({.action = can::FaultAction::duplicate, .nth = 1, .copies = 2});
  ASSERT_FALSE(a->send(can::make_frame(0x1, {7})));
  ASSERT_FALSE(a->send(can::make_frame(0x2, {8})));
  bus.deliver(clock.now());
  ASSERT_EQ(rb.frames.size(), 4u);
  EXPECT_EQ(rb.frames[0].id, 1u);
  EXPECT_EQ(rb.frames[1].id, 1u);
  EXPECT_EQ(rb.frames[2].id, 1u);
  EXPECT_EQ(rb.frames[3].id, 2u);
  EXPECT_EQ(bus.stats().duplicated, 2u);
}

TEST_F(VirtualBusTest, ReorderSwapsWithTheNextFrame) {
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  Rx rb;
  rb.attach(*b);
  bus.inject({.action = can::FaultAction::reorder, .match = [](const can::Frame& f) { return f.id == 0x1; }, .nth = 1});
  ASSERT_FALSE(a->send(can::make_frame(0x1, {})));
  EXPECT_EQ(bus.deliver(clock.now()), 0u) << "held until the next frame";
  ASSERT_FALSE(b->send(can::make_frame(0x2, {})));
  ASSERT_FALSE(a->send(can::make_frame(0x3, {})));
  Rx ra;
  ra.attach(*a);
  bus.deliver(clock.now());
  ASSERT_EQ(rb.frames.size(), 2u);  // b's own 0x2 went out first, then the held 0x1
  EXPECT_EQ(rb.frames[0].id, 1u);
  EXPECT_EQ(rb.frames[1].id, 3u);
  ASSERT_EQ(ra.frames.size(), 1u);
  EXPECT_EQ(ra.frames[0].id, 2u);
  // A third node sees the swap directly.
  auto c = bus.attach("c");
  Rx rc;
  rc.attach(*c);
  bus.inject({.action = can::FaultAction::reorder, .nth = 1});
  ASSERT_FALSE(a->send(can::make_frame(0x10, {})));
  ASSERT_FALSE(a->send(can::make_frame(0x11, {})));
  bus.deliver(clock.now());
  ASSERT_EQ(rc.frames.size(), 2u);
  EXPECT_EQ(rc.frames[0].id, 0x11u);
  EXPECT_EQ(rc.frames[1].id, 0x10u);
  EXPECT_EQ(bus.stats().reordered, 2u);
}

TEST_F(VirtualBusTest, CorruptDefaultAndCustomMutation) {
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  Rx rb;
  rb.attach(*b);
  bus.inject({.action = can::FaultAction::corrupt, .nth = 1});
  bus.inject({.action = can::FaultAction::corrupt,
              .match = [](const can::Frame& f) { return f.id == 0x20; },
              .mutate = [](can::Frame& f) { f.dlc = 1; }});
  ASSERT_FALSE(a->send(can::make_frame(0x10, {0x0F, 0x01})));
  ASSERT_FALSE(a->send(can::make_frame(0x20, {0xAA, 0xBB})));
  bus.deliver(clock.now());
  ASSERT_EQ(rb.frames.size(), 2u);
  EXPECT_EQ(rb.frames[0].data[0], 0xF0);
  EXPECT_EQ(rb.frames[0].data[1], 0x01);
  EXPECT_EQ(rb.frames[1].dlc, 1);
  EXPECT_EQ(bus.stats().corrupted, 2u);
}

TEST_F(VirtualBusTest, ParticipantBusOff) {
  auto a = bus.attach("a", {.filters = {.error_mask = can::error_class::bus_off | can::error_class::restarted}});
  auto b = bus.attach("b");
  Rx ra, rb;
  ra.attach(*a), rb.attach(*b);
  a->set_bus_off(true);
  EXPECT_EQ(a->send(can::make_frame(1, {})), std::make_error_code(std::errc::network_down));
  EXPECT_TRUE(a->stats().bus_off);
  ASSERT_FALSE(b->send(can::make_frame(2, {})));
  bus.deliver(clock.now());
  ASSERT_EQ(ra.frames.size(), 1u) << "only the bus-off error frame";
  EXPECT_TRUE(ra.frames[0].error);
  EXPECT_EQ(ra.frames[0].id, can::error_class::bus_off);
  EXPECT_EQ(bus.stats().lost_bus_off, 1u);
  a->set_bus_off(false);
  ASSERT_FALSE(a->send(can::make_frame(3, {})));
  bus.deliver(clock.now());
  ASSERT_EQ(ra.frames.size(), 2u);
  EXPECT_EQ(ra.frames[1].id, can::error_class::restarted);
  ASSERT_EQ(rb.frames.size(), 1u);
  EXPECT_EQ(rb.frames[0].id, 3u);
}

TEST_F(VirtualBusTest, WholeBusOffLosesQueuedFrames) {
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  Rx rb;
  rb.attach(*b);
  ASSERT_FALSE(a->send(can::make_frame(1, {})));
  bus.set_bus_off(true);
  EXPECT_EQ(b->send(can::make_frame(2, {})), std::make_error_code(std::errc::network_down));
  EXPECT_TRUE(b->stats().bus_off);
  bus.deliver(clock.now());
  EXPECT_TRUE(rb.frames.empty());
  bus.set_bus_off(false);
  EXPECT_FALSE(b->stats().bus_off);
  ASSERT_FALSE(a->send(can::make_frame(3, {})));
  bus.deliver(clock.now());
  ASSERT_EQ(rb.frames.size(), 1u);
  EXPECT_EQ(bus.stats().rejected_bus_off, 1u);
}

TEST_F(VirtualBusTest, BoundedQueuesRefuseWithNoBufferSpace) {
  can::VirtualBus small(clock, "x", {.max_in_flight = 5});
  auto a = small.attach("a", {.tx_queue_capacity = 3});
  auto b = small.attach("b");
  for (int i = 0; i < 3; ++i) ASSERT_FALSE(a->send(can::make_frame(1, {})));
  EXPECT_EQ(a->send(can::make_frame(1, {})), std::make_error_code(std::errc::no_buffer_space));
  EXPECT_EQ(a->stats().tx_dropped, 1u);
  EXPECT_EQ(a->in_flight(), 3u);
  ASSERT_FALSE(b->send(can::make_frame(2, {})));
  ASSERT_FALSE(b->send(can::make_frame(2, {})));
  EXPECT_EQ(b->send(can::make_frame(2, {})), std::make_error_code(std::errc::no_buffer_space));
  small.deliver(clock.now());
  EXPECT_EQ(a->in_flight(), 0u);
  EXPECT_FALSE(a->send(can::make_frame(1, {})));
  EXPECT_EQ(small.stats().rejected_full, 2u);
}

TEST_F(VirtualBusTest, InvalidFramesAreRejected) {
  auto a = bus.attach("a");
  can::Frame f = can::make_frame(0x1, {});
  f.dlc = 9;
  EXPECT_EQ(a->send(f), std::make_error_code(std::errc::invalid_argument));
  f = can::make_frame(0x1, {});
  f.id = 0x800;
  EXPECT_EQ(a->send(f), std::make_error_code(std::errc::invalid_argument));
}

TEST_F(VirtualBusTest, DetachDuringDeliveryAndChannelOutlivingBus) {
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  auto c = bus.attach("c");
  Rx rc;
  rc.attach(*c);
  b->set_receive_handler([&](const can::Frame&, TimePoint) { c.reset(); });
  ASSERT_FALSE(a->send(can::make_frame(1, {})));
  ASSERT_FALSE(a->send(can::make_frame(2, {})));
  bus.deliver(clock.now());
  EXPECT_TRUE(rc.frames.empty());
  EXPECT_EQ(bus.participant_count(), 2u);
  std::unique_ptr<can::VirtualChannel> orphan;
  {
    can::VirtualBus temp(clock, "tmp");
    orphan = temp.attach("o");
  }
  EXPECT_EQ(orphan->send(can::make_frame(1, {})), std::make_error_code(std::errc::network_down));
}

TEST_F(VirtualBusTest, WakeupAnnouncesEarliestDueTime) {
  bus.set_latency(1ms);
  std::vector<TimePoint> wakeups;
  bus.set_wakeup_handler([&](TimePoint t) { wakeups.push_back(t); });
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  ASSERT_FALSE(a->send(can::make_frame(1, {})));
  ASSERT_FALSE(a->send(can::make_frame(2, {})));  // same due: no new wakeup
  ASSERT_EQ(wakeups.size(), 1u);
  EXPECT_EQ(wakeups[0], at(1ms));
  clock.advance(1ms);
  ASSERT_FALSE(a->send(can::make_frame(3, {})));  // due 2ms, later than announced
  EXPECT_EQ(wakeups.size(), 1u);
  bus.deliver(clock.now());
  ASSERT_EQ(wakeups.size(), 2u);
  EXPECT_EQ(wakeups[1], at(2ms));
}

TEST_F(VirtualBusTest, DeterministicAcrossRunsWithManyParticipants) {
  auto run = [] {
    VirtualClock clk;
    can::VirtualBus b(clk, "det", {.latency = 10us});
    std::vector<std::unique_ptr<can::VirtualChannel>> nodes;
    std::vector<std::string> log;
    for (int i = 0; i < 9; ++i) {
      nodes.push_back(b.attach("n" + std::to_string(i)));
      auto* self = nodes.back().get();
      self->set_receive_handler([&log, self, i](const can::Frame& f, TimePoint t) {
        log.push_back(std::to_string(i) + ":" + std::to_string(f.id) + "@" +
                      std::to_string(t.time_since_epoch().count()));
        if (f.id < 0x700 && (f.id % 9) == static_cast<std::uint32_t>(i))
          (void)self->send(can::make_frame(f.id + 0x80, {}));
      });
    }
    b.inject({.action = can::FaultAction::delay, .nth = 3, .delay = 15us});
    for (std::uint32_t k = 0; k < 20; ++k) (void)nodes[k % 9]->send(can::make_frame(k, {}));
    b.run_until(clk, TimePoint{std::chrono::milliseconds(1)});
    return log;
  };
  const auto first = run();
  EXPECT_GT(first.size(), 100u);
  EXPECT_EQ(first, run());
}

}  // namespace
