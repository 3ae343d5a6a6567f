// SPDX-License-Identifier: MIT
// SDO server and client, byte-exact against the public python-canopen traces (see
// docs/canopen.md), every command specifier, segmented toggling, block transfer with CRC,
// abort codes, timeouts and retries, and a client/server pair in one process.
#include <gtest/gtest.h>

#include <deque>
#include <string>

#include "frames.hpp"
#include "hil/canopen/crc16.hpp"
#include "hil/canopen/sdo_client.hpp"
#include "hil/canopen/sdo_server.hpp"

using namespace hil::canopen;
using hil::canopen::test::f;
using hil::canopen::test::Recorder;
using hil::canopen::test::str;
using namespace std::chrono_literals;
using Strings = std::vector<std::string>;
namespace can = hil::can;

namespace {

std::vector<std::uint8_t> bytes(std::string_view s) {
  return {s.begin(), s.end()};
}

Variable var(std::uint16_t index, std::uint8_t sub, const char* name, DataType type, Access access, bool mappable,
             std::vector<std::uint8_t> value) {
  Variable v;
  v.index = index;
  v.sub = sub;
  v.name = name;
  v.type = type;
  v.access = access;
  v.pdo_mappable = mappable;
  v.value = std::move(value);
  return v;
}

ObjectDictionary make_od() {
  ObjectDictionary od;
  od.add(var(0x1000, 0, "Device type", DataType::unsigned32, Access::ro, false, {0x92, 0x01, 0x02, 0x00}));
  od.add(var(0x1008, 0, "Device name", DataType::visible_string, Access::const_, false,
             bytes("Tiny Node - Mega Domains !")));
  od.add(var(0x1017, 0, "Producer heartbeat time", DataType::unsigned16, Access::rw, false, {}));
  od.add(var(0x1018, 0, "Identity", DataType::unsigned8, Access::const_, false, {4}));
  od.add(var(0x1018, 1, "Vendor-ID", DataType::unsigned32, Access::ro, false, {4, 0, 0, 0}));
  od.add(var(0x1402, 0, "Highest sub-index", DataType::unsigned8, Access::const_, false, {0xFE}));
  od.add(var(0x2000, 0, "Text", DataType::visible_string, Access::rw, false, {}));
  od.add(var(0x2001, 0, "Secret", DataType::unsigned32, Access::wo, false, {}));
  Variable lim = var(0x2002, 0, "Limited", DataType::integer16, Access::rw, true, {});
  lim.low = -100;
  lim.high = 100;
  od.add(lim);
  od.add(var(0x2003, 0, "Flag", DataType::unsigned8, Access::rw, true, {}));
  return od;
}

struct ServerFixture : ::testing::Test {
  ObjectDictionary od = make_od();
  Recorder rec;
  SdoServer server{od, 2, rec.sink()};
  hil::TimePoint t{};
  Strings ask(std::initializer_list<const char*> reqs) {
    for (const char* r : reqs) server.on_frame(f(r), t += 1ms);
    return rec.take();
  }
};

}  // namespace

TEST_F(ServerFixture, ExpeditedUploadTrace) {
  EXPECT_EQ(ask({"602#4018100100000000"}), Strings{"582#4318100104000000"});
  EXPECT_EQ(ask({"602#4000100000000000"}), Strings{"582#4300100092010200"});
}

TEST_F(ServerFixture, ExpeditedDownloadTrace) {
  EXPECT_EQ(ask({"602#2B171000A00F0000"}), Strings{"582#6017100000000000"});
  EXPECT_EQ(od.get_int(0x1017, 0), 4000);
  // Expedited, size not indicated (0x22): the object's size is taken.
  EXPECT_EQ(ask({"602#2217100010270000"}), Strings{"582#6017100000000000"});
  EXPECT_EQ(od.get_int(0x1017, 0), 10000);
}

TEST_F(ServerFixture, SegmentedUploadTrace) {
  EXPECT_EQ(ask({"602#4008100000000000", "602#6000000000000000", "602#7000000000000000", "602#6000000000000000",
                 "602#7000000000000000"}),
            (Strings{"582#410810001A000000", "582#0054696E79204E6F", "582#106465202D204D65", "582#00676120446F6D61",
                     "582#15696E7320210000"}));
}

