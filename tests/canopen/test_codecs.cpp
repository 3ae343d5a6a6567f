// SPDX-License-Identifier: MIT
// Byte-exact tables for NMT, heartbeat, node guarding, SYNC, EMCY and CRC-16 (CiA 301), with
// vectors from the public stacks cited in docs/canopen.md.
#include <gtest/gtest.h>

#include <string>

#include "frames.hpp"
#include "hil/canopen/crc16.hpp"
#include "hil/canopen/emcy.hpp"
#include "hil/canopen/heartbeat.hpp"
#include "hil/canopen/nmt.hpp"
#include "hil/canopen/sdo_abort.hpp"
#include "hil/canopen/sync.hpp"

using namespace hil::canopen;
using hil::canopen::test::f;
using hil::canopen::test::str;
using namespace std::chrono_literals;

TEST(Nmt, CommandFramesAreByteExact) {
  struct Row {
    NmtCommand cmd;
    NodeId node;
    const char* frame;
  };
  const Row rows[] = {
      {NmtCommand::start, 0, "000#0100"},      {NmtCommand::reset_communication, 5, "000#8205"},
      {NmtCommand::stop, 5, "000#0205"},       {NmtCommand::enter_preoperational, 127, "000#807F"},
      {NmtCommand::reset_node, 1, "000#8101"},
  };
  for (const auto& r : rows) {
    EXPECT_EQ(str(make_nmt(r.cmd, r.node)), r.frame);
    const auto p = parse_nmt(f(r.frame));
    ASSERT_TRUE(p) << r.frame;
    EXPECT_EQ(p->command, r.cmd);
    EXPECT_EQ(p->node, r.node);
  }
}

TEST(Nmt, MalformedCommandsAreRejected) {
  for (const char* bad : {"000#01", "000#0380", "000#0180", "001#0100", "000#", "000#5000", "000#6000"})
    EXPECT_FALSE(parse_nmt(f(bad))) << bad;
}

TEST(Heartbeat, StatesAreByteExact) {
  EXPECT_EQ(str(make_heartbeat(5, NmtState::initialising)), "705#00");
  EXPECT_EQ(str(make_heartbeat(5, NmtState::preoperational)), "705#7F");
  EXPECT_EQ(str(make_heartbeat(5, NmtState::operational)), "705#05");
  EXPECT_EQ(str(make_heartbeat(5, NmtState::stopped)), "705#04");
  EXPECT_EQ(str(make_guard_response(5, NmtState::operational, true)), "705#85");
  EXPECT_EQ(str(make_guard_request(5)), "705#R1");
  const auto m = parse_error_control(f("705#85"));
  ASSERT_TRUE(m);
  EXPECT_EQ(m->node, 5);
  EXPECT_EQ(m->state, NmtState::operational);
  EXPECT_TRUE(m->toggle);
  for (const char* bad : {"705#", "705#06", "700#05", "780#05", "705#R1"})
    EXPECT_FALSE(parse_error_control(f(bad))) << bad;
}

TEST(Heartbeat, ProducerEmitsEveryPeriod) {
  hil::canopen::test::Recorder rec;
  HeartbeatProducer p(3, rec.sink());
  hil::TimePoint t{};
  p.set_period(100ms, t);
  for (int i = 0; i < 350; ++i) p.step(t += 1ms, NmtState::operational);
  EXPECT_EQ(rec.take(), (std::vector<std::string>{"703#05", "703#05", "703#05"}));
  p.set_muted(true);
  for (int i = 0; i < 200; ++i) p.step(t += 1ms, NmtState::operational);
  EXPECT_TRUE(rec.take().empty());
}

TEST(Heartbeat, ConsumerTimesOutOnlyAfterFirstHeartbeat) {
  std::vector<std::pair<NodeId, HeartbeatEvent>> events;
  HeartbeatConsumer c([&](NodeId n, HeartbeatEvent e, NmtState) { events.emplace_back(n, e); });
  c.set_consumer_entry(0x00050064);  // node 5, 100 ms (0x1016 encoding)
  hil::TimePoint t{};
  c.step(t += 1s);
  EXPECT_TRUE(events.empty()) << "a node that never sent a heartbeat must not time out";
  c.on_frame(f("705#00"), t);
  c.on_frame(f("705#7F"), t += 10ms);
  c.step(t += 100ms);
  EXPECT_TRUE(events.size() == 2 && !c.timed_out(5));
  c.step(t += 1ms);
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].second, HeartbeatEvent::boot_up);
  EXPECT_EQ(events[1].second, HeartbeatEvent::state_changed);
  EXPECT_EQ(events[2].second, HeartbeatEvent::timeout);
  c.step(t += 1s);
  EXPECT_EQ(events.size(), 3u) << "timeout reported once per loss";
  c.on_frame(f("705#7F"), t);
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[3].second, HeartbeatEvent::resumed);
  EXPECT_FALSE(c.on_frame(f("706#7F"), t)) << "unmonitored node";
}

