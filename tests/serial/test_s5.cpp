// SPDX-License-Identifier: MIT
// 3964R procedure (DLE doubling, BCC, timeouts, retries, collision priority) and RK512
// telegrams; two procedures talking on virtual time; client against the IP247 / WF endpoints.
#include <gtest/gtest.h>

#include "hil/mocks/legacy/s5_block_endpoint.hpp"
#include "hil/serial/memory_line.hpp"
#include "hil/serial/s5/db_listing.hpp"
#include "hil/serial/s5/procedure_3964r.hpp"
#include "hil/serial/s5/rk512.hpp"
#include "hil/serial/s5/rk512_client.hpp"
#include "hil/serial/serial_stream.hpp"

using namespace hil::serial;
using namespace hil::serial::s5;
using namespace std::chrono_literals;
using Bytes = std::vector<std::uint8_t>;

TEST(Procedure3964, NotesVectorBccEqualToDle) {
  // notes §4.1: payload 01 10 02 -> 01 10 10 02 10 03 with BCC 0x10, not doubled.
  EXPECT_EQ(make_block({0x01, 0x10, 0x02}, true), (Bytes{0x01, 0x10, 0x10, 0x02, 0x10, 0x03, 0x10}));
  EXPECT_EQ(make_block({0x01, 0x10, 0x02}, false), (Bytes{0x01, 0x10, 0x10, 0x02, 0x10, 0x03}));
}

namespace {
/// Connects two procedures byte for byte; `corrupt` may damage a->b traffic.
struct Pair {
  Procedure3964 a, b;
  hil::VirtualClock clock;
  std::function<void(Bytes&)> corrupt;
  std::function<void(Bytes&)> corrupt_ba;
  void run(hil::Duration max = 60s) {
    const auto end = clock.now() + max;
    while (clock.now() < end) {
      a.poll(clock.now());
      b.poll(clock.now());
      Bytes ab = a.take_output();
      Bytes ba = b.take_output();
      if (corrupt && !ab.empty()) corrupt(ab);
      if (corrupt_ba && !ba.empty()) corrupt_ba(ba);
      if (!ab.empty()) b.on_bytes(ab, clock.now());
      if (!ba.empty()) a.on_bytes(ba, clock.now());
      if (ab.empty() && ba.empty()) {
        const auto next = std::min(a.next_deadline(), b.next_deadline());
        if (next == hil::TimePoint::max()) return;
        clock.advance_to(next);
      }
    }
  }
};
}  // namespace

TEST(Procedure3964, BlockTransferWithDleInPayloadAndBcc) {
  Pair p;
  Bytes payload{0x00, 0x00, 'A', 'D', 0x0A, 0x80, 0x00, 0x01, 0xFF, 0xFF, 0x10, 0x10, 0x02, 0x03};
  p.a.send(payload);
  p.run();
  auto res = p.a.take_send_result();
  ASSERT_TRUE(res);
  EXPECT_TRUE(res->ok);
  EXPECT_EQ(p.b.take_received(), payload);
}

TEST(Procedure3964, BccErrorGetsNakAndTheRetrySucceeds) {
  Pair p;
  int damaged = 0;
  p.corrupt = [&](Bytes& v) {
    if (v.size() > 3 && damaged == 0) {
      v[1] ^= 0x01;
      ++damaged;
    }
  };
  p.a.send({1, 2, 3, 4, 5});
  p.run();
  EXPECT_TRUE(p.a.take_send_result()->ok);
  EXPECT_EQ(p.a.retries(), 1);
  EXPECT_EQ(p.b.take_receive_errors().front(), ProcedureError::bcc_error);
  EXPECT_EQ(p.b.take_received(), (Bytes{1, 2, 3, 4, 5}));
}

