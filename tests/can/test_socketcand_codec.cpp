// SPDX-License-Identifier: MIT
// socketcand codec: wire forms from the daemon's sources (state_raw.c) and python-can's client,
// table-driven parse errors, stream splitting across reads, and format/parse round trips.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "hil/can/socketcand.hpp"

namespace can = hil::can;
namespace sc = hil::can::socketcand;

namespace {

template <class T>
T parse_as(std::string_view text) {
  auto e = sc::parse_element(text);
  EXPECT_TRUE(e.has_value()) << text << ": " << (e ? "" : e.error().message());
  if (!e) return T{};
  EXPECT_TRUE(std::holds_alternative<T>(*e)) << text;
  return std::holds_alternative<T>(*e) ? std::get<T>(*e) : T{};
}

TEST(SocketcandCodec, ParsesSessionElements) {
  parse_as<sc::Hi>("< hi >");
  parse_as<sc::Ok>("<ok>");
  EXPECT_EQ(parse_as<sc::Open>("< open can0 >").bus, "can0");
  EXPECT_EQ(parse_as<sc::SwitchMode>("< rawmode >").mode, sc::Mode::raw);
  EXPECT_EQ(parse_as<sc::SwitchMode>("< bcmmode >").mode, sc::Mode::bcm);
  EXPECT_EQ(parse_as<sc::ErrorText>("< error could not open bus >").text, "could not open bus");
  EXPECT_EQ(parse_as<sc::Other>("< add 1 0 123 8 11 22 33 44 55 66 77 88 >").command, "add");
}

TEST(SocketcandCodec, ParsesRxFramesAsTheDaemonPrintsThem) {
  auto r = parse_as<sc::RxFrame>("< frame 123 23.424242 1A220344 >");
  EXPECT_EQ(r.frame, can::make_frame(0x123, {0x1A, 0x22, 0x03, 0x44}));
  EXPECT_EQ(r.time, (sc::Timestamp{23, 424242}));
  auto sync = parse_as<sc::RxFrame>("< frame 080 1700000000.000123  >");
  EXPECT_EQ(sync.frame, can::make_frame(0x080, {}));
  EXPECT_EQ(sync.time, (sc::Timestamp{1700000000, 123}));
  auto ext = parse_as<sc::RxFrame>("< frame 1ABCDEF0 1.5 0102 >");
  EXPECT_TRUE(ext.frame.extended);
  EXPECT_EQ(ext.frame.id, 0x1ABCDEF0u);
  EXPECT_EQ(ext.time.usec, 500000u);
  auto ext_small = parse_as<sc::RxFrame>("< frame 00000123 1.000000 >");
  EXPECT_TRUE(ext_small.frame.extended) << "8 digits mean 29-bit even for a small value";
  auto spaced = parse_as<sc::RxFrame>("< frame 123 1.000000 11 22 33 >");
  EXPECT_EQ(spaced.frame, can::make_frame(0x123, {0x11, 0x22, 0x33}));
}

TEST(SocketcandCodec, ParsesSendAsPythonCanAndTheDocsWriteIt) {
  EXPECT_EQ(parse_as<sc::Send>("< send 1AAAAAAA 2 1 f1 >").frame,
            can::make_extended_frame(0x1AAAAAAA, std::vector<std::uint8_t>{0x01, 0xF1}));
  EXPECT_EQ(parse_as<sc::Send>("< send 601 8 40 18 10 1 0 0 0 0 >").frame,
            can::make_frame(0x601, {0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0}));
  // python-can 4.1 does not pad ids: "< send 80 0  >" is SYNC, "< send 1234 1 ff >" is 29-bit.
  EXPECT_EQ(parse_as<sc::Send>("< send 80 0  >").frame, can::make_frame(0x80, {}));
  EXPECT_TRUE(parse_as<sc::Send>("< send 1234 1 ff >").frame.extended);
}

TEST(SocketcandCodec, ParsesErrorFrames) {
  auto e = parse_as<sc::ErrorFrame>("< error 040 1700000000.000001 >");
  EXPECT_TRUE(e.frame.error);
  EXPECT_EQ(e.frame.id, can::error_class::bus_off);
  EXPECT_EQ(e.time, (sc::Timestamp{1700000000, 1}));
}

struct BadCase {
  const char* text;
  sc::ParseErrc errc;
};

TEST(SocketcandCodec, RejectsMalformedElementsWithTheRightCode) {
  const BadCase cases[] = {
      {"hi", sc::ParseErrc::not_an_element},
      {"< hi", sc::ParseErrc::not_an_element},
      {"< <hi> >", sc::ParseErrc::not_an_element},
      {"<   >", sc::ParseErrc::empty_element},
      {"< bogus >", sc::ParseErrc::unknown_command},
      {"< hi there >", sc::ParseErrc::extra_argument},
      {"< open >", sc::ParseErrc::missing_argument},
      {"< open abcdefghijklmnopq >", sc::ParseErrc::bad_bus_name},
      {"< send >", sc::ParseErrc::missing_argument},
      {"< send 12G 1 00 >", sc::ParseErrc::bad_id},
      {"< send 123456789 1 00 >", sc::ParseErrc::bad_id},
      {"< send 3FFFFFFF 1 00 >", sc::ParseErrc::bad_id},
      {"< send 123 9 0 0 0 0 0 0 0 0 0 >", sc::ParseErrc::bad_dlc},
      {"< send 123 10 0 >", sc::ParseErrc::bad_dlc},
      {"< send 123 2 00 >", sc::ParseErrc::bad_data},
      {"< send 123 1 00 11 >", sc::ParseErrc::bad_data},
      {"< send 123 1 100 >", sc::ParseErrc::bad_data},
      {"< send 123 1 zz >", sc::ParseErrc::bad_data},
      {"< frame 123 >", sc::ParseErrc::missing_argument},
      {"< frame 123 x.5 00 >", sc::ParseErrc::bad_timestamp},
      {"< frame 123 1. 00 >", sc::ParseErrc::bad_timestamp},
      {"< frame 123 1.0000000000 00 >", sc::ParseErrc::bad_timestamp},
      {"< frame 123 1.0 0 >", sc::ParseErrc::bad_data},
      {"< frame 123 1.0 001122334455667788 >", sc::ParseErrc::bad_data},
  };
  for (const auto& c : cases) {
    auto e = sc::parse_element(c.text);
    ASSERT_FALSE(e.has_value()) << c.text;
    EXPECT_EQ(e.error(), sc::make_error_code(c.errc)) << c.text << " gave " << e.error().message();
    EXPECT_FALSE(e.error().message().empty());
  }
}

TEST(SocketcandCodec, FormatsExactlyLikeTheDaemon) {
  std::string out;
  ASSERT_TRUE(sc::format_rx_frame(out, can::make_frame(0x123, {0x1A, 0x22, 0x03, 0x44}), {23, 424242}));
  EXPECT_EQ(out, "< frame 123 23.424242 1A220344 >");
  out.clear();
  ASSERT_TRUE(sc::format_rx_frame(out, can::make_frame(0x080, {}), {1700000000, 123}));
  EXPECT_EQ(out, "< frame 080 1700000000.000123  >");
  out.clear();
  ASSERT_TRUE(sc::format_rx_frame(out, can::make_extended_frame(0x1AAAAAAA, std::vector<std::uint8_t>{0xF1}), {1, 0}));
  EXPECT_EQ(out, "< frame 1AAAAAAA 1.000000 F1 >");
  out.clear();
  ASSERT_TRUE(sc::format_send(out, can::make_frame(0x601, {0x40, 0x18})));
  EXPECT_EQ(out, "< send 601 2 40 18 >");
  out.clear();
  EXPECT_FALSE(sc::format_send(out, can::make_remote_frame(0x701, 1))) << "socketcand has no RTR form";
  EXPECT_FALSE(sc::format_rx_frame(out, can::make_remote_frame(0x701, 1), {}));
  EXPECT_TRUE(out.empty());
  sc::format_error_frame(out, can::error_class::controller, {5, 6});
  EXPECT_EQ(out, "< error 004 5.000006 >");
  out.clear();
  sc::format_error_text(out, "bad <thing>");
  EXPECT_EQ(out, "< error bad ?thing? >");
}

TEST(SocketcandCodec, RoundTripsRandomFrames) {
  std::mt19937 rng(1234);
  for (int i = 0; i < 2000; ++i) {
    can::Frame f;
    f.extended = (rng() & 1) != 0;
    f.id = static_cast<std::uint32_t>(rng()) & (f.extended ? can::eff_mask : can::sff_mask);
    f.dlc = static_cast<std::uint8_t>(rng() % 9);
    for (int k = 0; k < f.dlc; ++k) f.data[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(rng());
    std::string s;
    ASSERT_TRUE(sc::format_send(s, f));
    auto back = sc::parse_element(s);
    ASSERT_TRUE(back) << s;
    EXPECT_EQ(std::get<sc::Send>(*back).frame, f) << s;
    s.clear();
    const sc::Timestamp t{static_cast<std::int64_t>(rng()), static_cast<std::uint32_t>(rng() % 1000000)};
    ASSERT_TRUE(sc::format_rx_frame(s, f, t));
    back = sc::parse_element(s);
    ASSERT_TRUE(back) << s;
    EXPECT_EQ(std::get<sc::RxFrame>(*back), (sc::RxFrame{f, t})) << s;
  }
}

std::vector<std::string> split_all(sc::ElementSplitter& sp, std::vector<std::string>* errors = nullptr) {
  std::vector<std::string> out;
  sc::ElementSplitter::Item item;
  while (sp.next(item)) {
    if (item.error) {
      if (errors) errors->push_back(item.error.message());
    } else {
      out.emplace_back(item.element);
    }
  }
  return out;
}

TEST(SocketcandSplitter, HandlesConcatenatedSplitAndGarbageInput) {
  sc::ElementSplitter sp;
  sp.feed("< hi >< ok ><frame 1");
  EXPECT_EQ(split_all(sp), (std::vector<std::string>{"< hi >", "< ok >"}));
  sp.feed("23 1.0 00 >junk< open");
  EXPECT_EQ(split_all(sp), (std::vector<std::string>{"<frame 123 1.0 00 >"}));
  sp.feed(" can0 >");
  EXPECT_EQ(split_all(sp), (std::vector<std::string>{"< open can0 >"}));
  EXPECT_EQ(sp.skipped_bytes(), 4u);
  sp.feed("< broken < hi >");
  EXPECT_EQ(split_all(sp), (std::vector<std::string>{"< hi >"}));
}

TEST(SocketcandSplitter, OverlongElementIsReportedOnceAndBufferStaysBounded) {
  sc::ElementSplitter sp;
  sp.feed("<");
  for (int i = 0; i < 100; ++i) sp.feed(std::string(100, 'a'));
  std::vector<std::string> errors;
  EXPECT_TRUE(split_all(sp, &errors).empty());
  EXPECT_EQ(errors.size(), 1u);
  EXPECT_LE(sp.buffered(), sc::max_element_size + 100);
  sp.feed(std::string(50, 'b') + "> < hi >");
  EXPECT_EQ(split_all(sp), (std::vector<std::string>{"< hi >"}));
}

TEST(SocketcandSplitter, ByteByByteFeedGivesTheSameElements) {
  const std::string stream = "< hi >< frame 123 23.424242 1A220344 >xx< send 601 2 40 18 ><error 004 1.0 >";
  sc::ElementSplitter whole;
  whole.feed(stream);
  const auto expected = split_all(whole);
  sc::ElementSplitter sp;
  std::vector<std::string> got;
  for (char c : stream) {
    sp.feed(std::string_view(&c, 1));
    for (auto& e : split_all(sp)) got.push_back(e);
  }
  EXPECT_EQ(got, expected);
  EXPECT_EQ(got.size(), 4u);
}

}  // namespace
