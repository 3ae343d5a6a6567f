// SPDX-License-Identifier: MIT
// Emulated CLM1.4 station against the manual's telegrams: replies byte for byte, every serial
// error path, modes, parameter validation on leaving Parameter mode, RS-485 addressing,
// persistence.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "hil/mocks/legacy/clm14_line.hpp"
#include "hil/serial/clm14/serial_error.hpp"
#include "hil/serial/clm14/telegram.hpp"

using namespace hil::mocks::legacy;
using namespace hil::serial::clm14;

namespace {
std::shared_ptr<const DeviceData> data() {
  static auto d = load_device_data();
  EXPECT_TRUE(d) << d.error();
  return *d;
}
/// Send a telegram with checksum; returns the reply bytes.
std::string ask(Clm14Station& s, char lead, std::string_view body, char station = ' ') {
  std::string wire = make_telegram(lead, station, body);
  return s.on_line(std::string_view(wire).substr(0, wire.size() - 2));
}
std::string err(int code, char station = ' ') {
  return make_telegram('X', station, make_error_body(code, data()->serial_error_text(code)));
}
}  // namespace

TEST(Clm14Emulator, EmptyProgramLineAsInTheManual) {
  Clm14Station s(0, data());
  // An empty line reads back as "NOP" + 2 spaces, like the manual's "#5N0123␣NOP␣␣$45" (§9.2)
  EXPECT_EQ(ask(s, '?', "N0000"), "# N0000 NOP  $60\r\n");
}

TEST(Clm14Emulator, ProgramWriteConfirmAndReadBack) {
  Clm14Station s(0, data());
  EXPECT_EQ(s.on_line("# N0101 AEA Q1.00.3 1 $C0"), "Y\r\n");
  EXPECT_EQ(ask(s, '?', "N0101"), "# N0101 AEA Q1.00.3 1 $C0\r\n");
  EXPECT_EQ(s.on_line("# N0100 POI 1    +123456.786 123 $C6"), "Y\r\n");
}

TEST(Clm14Emulator, SerialErrorsWithTheirTexts) {
  Clm14Station s(0, data());
  EXPECT_EQ(s.on_line("# N0101 AEA Q1.00.3 1 $C1"), err(4));  // checksum
  EXPECT_EQ(ask(s, '?', "N3000"), err(12));                   // block # too large
  EXPECT_EQ(ask(s, '?', "N30X0"), err(1));                    // not decimal
  EXPECT_EQ(ask(s, '#', "N0001 XYZ 1 "), err(13));            // invalid command
  EXPECT_EQ(ask(s, '#', "K B002 019200 0 1 8 1"), err(5));    // not in Parameter mode
  EXPECT_EQ(ask(s, '?', "X  01 "), err(9));                   // status 01 cannot be queried
  EXPECT_EQ(ask(s, '?', "X  5A "), err(8));
  EXPECT_EQ(ask(s, '#', "V100 +00000001.000000 "), err(23));  // system variable
  EXPECT_EQ(ask(s, '#', "V600 +0000000A.000000 "), err(18));
  EXPECT_EQ(ask(s, '?', "K Z000"), err(11));
  EXPECT_EQ(ask(s, '?', "K B0X1"), err(6));
  EXPECT_EQ(ask(s, '?', "K B099"), err(7));
  EXPECT_TRUE(err(12).starts_with("X 01 12 Block # too large    $")) << err(12);
}

TEST(Clm14Emulator, ParametersOnlyInParameterModeAndValidatedOnLeaving) {
  Clm14Station s(0, data());
  s.set_mode(ClmMode::parameter);
  EXPECT_EQ(ask(s, '#', "K B002 019200 0 1 8 1"), "Y\r\n");
  EXPECT_EQ(ask(s, '!', "K A101 0020.00000"), "Y\r\n");  // '!' accepted for parameter writes
  EXPECT_EQ(ask(s, '?', "K A101"), "# K A101 0020.00000$7C\r\n");
  EXPECT_EQ(ask(s, '?', "K B006"), "# K B006 $59\r\n");
  // An out-of-range value is stored but flagged when Parameter mode is left (error 02, status 60).
  EXPECT_EQ(ask(s, '#', "K A112 99999 10.0"), "Y\r\n");
  s.set_mode(ClmMode::manual);
  EXPECT_EQ(s.fault(), 0x02);
  EXPECT_NE(ask(s, '?', "X  60 0 ").find("0 A112"), std::string::npos);
  s.set_mode(ClmMode::parameter);
  EXPECT_EQ(ask(s, '#', "K A112 03000 10.0"), "Y\r\n");
  s.set_mode(ClmMode::manual);
  EXPECT_EQ(s.fault(), 0x00);
}