TEST(Procedure3964, NoPartnerGivesNoConnectionAfterAllAttemptsOnVirtualTime) {
  Procedure3964 a;
  hil::VirtualClock clock;
  a.send({1});
  int stx_count = 0;
  for (int i = 0; i < 100 && !a.idle(); ++i) {
    a.poll(clock.now());
    for (auto b : a.take_output()) stx_count += b == stx ? 1 : 0;
    if (a.next_deadline() != hil::TimePoint::max()) clock.advance_to(a.next_deadline());
    if (auto r = a.take_send_result()) {
      EXPECT_FALSE(r->ok);
      EXPECT_EQ(r->error, ProcedureError::no_connection);
      break;
    }
  }
  EXPECT_EQ(stx_count, 6);
  // 6 attempts x QVZ 2 s + 5 retry delays of ZVZ 220 ms
  EXPECT_EQ(clock.now().time_since_epoch(), 6 * 2000ms + 5 * 220ms);
}

TEST(Procedure3964, CharacterDelayTimeoutAnswersNak) {
  Procedure3964 b;
  hil::VirtualClock clock;
  b.on_bytes(Bytes{stx}, clock.now());
  EXPECT_EQ(b.take_output(), Bytes{dle});
  b.on_bytes(Bytes{0x41}, clock.now());
  clock.advance(221ms);
  b.poll(clock.now());
  EXPECT_EQ(b.take_output(), Bytes{nak});
  EXPECT_EQ(b.take_receive_errors().front(), ProcedureError::char_timeout);
}

TEST(Procedure3964, CollisionLowPriorityDefersAndBothBlocksArrive) {
  Pair p;
  ProcedureOptions low;
  low.high_priority = false;
  p.b = Procedure3964(low);
  p.a.send({0xA1});
  p.b.send({0xB2});
  p.run();
  EXPECT_TRUE(p.a.take_send_result()->ok);
  EXPECT_TRUE(p.b.take_send_result()->ok);
  EXPECT_EQ(p.b.take_received(), Bytes{0xA1});
  EXPECT_EQ(p.a.take_received(), Bytes{0xB2});
}

TEST(Procedure3964, PlainProcedureWithoutBcc) {
  Pair p;
  ProcedureOptions o;
  o.with_bcc = false;
  o.ack_timeout = 550ms;
  p.a = Procedure3964(o);
  p.b = Procedure3964(o);
  p.a.send({0x10, 0x03});
  p.run();
  EXPECT_TRUE(p.a.take_send_result()->ok);
  EXPECT_EQ(p.b.take_received(), (Bytes{0x10, 0x03}));
}

TEST(Rk512, BoschExampleHeader) {
  // notes §4.2: SEND to DB10 from DW128 (0x80), 50 words -> 00 00 41 44 0A 80 00 32 FF FF + data
  Rk512Header h;
  h.db = 10;
  h.dw = 0x80;
  h.length = 50;
  Bytes data(100, 0x55);
  auto t = make_rk512_request(h, data);
  ASSERT_EQ(t.size(), 1U);
  EXPECT_EQ(Bytes(t[0].begin(), t[0].begin() + 10),
            (Bytes{0x00, 0x00, 0x41, 0x44, 0x0A, 0x80, 0x00, 0x32, 0xFF, 0xFF}));
  auto parsed = parse_rk512(t[0]);
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->header, h);
  EXPECT_EQ(parsed->data.size(), 100U);
}

TEST(Rk512, ContinuationsCarryFourByteHeadersAndReassemble) {
  Rk512Header h;
  h.db = 3;
  h.length = 140;  // 280 bytes -> 128 + 128 + 24
  Bytes data(280);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i);
  auto t = make_rk512_request(h, data);
  ASSERT_EQ(t.size(), 3U);
  EXPECT_EQ(Bytes(t[1].begin(), t[1].begin() + 4), (Bytes{0xFF, 0x00, 0x41, 0x44}));
  Rk512Assembler as;
  EXPECT_EQ(as.feed(*parse_rk512(t[0])), Rk512Assembler::Status::need_more);
  EXPECT_EQ(as.feed(*parse_rk512(t[1])), Rk512Assembler::Status::need_more);
  EXPECT_EQ(as.feed(*parse_rk512(t[2])), Rk512Assembler::Status::complete);
  EXPECT_EQ(as.job().data, data);
  Rk512Assembler orphan;
  EXPECT_EQ(orphan.feed(*parse_rk512(t[1])), Rk512Assembler::Status::error);
}

