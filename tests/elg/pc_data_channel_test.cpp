// SPDX-License-Identifier: MIT
// The PC <-> ELG data channel (manual 12.5; digest §8.4): the frame codec and the requests on a
// running gearbox, with alarms 3016 and 3018 raised by the manual's conditions (wrong code, value
// too high, impermissible dimension; unknown address) and the transfer still acknowledged.
#include <gtest/gtest.h>

#include "hil/controllers/elg/pc_data_image.hpp"

namespace elg = hil::controllers::elg;
using elg::Alarm;
using elg::PcCoding;
using elg::PcRequest;
using elg::PcValue;

namespace {

PcRequest read(PcCoding coding, int address) {
  return {false,
          static_cast<std::uint8_t>(coding),
          static_cast<std::uint8_t>(address % 100),
          static_cast<std::uint8_t>(address / 100),
          {}};
}
PcRequest write(PcCoding coding, int address, std::string_view value) {
  auto r = read(coding, address);
  r.write = true;
  r.value = *elg::parse_pc_value(value);
  return r;
}

struct Channel {
  Channel() {
    md = {{3960, "180000"}, {3961, "180000"}, {2801, "10000"}, {5020, "00010010"}, {5021, "00000011"}};
    sd = {{5016, "00000000"}};
  }
  elg::Gearbox box{elg::GearboxConfig{}};
  std::map<int, std::string> md, sd;
  elg::PcDataImage image{box, md, sd,
                         [](elg::DatumKind, int number, const std::string& v) -> std::optional<std::string> {
                           if (number == 2801 && v.size() > 5) return "MD 280*: 0..24000";
                           return std::nullopt;
                         }};
  elg::Signals s;
  elg::AxisFeedback axes;
  void step() {
    box.step(s, axes);
    image.update(axes);
  }
};

}  // namespace

TEST(ElgPcDataChannel, FrameCarriesCodingAddressAndBcdValue) {
  // The manual's example: MD 2043 is code 10, relative address 1. = 43, 2. = 20.
  const auto r = write(PcCoding::word, 2043, "-123456789");
  EXPECT_EQ(r.rel1, 43);
  EXPECT_EQ(r.rel2, 20);
  const auto f = elg::make_pc_request(r);
  EXPECT_EQ(f, (elg::PcFrame{0x8A, 0x43, 0x20, 0x80, 0x01, 0x23, 0x45, 0x67, 0x89}));
  const auto back = elg::parse_pc_request(f);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->address(), 2043);
  EXPECT_TRUE(back->write);
  EXPECT_EQ(back->value, r.value);
  EXPECT_EQ(elg::to_string(back->value), "-123456789");
  // R61 = 8.18511: five decimal places (the dimension identifier).
  const auto ud = elg::parse_pc_request(elg::make_pc_request(write(PcCoding::r_parameter, 61, "8.18511")));
  ASSERT_TRUE(ud);
  EXPECT_EQ(ud->value.decimals, 5);
  EXPECT_EQ(elg::to_string(ud->value), "8.18511");
}

TEST(ElgPcDataChannel, MalformedFramesAre3016) {
  auto f = elg::make_pc_request(read(PcCoding::word, 3961));
  auto bad_bcd = f;
  bad_bcd[1] = 0x4A;  // not a decimal digit
  EXPECT_EQ(elg::parse_pc_request(bad_bcd).error(), Alarm::pc_data_channel_error);
  auto tenth_digit = f;
  tenth_digit[4] = 0x10;  // a value of ten digits: too high
  EXPECT_EQ(elg::parse_pc_request(tenth_digit).error(), Alarm::pc_data_channel_error);
  auto dimension = f;
  dimension[3] = 0x0C;  // twelve decimal places: impermissible dimension
  EXPECT_EQ(elg::parse_pc_request(dimension).error(), Alarm::pc_data_channel_error);
  EXPECT_EQ(elg::parse_pc_request(std::span(f).first(8)).error(), Alarm::pc_data_channel_error);
}

TEST(ElgPcDataChannel, ReadsAndWritesMachineAndSettingData) {
  Channel ch;
  auto r = ch.image.request(read(PcCoding::word, 3961));
  EXPECT_TRUE(r.performed);
  EXPECT_EQ(elg::to_string(r.value), "180000");
  r = ch.image.request(read(PcCoding::md_bits, 5020));
  EXPECT_TRUE(r.performed);
  EXPECT_EQ(elg::to_string(r.value), "10010");  // 00010010: B = axis 1, C = axis 2
  r = ch.image.request(write(PcCoding::sd_bits, 5016, "00100000"));
  EXPECT_TRUE(r.performed);
  EXPECT_EQ(ch.sd[5016], "00100000");
  r = ch.image.request(write(PcCoding::word, 2801, "12000"));
  EXPECT_TRUE(r.performed);
  EXPECT_EQ(ch.md[2801], "12000");
  EXPECT_TRUE(ch.box.alarms().empty());
}

TEST(ElgPcDataChannel, UnknownAddressIs3018AndTheTransferIsAcknowledged) {
  Channel ch;
  for (const auto& req : {read(PcCoding::word, 150), read(PcCoding::md_bits, 5005), read(PcCoding::word, 5020),
                          read(PcCoding::actual_value, 4), read(PcCoding::word, 8001)}) {
    const auto r = ch.image.request(req);
    EXPECT_TRUE(r.acknowledged);
    EXPECT_FALSE(r.performed);
    EXPECT_EQ(r.alarm, Alarm::pc_datum_not_present) << req.address();
  }
  EXPECT_TRUE(ch.box.has_alarm(Alarm::pc_datum_not_present));
  EXPECT_TRUE(ch.box.status().alarm);
  // A message only: RESET with the coupling off clears it.
  ch.s.reset = true;
  ch.step();
  EXPECT_FALSE(ch.box.has_alarm(Alarm::pc_datum_not_present));
}