TEST_F(ServerFixture, SegmentedDownloadTrace) {
  EXPECT_EQ(ask({"602#210020000D000000", "602#0041206C6F6E6720", "602#13737472696E6700"}),
            (Strings{"582#6000200000000000", "582#2000000000000000", "582#3000000000000000"}));
  const auto* v = od.find(0x2000, 0);
  EXPECT_EQ(std::string(v->value.begin(), v->value.end()), "A long string");
  EXPECT_EQ(ask({"602#2100200000000000", "602#0F00000000000000"}),
            (Strings{"582#6000200000000000", "582#2000000000000000"}));
  EXPECT_TRUE(od.find(0x2000, 0)->value.empty());
}

TEST_F(ServerFixture, BlockDownloadTraceWithCrc) {
  // Block download of "A really really long string..." (30 bytes, CRC 0x6945).
  EXPECT_EQ(ask({"602#C60020001E000000"}), Strings{"582#A40020007F000000"});
  EXPECT_EQ(ask({"602#0141207265616C6C", "602#0279207265616C6C", "602#0379206C6F6E6720", "602#04737472696E672E",
                 "602#852E2E0000000000"}),
            Strings{"582#A2057F0000000000"});
  EXPECT_EQ(ask({"602#D545690000000000"}), Strings{"582#A100000000000000"});
}

TEST_F(ServerFixture, BlockDownloadBadCrcAborts) {
  ask({"602#C600200007000000"});
  EXPECT_EQ(ask({"602#8141424344454647"}), Strings{"582#A2017F0000000000"});
  EXPECT_EQ(ask({"602#C100000000000000"}), Strings{"582#8000200004000405"});
  EXPECT_TRUE(od.find(0x2000, 0)->value.empty()) << "nothing stored on a CRC error";
}

TEST_F(ServerFixture, BlockUploadTrace) {
  EXPECT_EQ(ask({"602#A40810007F000000"}), Strings{"582#C60810001A000000"});
  EXPECT_EQ(ask({"602#A300000000000000"}),
            (Strings{"582#0154696E79204E6F", "582#026465202D204D65", "582#03676120446F6D61", "582#84696E7320210000"}));
  EXPECT_EQ(ask({"602#A2047F0000000000"}), Strings{"582#C940E10000000000"});
  EXPECT_TRUE(ask({"602#A100000000000000"}).empty());
  EXPECT_FALSE(server.busy());
}

TEST_F(ServerFixture, AbortCodes) {
  struct Row {
    const char* req;
    const char* rsp;
  };
  const Row rows[] = {
      {"602#4018100500000000", "582#8018100511000906"},  // sub-index does not exist
      {"602#4000300000000000", "582#8000300000000206"},  // object does not exist
      {"602#4001200000000000", "582#8001200001000106"},  // read of a write-only object
      {"602#2300100001000000", "582#8000100002000106"},  // write of a read-only object: 0x06010002
      {"602#2F02200001000000", "582#8002200013000706"},  // 1 byte into INTEGER16: length too low
      {"602#2302200001000000", "582#8002200012000706"},  // 4 bytes into INTEGER16: length too high
      {"602#2B02200065000000", "582#8002200031000906"},  // 101 > high limit 100
      {"602#2B0220009BFF0000", "582#8002200032000906"},  // -101 < low limit
      {"602#E000100000000000", "582#8000100001000405"},  // unknown command specifier
      {"602#A40810000000000", "582#8008100001000405"},   // short frame (DLC 7)
      {"602#A408100080000000", "582#8008100002000405"},  // block upload with blksize 128
      {"602#2102200003000000", "582#8002200012000706"},  // segmented, size 3 into INTEGER16
  };
  for (const auto& r : rows) EXPECT_EQ(ask({r.req}), Strings{r.rsp}) << r.req;
}

TEST_F(ServerFixture, WrongToggleAndOversizeSegmentsAbort) {
  ask({"602#2100200003000000"});
  EXPECT_EQ(ask({"602#1041424300000000"}), Strings{"582#8000200000000305"}) << "toggle must start at 0";
  ask({"602#2100200003000000"});
  EXPECT_EQ(ask({"602#0041424344454647"}), Strings{"582#8000200012000706"}) << "7 bytes announced as 3";
  ask({"602#4008100000000000"});
  EXPECT_EQ(ask({"602#7000000000000000"}), Strings{"582#8008100000000305"});
}