TEST(Rk512, ParseErrors) {
  EXPECT_FALSE(parse_rk512(Bytes{0x00, 0x00}));
  EXPECT_FALSE(parse_rk512(Bytes{0x01, 0x00, 'A', 'D'}));
  EXPECT_FALSE(parse_rk512(Bytes{0x00, 0x00, 'Q', 'D', 0, 0, 0, 0, 0xFF, 0xFF}));
  EXPECT_FALSE(parse_rk512(Bytes{0x00, 0x00, 'A', 'M', 0, 0, 0, 1, 0xFF, 0xFF, 0, 0}));  // SEND only D/X
  EXPECT_FALSE(parse_rk512(Bytes{0x00, 0x00, 'A', 'D', 0, 0}));                          // short header
  auto r = parse_rk512(Bytes{0x00, 0x00, 0x00, 0x07});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->kind, Rk512Telegram::Kind::reaction);
  EXPECT_EQ(r->error, Rk512Error::db_exists);
}

namespace {
std::vector<std::uint16_t> md_image(std::uint8_t db, std::uint8_t axis) {
  std::vector<std::uint16_t> w(70, 0);
  w[0] = 70;
  w[1] = 0x0044;
  w[2] = static_cast<std::uint16_t>(0x4200 | db);
  w[3] = axis;
  w[4] = 0x0100;
  w[5] = 0x0000;
  w[6] = 0x1388;  // fmax 5000 Hz
  return w;
}

/// Client and endpoint on one thread over a memory line on virtual time.
struct S5Fixture {
  hil::VirtualClock clock;
  MemoryLinePair line = make_memory_line(&clock);
  std::unique_ptr<SerialStream> client_stream;
  std::unique_ptr<SerialStream> device_stream;
  std::unique_ptr<hil::mocks::legacy::S5BlockEndpoint> ep;
  explicit S5Fixture(std::unique_ptr<hil::mocks::legacy::DbPolicy> policy) {
    LineFormat f = *parse_char_format("8E1");
    client_stream = std::make_unique<SerialStream>(std::move(line.a), f, Discipline{}, clock);
    device_stream = std::make_unique<SerialStream>(std::move(line.b), f, Discipline{}, clock);
    ep = std::make_unique<hil::mocks::legacy::S5BlockEndpoint>(std::move(policy));
    // The device answers inside the client's writes: run the endpoint whenever bytes cross.
    auto* dev = device_stream.get();
    auto* e = ep.get();
    auto* clk = &clock;
    *line.a_to_b = [dev, e, clk](std::vector<std::uint8_t>& bytes) {
      (void)dev;
      std::string out = e->on_bytes(bytes, clk->now());
      bytes.clear();  // consumed by the endpoint directly
      if (!out.empty())
        (void)dev->raw().write(std::span(reinterpret_cast<const std::uint8_t*>(out.data()), out.size()), 1s);
    };
  }
};
}  // namespace