TEST(ElgPcDataChannel, WrongCodeValueTooHighOrDimensionIs3016AndNothingChanges) {
  Channel ch;
  const std::vector<PcRequest> bad{
      {false, 5, 0, 0, {}},                          // a coding the table does not list
      write(PcCoding::actual_value, 2, "1"),         // actual values are read only
      write(PcCoding::word, 8000, "1"),              // service data are read only
      write(PcCoding::word, 2801, "123456"),         // value too high for MD 280*
      write(PcCoding::word, 2801, "100.5"),          // an MD word has no decimal point
      write(PcCoding::md_bits, 5020, "00000012"),    // a bit datum takes digits 0/1 only
      write(PcCoding::r_parameter, 21, "1000"),      // Z2 above 999
      write(PcCoding::r_parameter, 61, "8.185111"),  // six decimals: impermissible dimension
      write(PcCoding::r_parameter, 7, "123456789"),  // nine digits: above +-99999.999
  };
  for (const auto& req : bad) {
    const auto r = ch.image.request(req);
    EXPECT_TRUE(r.acknowledged);
    EXPECT_FALSE(r.performed);
    EXPECT_EQ(r.alarm, Alarm::pc_data_channel_error) << int(req.coding) << " " << req.address();
  }
  EXPECT_EQ(ch.md[2801], "10000");
  EXPECT_EQ(ch.md[5020], "00010010");
  EXPECT_TRUE(ch.box.has_alarm(Alarm::pc_data_channel_error));
}

TEST(ElgPcDataChannel, InputParametersReachTheGearboxAndMdAreLockedWhileCoupled) {
  Channel ch;
  ch.step();
  for (auto [r, v] : {std::pair{20, "1"}, {21, "40"}, {61, "8.18511"}, {60, "-114.59156"}})
    ASSERT_TRUE(ch.image.request(write(PcCoding::r_parameter, r, v)).performed) << r;
  EXPECT_EQ(ch.box.input().z0, 1);
  EXPECT_EQ(ch.box.input().z2, 40);
  EXPECT_EQ(ch.box.input().ud_z.e5, 818511);
  EXPECT_EQ(ch.box.input().ud_y.e5, -11459156);
  EXPECT_EQ(elg::to_string(ch.image.request(read(PcCoding::r_parameter, 60)).value), "-114.59156");
  ch.s.compute = true;
  ch.step();
  ch.s.compute = false;
  ch.s.gearing_on = true;
  ch.step();
  ASSERT_TRUE(ch.box.status().coupled);
  // "$": no MD or SD writes while coupled; the transfer is refused (3016) but acknowledged.
  const auto r = ch.image.request(write(PcCoding::word, 2801, "9000"));
  EXPECT_TRUE(r.acknowledged);
  EXPECT_FALSE(r.performed);
  EXPECT_EQ(r.alarm, Alarm::pc_data_channel_error);
  EXPECT_EQ(ch.md[2801], "10000");
  // R40 may change while coupled; one below MD 169 (20) is kept as R40 but not as the limit.
  EXPECT_TRUE(ch.image.request(write(PcCoding::r_parameter, 40, "500")).performed);
  EXPECT_EQ(ch.box.status().fe_limit, 500);
  EXPECT_TRUE(ch.image.request(write(PcCoding::r_parameter, 40, "10")).performed);
  ch.step();
  EXPECT_EQ(ch.box.status().fe_limit, 500);
  // Z2 written while coupled waits for Gearing OFF.
  EXPECT_TRUE(ch.image.request(write(PcCoding::r_parameter, 21, "20")).performed);
  ch.step();
  EXPECT_EQ(ch.box.input().z2, 40);
  ch.s.gearing_on = false;
  ch.s.gearing_off = true;
  ch.step();
  EXPECT_EQ(ch.box.input().z2, 20);
}

TEST(ElgPcDataChannel, ActualValuesAlarmsAndServiceData) {
  Channel ch;
  ch.axes.c = 72001;  // 36.0005 deg at MS 0.0005 deg: three decimals
  ch.axes.b = -720000;
  ch.axes.z = 100000;  // 50 mm at 0.5 um
  ch.axes.c_following_error = -17;
  ch.step();
  EXPECT_EQ(elg::to_string(ch.image.request(read(PcCoding::actual_value, 2)).value), "36.001");
  EXPECT_EQ(elg::to_string(ch.image.request(read(PcCoding::actual_value, 1)).value), "-360.000");
  EXPECT_EQ(elg::to_string(ch.image.request(read(PcCoding::actual_value, 3)).value), "50.000");
  EXPECT_EQ(elg::to_string(ch.image.request(read(PcCoding::word, 8000)).value), "-17");
  // Alarm slots: 2207 first (Gearing ON without constants), then an empty slot reads 0.
  ch.s.gearing_on = true;
  ch.step();
  EXPECT_EQ(elg::to_string(ch.image.request(read(PcCoding::alarms, 1)).value), "2207");
  EXPECT_EQ(elg::to_string(ch.image.request(read(PcCoding::alarms, 2)).value), "0");
}