TEST(Clm14Emulator, DefaultParametersAreTheManualStrings) {
  Clm14Station s(0, data());
  // digest §2.5: the printed default telegrams and checksums
  EXPECT_EQ(ask(s, '?', "K B002"), "# K B002 019200 0 1 8 1$E4\r\n");
  EXPECT_EQ(ask(s, '?', "K B003"), "# K B003 0 1 00 0 000 000$A8\r\n");
  EXPECT_EQ(ask(s, '?', "K A124"), "# K A124 Q1.00.0 -100 0$BA\r\n");
  EXPECT_EQ(ask(s, '?', "K C008"), "# K C008 00.00.0 000$58\r\n");
}

TEST(Clm14Emulator, VariablesStatusCommandsAndPoll) {
  Clm14Station s(0, data());
  EXPECT_EQ(s.on_line("# V600 +00000100.000000 $93"), "Y\r\n");
  EXPECT_EQ(ask(s, '?', "V600"), make_telegram('V', ' ', "600 +00000100.000000 "));
  EXPECT_EQ(ask(s, '#', "V601 -12,5 "), "Y\r\n");
  EXPECT_EQ(ask(s, '?', "V601"), make_telegram('V', ' ', "601 -00000012.500000 "));
  EXPECT_NE(ask(s, '?', "X 53 ").find("X 53 00 "), std::string::npos);  // one space accepted too
  EXPECT_EQ(s.on_line("! START $10"), err(5));                          // only in Automatic
  s.set_mode(ClmMode::automatic);
  EXPECT_EQ(s.on_line("! START $10"), "Y\r\n");
  EXPECT_EQ(s.on_line("! STOP $58"), "Y\r\n");
  EXPECT_EQ(s.on_line("! CSETPA $DD"), err(5));  // Parameter mode only
  EXPECT_EQ(ask(s, '!', "START"), "Y\r\n");
  EXPECT_EQ(s.on_line("! START "), err(4)) << "'!' commands always need the checksum";
  EXPECT_EQ(ask(s, '!', "FOO"), err(2));
  s.set_mode(ClmMode::parameter);
  EXPECT_EQ(ask(s, '!', "CNOPNC10000999"), err(12));
  EXPECT_EQ(ask(s, '!', "CNOPNC00000999"), "Y\r\n");
  EXPECT_EQ(ask(s, '?', "P 0000"), make_telegram('P', ' ', "0000 END "));
}

TEST(Clm14Emulator, Rs485StationsSilentOnWrongStationAndBroadcast) {
  Clm14Line line(data(), 32);
  ASSERT_EQ(line.size(), 32U);
  const auto send = [&](std::string wire) {
    return line.on_bytes(std::span(reinterpret_cast<const std::uint8_t*>(wire.data()), wire.size()), {});
  };
  // Only station 10 ('A') answers.
  EXPECT_EQ(send(make_telegram('?', 'A', "N0000")), make_telegram('#', 'A', "N0000 NOP  "));
  EXPECT_EQ(send(make_telegram('?', 'W', "X  53 ")).substr(0, 6), "XW53 0");
  EXPECT_EQ(send(make_telegram('?', 'X', "N0000")), "") << "no station X: silence";
  EXPECT_EQ(send(":5\r\n"), ":500\r\n");
  // Broadcast (space) on RS-485: every station stores, none answers.
  line.set_mode(ClmMode::parameter);
  EXPECT_EQ(send(make_telegram('#', ' ', "N0007 WAI 00.500 ")), "");
  for (std::size_t i = 0; i < line.size(); ++i) EXPECT_EQ(line.station(i).program_line(7), "WAI 00.500 ");
  // Noise on the station character makes it nobody's telegram: silence, not an error.
  std::string bad = make_telegram('?', '3', "N0000");
  bad[1] = 'Z';
  EXPECT_EQ(send(bad), "");
  std::string bad_mine = make_telegram('?', '3', "N0000");
  bad_mine[4] = '1';
  EXPECT_EQ(send(bad_mine), err(4, '3'));
}