TEST_F(ServerFixture, TimeoutAbortsAStalledTransfer) {
  ask({"602#4008100000000000"});
  server.step(t + 999ms);
  EXPECT_TRUE(rec.take().empty());
  server.step(t + 1001ms);
  EXPECT_EQ(rec.take(), Strings{"582#8008100000000405"});
  EXPECT_FALSE(server.busy());
}

TEST_F(ServerFixture, ClientAbortEndsTransferSilently) {
  ask({"602#4008100000000000"});
  EXPECT_TRUE(ask({"602#8008100000000405"}).empty());
  EXPECT_FALSE(server.busy());
}

TEST_F(ServerFixture, DelayedAndMutedResponses) {
  server.set_response_delay(50ms);
  EXPECT_TRUE(ask({"602#4018100100000000"}).empty());
  server.step(t + 49ms);
  EXPECT_TRUE(rec.take().empty());
  server.step(t + 50ms);
  EXPECT_EQ(rec.take(), Strings{"582#4318100104000000"});
  server.set_response_delay({});
  server.set_muted(true);
  EXPECT_TRUE(ask({"602#4018100100000000"}).empty());
}

// ---------------------------------------------------------------------------------------------
// Client against scripted server answers.

namespace {
struct ClientFixture : ::testing::Test {
  Recorder rec;
  SdoClient client{2, rec.sink()};
  hil::TimePoint t{};
  std::error_code ec;
  std::vector<std::uint8_t> data;
  bool done = false;
  SdoCompletion handler() {
    return [this](std::error_code e, std::vector<std::uint8_t> d) {
      ec = e;
      data = std::move(d);
      done = true;
    };
  }
  Strings answer(std::initializer_list<const char*> rsps) {
    for (const char* r : rsps) client.on_frame(f(r), t += 1ms);
    return rec.take();
  }
};
}  // namespace

TEST_F(ClientFixture, ExpeditedUploadVariants) {
  client.async_upload(0x1018, 1, t, handler());
  EXPECT_EQ(rec.take(), Strings{"602#4018100100000000"});
  answer({"582#4318100104000000"});
  ASSERT_TRUE(done && !ec);
  EXPECT_EQ(data, (std::vector<std::uint8_t>{4, 0, 0, 0}));
  done = false;
  client.async_upload(0x1400, 2, t, handler());
  rec.take();
  answer({"582#4F001402FE"});  // DLC 5, no padding: accepted
  EXPECT_EQ(data, std::vector<std::uint8_t>{0xFE});
  client.async_upload(0x1400, 2, t, handler());
  rec.take();
  answer({"582#42001402FE000000"});  // size not indicated: 4 bytes, caller trims by type
  EXPECT_EQ(data.size(), 4u);
}

TEST_F(ClientFixture, SegmentedUploadTrace) {
  client.async_upload(0x1008, 0, t, handler());
  EXPECT_EQ(rec.take(), Strings{"602#4008100000000000"});
  EXPECT_EQ(answer({"582#410810001A000000", "582#0054696E79204E6F", "582#106465202D204D65", "582#00676120446F6D61",
                    "582#15696E7320210000"}),
            (Strings{"602#6000000000000000", "602#7000000000000000", "602#6000000000000000", "602#7000000000000000"}));
  ASSERT_TRUE(done && !ec);
  EXPECT_EQ(std::string(data.begin(), data.end()), "Tiny Node - Mega Domains !");
}

TEST_F(ClientFixture, SegmentedDownloadTrace) {
  client.async_download(0x2000, 0, bytes("A long string"), t, handler());
  EXPECT_EQ(rec.take(), Strings{"602#210020000D000000"});
  EXPECT_EQ(answer({"582#6000200000000000"}), Strings{"602#0041206C6F6E6720"});
  EXPECT_EQ(answer({"582#2000000000000000"}), Strings{"602#13737472696E6700"});
  answer({"582#3000000000000000"});
  EXPECT_TRUE(done && !ec);
}

TEST_F(ClientFixture, ExpeditedDownloadAndWrongToggle) {
  client.async_download(0x1017, 0, {0xA0, 0x0F}, t, handler());
  EXPECT_EQ(rec.take(), Strings{"602#2B171000A00F0000"});
  answer({"582#6017100000000000"});
  EXPECT_TRUE(done && !ec);
  done = false;
  client.async_download(0x2000, 0, bytes("A long string"), t, handler());
  rec.take();
  answer({"582#6000200000000000"});
  rec.take();
  EXPECT_EQ(answer({"582#3000000000000000"}), Strings{"602#8000200000000305"});
  EXPECT_TRUE(done);
  EXPECT_EQ(ec, SdoAbort::toggle_bit);
}