TEST(NodeGuarding, RequestsToggleAndLoss) {
  hil::canopen::test::Recorder rec;
  std::vector<NodeGuardMaster::Event> events;
  NodeGuardMaster g(rec.sink(), [&](NodeId, NodeGuardMaster::Event e, NmtState) { events.push_back(e); });
  hil::TimePoint t{};
  g.guard(9, 100ms, 3, t);
  g.step(t);
  EXPECT_EQ(rec.take(), std::vector<std::string>{"709#R1"});
  g.on_frame(f("709#7F"), t += 5ms);
  g.on_frame(f("709#FF"), t += 100ms);
  EXPECT_EQ(events, std::vector<NodeGuardMaster::Event>{NodeGuardMaster::Event::state});
  g.on_frame(f("709#FF"), t += 5ms);  // toggle not alternated
  EXPECT_EQ(events.back(), NodeGuardMaster::Event::toggle_error);
  for (int i = 0; i < 400; ++i) g.step(t += 1ms);
  EXPECT_EQ(events.back(), NodeGuardMaster::Event::lost);
}

TEST(Sync, CounterAndPeriod) {
  hil::canopen::test::Recorder rec;
  SyncProducer s(rec.sink());
  hil::TimePoint t{};
  s.configure(1ms, 3, t);
  for (int i = 0; i < 5; ++i) {
    s.step(t);
    t += 1ms;
  }
  EXPECT_EQ(rec.take(), (std::vector<std::string>{"080#01", "080#02", "080#03", "080#01", "080#02"}));
  s.configure(1ms, 0, t);
  s.step(t);
  s.step(t + 500us);
  EXPECT_EQ(rec.take(), std::vector<std::string>{"080#"});
  EXPECT_TRUE(parse_sync(f("080#")));
  EXPECT_EQ(parse_sync(f("080#07"))->counter, 7);
  EXPECT_FALSE(parse_sync(f("080#00")));
  EXPECT_FALSE(parse_sync(f("080#0102")));
  EXPECT_FALSE(parse_sync(f("081#")));
}

TEST(Emcy, FramesAndInhibit) {
  EmcyMessage m{5, 0x8611, 0x21, {1, 2, 3, 4, 5}};
  EXPECT_EQ(str(make_emcy(m)), "085#1186210102030405");
  EXPECT_EQ(parse_emcy(f("085#1186210102030405")), m);
  EXPECT_FALSE(parse_emcy(f("085#118621")));
  EXPECT_FALSE(parse_emcy(f("080#1186210102030405")));
  hil::canopen::test::Recorder rec;
  EmcyProducer p(5, rec.sink());
  p.set_inhibit(10ms);
  hil::TimePoint t{};
  p.raise(0x2310, 0x03, {}, t);
  p.raise(0x0000, 0x00, {}, t);
  EXPECT_EQ(rec.take(), std::vector<std::string>{"085#1023030000000000"});
  p.step(t += 9ms);
  EXPECT_TRUE(rec.take().empty());
  p.step(t += 1ms);
  EXPECT_EQ(rec.take(), std::vector<std::string>{"085#0000000000000000"});
}

TEST(Crc16, CheckValuesMatchPublicTraces) {
  const std::string a = "123456789", b = "A really really long string...", c = "Tiny Node - Mega Domains !";
  const auto span = [](const std::string& s) {
    return std::span(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
  };
  EXPECT_EQ(crc16_ccitt(span(a)), 0x31C3);
  EXPECT_EQ(crc16_ccitt(span(b)), 0x6945);
  EXPECT_EQ(crc16_ccitt(span(c)), 0xE140);
  EXPECT_EQ(crc16_ccitt(span(a).subspan(4), crc16_ccitt(span(a).first(4))), 0x31C3) << "incremental";
}

TEST(SdoAbortCodes, ValuesAreTheWireCodes) {
  EXPECT_EQ(static_cast<std::uint32_t>(SdoAbort::write_only), 0x06010001u) << "read of a write-only object";
  EXPECT_EQ(static_cast<std::uint32_t>(SdoAbort::read_only), 0x06010002u)
      << "write of a read-only object (openCANopen swaps these)";
  std::error_code ec = SdoAbort::no_sub_index;
  EXPECT_EQ(ec.value(), 0x06090011);
  EXPECT_STREQ(ec.category().name(), "canopen.sdo");
  EXPECT_EQ(ec.message(), "0x06090011 Sub-index does not exist");
  EXPECT_TRUE(is_known_abort_code(0x08000024));
  EXPECT_FALSE(is_known_abort_code(0x12345678));
}