namespace {
/// The emulator host's idle loop (EndpointHost::step) on virtual time: wake at every
/// next_deadline() from `from` up to `until` and call on_idle(). Returns what was sent, and when.
/// The deadline covers the held answers and the stations' NC cycles (the CLM1.4 model runs on the
/// emulator's clock), so an answer leaves at its due time only if the line asks to be woken then.
std::vector<std::pair<hil::TimePoint, std::string>> idle_until(Clm14Line& line, hil::TimePoint from,
                                                               hil::TimePoint until) {
  std::vector<std::pair<hil::TimePoint, std::string>> sent;
  hil::TimePoint now = from;
  for (int wakeups = 0; wakeups < 100'000; ++wakeups) {
    const hil::TimePoint next = std::max(now, line.next_deadline());
    if (next > until) return sent;
    now = next;
    if (std::string out = line.on_idle(now); !out.empty()) sent.emplace_back(now, std::move(out));
    if (line.next_deadline() <= now) now += std::chrono::nanoseconds(1);  // due work done: time moves on
  }
  ADD_FAILURE() << "the line asked to be woken more than 100000 times";
  return sent;
}
using Sent = std::vector<std::pair<hil::TimePoint, std::string>>;
}  // namespace

TEST(Clm14Emulator, Rs485ResponseDelayFromB005HoldsTheAnswerInOrder) {
  using std::chrono::milliseconds;
  Clm14Line line(data(), 3);
  const hil::TimePoint t0{};
  const auto send = [&](std::string wire, hil::TimePoint at) {
    return line.on_bytes(std::span(reinterpret_cast<const std::uint8_t*>(wire.data()), wire.size()), at);
  };
  // Station 2 gets B005 DDD = 050 ms (fields H C NN E DDD RRR); station 1 keeps 000.
  line.set_mode(ClmMode::parameter);
  EXPECT_EQ(send(make_telegram('#', '2', "K B005 0 1 02 0 050 000"), t0), "");
  EXPECT_EQ(idle_until(line, t0, t0 + milliseconds(60)), (Sent{{t0 + milliseconds(50), "Y\r\n"}}))
      << "even its confirmation waits 50 ms, and the line wakes its host for it";
  line.set_mode(ClmMode::manual);
  EXPECT_EQ(line.station(1).response_delay(), milliseconds(50));
  EXPECT_EQ(line.station(0).response_delay(), milliseconds(0));

  // Between two NC cycles (they run on whole milliseconds from t0): at t1 + 50 ms only the held
  // answer's own deadline wakes the host.
  const auto t1 = t0 + milliseconds(100) + std::chrono::microseconds(250);
  const std::string late = make_telegram('#', '2', "N0000 NOP  ");
  EXPECT_EQ(send(make_telegram('?', '2', "N0000"), t1), "") << "held for 50 ms";
  // Station 1 answers at once by itself, but never overtakes the answer already on hold.
  EXPECT_EQ(send(make_telegram('?', '1', "N0000"), t1 + milliseconds(10)), "");
  EXPECT_EQ(idle_until(line, t1 + milliseconds(10), t1 + milliseconds(60)),
            (Sent{{t1 + milliseconds(50), late + make_telegram('#', '1', "N0000 NOP  ")}}))
      << "both leave when the first is due, in request order";
  // Nothing is held any more: station 1 answers at once again.
  EXPECT_EQ(send(make_telegram('?', '1', "N0000"), t1 + milliseconds(60)), make_telegram('#', '1', "N0000 NOP  "));
}

TEST(Clm14Emulator, ParityErrorInATelegramIsAFormatError) {
  Clm14Line line(data(), 0);
  const std::string first = "# N0001 ";
  (void)line.on_bytes(std::span(reinterpret_cast<const std::uint8_t*>(first.data()), first.size()), {});
  (void)line.on_line_error(hil::serial::LineError::parity, {});
  const std::string rest = "NOP  $00\r\n";
  EXPECT_EQ(line.on_bytes(std::span(reinterpret_cast<const std::uint8_t*>(rest.data()), rest.size()), {}), err(2));
}