TEST_F(ClientFixture, BlockDownloadTrace) {
  SdoClientOptions o;
  o.block = true;
  client.set_options(o);
  client.async_download(0x2000, 0, bytes("A really really long string..."), t, handler());
  EXPECT_EQ(rec.take(), Strings{"602#C60020001E000000"});
  EXPECT_EQ(answer({"582#A40020007F000000"}),
            (Strings{"602#0141207265616C6C", "602#0279207265616C6C", "602#0379206C6F6E6720", "602#04737472696E672E",
                     "602#852E2E0000000000"}));
  EXPECT_EQ(answer({"582#A2057F0000000000"}), Strings{"602#D545690000000000"});
  answer({"582#A100000000000000"});
  EXPECT_TRUE(done && !ec);
}

TEST_F(ClientFixture, BlockDownloadRetransmitsFromAckseq) {
  SdoClientOptions o;
  o.block = true;
  client.set_options(o);
  client.async_download(0x2000, 0, bytes("A really really long string..."), t, handler());
  rec.take();
  answer({"582#A40020007F000000"});
  EXPECT_EQ(answer({"582#A2027F0000000000"}),
            (Strings{"602#0179206C6F6E6720", "602#02737472696E672E", "602#832E2E0000000000"}))
      << "segments 3.. again, renumbered from 1";
}

TEST_F(ClientFixture, BlockUploadTrace) {
  SdoClientOptions o;
  o.block = true;
  o.block_threshold = 0;  // pst 0: no protocol switch
  client.set_options(o);
  client.async_upload(0x1008, 0, t, handler());
  EXPECT_EQ(rec.take(), Strings{"602#A40810007F000000"});
  EXPECT_EQ(answer({"582#C60810001A000000"}), Strings{"602#A300000000000000"});
  EXPECT_EQ(answer({"582#0154696E79204E6F", "582#026465202D204D65", "582#03676120446F6D61", "582#84696E7320210000"}),
            Strings{"602#A2047F0000000000"});
  EXPECT_EQ(answer({"582#C940E10000000000"}), Strings{"602#A100000000000000"});
  ASSERT_TRUE(done && !ec) << ec.message();
  EXPECT_EQ(std::string(data.begin(), data.end()), "Tiny Node - Mega Domains !");
}

TEST_F(ClientFixture, ServerAbortIsReported) {
  client.async_upload(0x1018, 5, t, handler());
  answer({"582#8018100511000906"});
  EXPECT_TRUE(done);
  EXPECT_EQ(ec, SdoAbort::no_sub_index);
  EXPECT_EQ(ec.value(), 0x06090011);
}

TEST_F(ClientFixture, TimeoutSendsAbortAndRetries) {
  SdoClientOptions o;
  o.timeout = 20ms;
  o.retries = 1;
  client.set_options(o);
  client.async_upload(0x1018, 1, t, handler());
  EXPECT_EQ(rec.take(), Strings{"602#4018100100000000"});
  client.step(t + 19ms);
  EXPECT_TRUE(rec.take().empty());
  client.step(t + 20ms);
  EXPECT_EQ(rec.take(), (Strings{"602#8018100100000405", "602#4018100100000000"})) << "abort, then the retry";
  EXPECT_FALSE(done);
  client.step(t + 40ms);
  EXPECT_EQ(rec.take(), Strings{"602#8018100100000405"});
  ASSERT_TRUE(done);
  EXPECT_EQ(ec, SdoAbort::timeout);
}

TEST_F(ClientFixture, QueuedTransfersRunInOrder) {
  std::vector<int> order;
  client.async_upload(0x1000, 0, t, [&](std::error_code, std::vector<std::uint8_t>) { order.push_back(1); });
  client.async_upload(0x1018, 1, t, [&](std::error_code, std::vector<std::uint8_t>) { order.push_back(2); });
  EXPECT_EQ(rec.take(), Strings{"602#4000100000000000"});
  EXPECT_EQ(answer({"582#4300100092010200"}), Strings{"602#4018100100000000"});
  answer({"582#4318100104000000"});
  EXPECT_EQ(order, (std::vector<int>{1, 2}));
}

// ---------------------------------------------------------------------------------------------
// Client and server wired together, every protocol, every size class.