TEST(Ip247Endpoint, WriteReadNoOverwriteDeleteAndRejectedImage) {
  S5Fixture f(hil::mocks::legacy::make_ip247_policy(
      [](std::uint8_t, const std::vector<std::uint16_t>& w) { return w[6] == 0 ? 3 : 0; }));
  Rk512Client c(*f.client_stream, f.clock);
  const auto img = md_image(10, 1);
  ASSERT_TRUE(c.send_db(10, 0, img));
  auto back = c.fetch_db(10, 0, 70);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(*back, img);
  auto again = c.send_db(10, 0, img);
  ASSERT_FALSE(again);
  EXPECT_EQ(again.error().code, Rk512Error::db_exists);
  ASSERT_TRUE(c.send_db(10, 0, {0x0000}));  // delete
  EXPECT_EQ(c.fetch_db(10, 0, 1).error().code, Rk512Error::db_missing);
  auto bad = md_image(11, 1);
  bad[6] = 0;  // fmax 0: the profile check refuses it
  EXPECT_EQ(c.send_db(11, 0, bad).error().code, Rk512Error::image_rejected);
  EXPECT_FALSE(f.ep->store().contains(11)) << "a rejected image must not be stored";
  auto wrong_db = md_image(12, 1);
  EXPECT_EQ(c.send_db(13, 0, wrong_db).error().code, Rk512Error::wrong_identifier);
  EXPECT_EQ(c.send_db(14, 0, md_image(14, 4)).error().code, Rk512Error::image_rejected);  // axis 4
}

TEST(Ip247Endpoint, StateSurvivesSaveAndLoad) {
  S5Fixture f(hil::mocks::legacy::make_ip247_policy({}));
  Rk512Client c(*f.client_stream, f.clock);
  ASSERT_TRUE(c.send_db(20, 0, md_image(20, 2)));
  const std::string state = f.ep->save_state();
  hil::mocks::legacy::S5BlockEndpoint restored(hil::mocks::legacy::make_ip247_policy({}));
  ASSERT_TRUE(restored.load_state(state));
  EXPECT_EQ(restored.store().at(20), md_image(20, 2));
}

TEST(Wf725Endpoint, DataCodesAndMdArea) {
  // The check stands in for the profile: MD34 (pulse check, DW 66/67) must not be 0.
  S5Fixture f(hil::mocks::legacy::make_wf725_policy(
      [](const std::vector<std::uint16_t>& w) { return w[66] != 0 || w[67] != 0; }));
  f.ep->store()[1] = std::vector<std::uint16_t>(100, 0);
  f.ep->store()[1][67] = 4000;
  Rk512Client c(*f.client_stream, f.clock);
  // MD11 = -24537 um binary FFFF A027 (wf725 vectors), written at DW 20/21.
  ASSERT_TRUE(c.send_db(1, 20, {0xFFFF, 0xA027}));
  auto back = c.fetch_db(1, 20, 2);
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, (std::vector<std::uint16_t>{0xFFFF, 0xA027}));
  EXPECT_EQ(c.fetch_db(0, 0, 2).error().code, Rk512Error::header_error);         // data code 0 (WF 112)
  EXPECT_EQ(c.fetch_db(0x77, 0, 2).error().code, Rk512Error::header_error);      // unknown code (WF 113)
  EXPECT_TRUE(c.fetch_db(0x03, 0, 2));                                           // speed in rpm
  EXPECT_EQ(c.send_db(1, 66, {0, 0}).error().code, Rk512Error::image_rejected);  // MD34 = 0
  EXPECT_EQ(f.ep->store()[1][67], 4000) << "a rejected write changes nothing";
  EXPECT_EQ(c.send_db(1, 100, {0, 0}).error().code, Rk512Error::target_too_small);  // MD51 (WF 121)
}

TEST(DbListing, RoundTripAndErrors) {
  std::vector<DbImage> dbs{{10, md_image(10, 1)}, {1, {0x2520, 0x2031}}};
  const std::string text = make_db_listing(dbs, "test");
  auto back = parse_db_listing(text, "t.s5db");
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, dbs);
  auto ky = parse_db_listing("DB1\n 0: KF = +00070\n 1: KY = 066,001\n 2: KH = 44\n", "x");
  ASSERT_TRUE(ky);
  EXPECT_EQ((*ky)[0].words, (std::vector<std::uint16_t>{70, 0x4201, 0x0044}));
  auto bad = parse_db_listing("DB1\n 0: KH = 12345\n 2: KF = 1\n 3: KZ = 1\nDB300\n", "x.s5db");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().size(), 4U);
  EXPECT_NE(bad.error()[0].find("x.s5db:2:"), std::string::npos);
}