TEST(Clm14Emulator, StateSurvivesRestart) {
  Clm14Line line(data(), 0);
  line.set_mode(ClmMode::parameter);
  EXPECT_EQ(ask(line.station(0), '#', "N2999 JMP 0000 "), "Y\r\n");
  EXPECT_EQ(ask(line.station(0), '#', "K A101 0020.00000"), "Y\r\n");
  EXPECT_EQ(ask(line.station(0), '#', "V999 +00000001.500000 "), "Y\r\n");
  const std::string saved = line.save_state();
  Clm14Line restarted(data(), 0);
  ASSERT_TRUE(restarted.load_state(saved));
  EXPECT_EQ(restarted.station(0).program_line(2999), "JMP 0000 ");
  EXPECT_EQ(restarted.station(0).parameter("A101"), "0020.00000");
  EXPECT_EQ(ask(restarted.station(0), '?', "V999"), make_telegram('V', ' ', "999 +00000001.500000 "));
  EXPECT_FALSE(restarted.load_state("{not json"));
  EXPECT_FALSE(restarted.load_state(R"({"device":"clm14","stations":[{"program":{"9999":"NOP"}}]})"));
}

// The emulator's restart keeps, besides program, variables and counters, the flying cutoff's
// length counters (status 54), the analog inputs AE1..AE4 (status 49/45, the console's
// potentiometers) and the test mode's speed step (the CTA's keys).
TEST(Clm14Emulator, LengthCountersAnalogInputsAndTestSpeedSurviveRestart) {
  using namespace std::chrono_literals;
  Clm14Station s(0, data());
  s.set_mode(ClmMode::parameter);
  EXPECT_EQ(ask(s, '#', "K A100 1 5 0 0 0"), "Y\r\n");   // axis 1 a flying cutoff
  EXPECT_EQ(ask(s, '#', "K C000 01250 0000"), "Y\r\n");  // measuring wheel: 1250 pulses per 20 IU
  EXPECT_EQ(ask(s, '#', "K C002 0020.00000"), "Y\r\n");
  s.set_mode(ClmMode::manual);
  hil::TimePoint t{};
  s.tick(t);
  ASSERT_EQ(s.fault(), 0) << s.controller().error_message();
  ASSERT_TRUE(s.set_material_velocity(40.0));
  s.tick(t += 500ms);
  ASSERT_TRUE(s.set_material_velocity(0.0));
  s.tick(t += 1s);
  const double material = s.controller().length_counter(1);
  EXPECT_GT(material, 15.0);  // 40 IU/s for about 0.5 s, ramped
  EXPECT_EQ(s.controller().length_counter(2), 0.0) << "product: Automatic only";
  s.controller().set_analog_input(1, 5000);
  s.controller().set_analog_input(3, -2500);
  s.controller().set_test_speed_step(7);
  s.tick(t += 2s);
  EXPECT_TRUE(s.take_dirty()) << "the hardware settings and the counters are persisted";
  const std::string status54 = ask(s, '?', "X 54 ");
  const std::string status49 = ask(s, '?', "X 49 ");
  EXPECT_NE(status49.find("+05000 +00000"), std::string::npos) << status49;
  const auto saved = s.to_json();

  Clm14Station restarted(0, data());
  ASSERT_TRUE(restarted.from_json(saved));
  EXPECT_EQ(restarted.controller().length_counter(1), material);
  EXPECT_EQ(restarted.controller().analog_input(1), 5000);
  EXPECT_EQ(restarted.controller().analog_input(3), -2500);
  EXPECT_EQ(restarted.controller().test_speed_step(), 7);
  restarted.tick(t);
  EXPECT_EQ(ask(restarted, '?', "X 54 "), status54);
  EXPECT_EQ(ask(restarted, '?', "X 49 "), status49);
  EXPECT_EQ(ask(restarted, '?', "X 45 "), make_telegram('X', ' ', "45 -02500 +00000 "));
  EXPECT_EQ(hil::controllers::clm14::to_double(restarted.controller().variable(9)), -0.25)
      << "V009 from the restored AE3";

  auto bad = saved;
  bad["hardware"]["analog_mv"][1] = 12000;
  EXPECT_FALSE(Clm14Station(0, data()).from_json(bad));
  bad = saved;
  bad["hardware"]["analog_mv"][0] = 1.5;
  EXPECT_FALSE(Clm14Station(0, data()).from_json(bad)) << "whole mV only";
  bad = saved;
  bad["hardware"]["test_speed_step"] = 32;
  EXPECT_FALSE(Clm14Station(0, data()).from_json(bad));
  bad = saved;
  bad["controller"]["length_counters"] = "x";
  EXPECT_FALSE(Clm14Station(0, data()).from_json(bad));
}