namespace {
struct Pair {
  ObjectDictionary od = make_od();
  std::deque<can::Frame> to_server, to_client;
  SdoServer server{od, 2, [this](const can::Frame& fr) { to_client.push_back(fr); }};
  SdoClient client{2, [this](const can::Frame& fr) { to_server.push_back(fr); }};
  hil::TimePoint t{};
  std::size_t drop_nth_to_server = 0;  // 1-based; 0 = none
  std::size_t sent = 0;
  void pump() {
    while (!to_server.empty() || !to_client.empty()) {
      while (!to_server.empty()) {
        auto fr = to_server.front();
        to_server.pop_front();
        if (++sent == drop_nth_to_server) continue;
        server.on_frame(fr, t);
      }
      while (!to_client.empty()) {
        auto fr = to_client.front();
        to_client.pop_front();
        client.on_frame(fr, t);
      }
    }
  }
  void run_for(hil::Duration d) {
    for (auto end = t + d; t < end; t += 1ms) {
      server.step(t);
      client.step(t);
      pump();
    }
  }
};
}  // namespace

class SdoRoundTrip : public ::testing::TestWithParam<std::tuple<bool, std::size_t>> {};

TEST_P(SdoRoundTrip, DownloadThenUploadIsIdentical) {
  const auto [block, size] = GetParam();
  Pair p;
  SdoClientOptions o;
  o.block = block;
  o.block_threshold = 0;
  p.client.set_options(o);
  std::vector<std::uint8_t> payload(size);
  for (std::size_t i = 0; i < size; ++i) payload[i] = static_cast<std::uint8_t>(i * 7 + 3);
  std::error_code dec, uec;
  std::vector<std::uint8_t> back;
  p.client.async_download(0x2000, 0, payload, p.t, [&](std::error_code e, auto) { dec = e; });
  p.client.async_upload(0x2000, 0, p.t, [&](std::error_code e, std::vector<std::uint8_t> d) {
    uec = e;
    back = std::move(d);
  });
  p.pump();
  EXPECT_FALSE(dec) << dec.message();
  EXPECT_FALSE(uec) << uec.message();
  EXPECT_EQ(back, payload);
}
INSTANTIATE_TEST_SUITE_P(Sizes, SdoRoundTrip,
                         ::testing::Combine(::testing::Bool(),
                                            ::testing::Values(0u, 1u, 4u, 5u, 7u, 8u, 14u, 889u, 890u, 5000u)));

TEST(SdoLoss, LostSegmentTimesOutWithoutRetryAndSucceedsWithRetry) {
  Pair p;
  SdoClientOptions o;
  o.timeout = 10ms;
  p.client.set_options(o);
  p.drop_nth_to_server = 2;  // the first segment request
  std::error_code ec;
  bool done = false;
  p.client.async_upload(0x1008, 0, p.t, [&](std::error_code e, auto) { ec = e, done = true; });
  p.run_for(2s);
  ASSERT_TRUE(done);
  EXPECT_EQ(ec, SdoAbort::timeout);
  EXPECT_FALSE(p.server.busy()) << "the client's abort released the server";

  Pair q;
  o.retries = 2;
  q.client.set_options(o);
  q.drop_nth_to_server = 2;
  done = false;
  std::vector<std::uint8_t> data;
  q.client.async_upload(0x1008, 0, q.t, [&](std::error_code e, std::vector<std::uint8_t> d) {
    ec = e, done = true, data = std::move(d);
  });
  q.run_for(1s);
  ASSERT_TRUE(done);
  EXPECT_FALSE(ec) << ec.message();
  EXPECT_EQ(std::string(data.begin(), data.end()), "Tiny Node - Mega Domains !");
}

TEST(SdoLoss, LostBlockSegmentIsRetransmitted) {
  Pair p;
  SdoClientOptions o;
  o.block = true;
  o.block_threshold = 0;
  p.client.set_options(o);
  p.drop_nth_to_server = 4;  // segment 3 of the first block
  std::vector<std::uint8_t> payload(100, 0x5A);
  std::error_code ec{SdoAbort::general};
  p.client.async_download(0x2000, 0, payload, p.t, [&](std::error_code e, auto) { ec = e; });
  p.pump();
  EXPECT_FALSE(ec) << ec.message();
  EXPECT_EQ(p.od.find(0x2000, 0)->value, payload);
}
