// SPDX-License-Identifier: MIT
// Device files and profiles: the shipped examples validate against the profiles; every CLM1.4
// parameter round-trips (profile default -> check -> emulator -> client); the ELG tape
// endpoint accepts, rejects atomically, punches on Data Start and raises its alarms.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "hil/mocks/legacy/clm14_line.hpp"
#include "hil/mocks/legacy/elg_tape_endpoint.hpp"
#include "hil/serial/clm14/client.hpp"
#include "hil/serial/clm14/files.hpp"
#include "hil/serial/clm14/item_devices.hpp"
#include "hil/serial/item_transfer.hpp"
#include "hil/serial/memory_line.hpp"
#include "hil/serial/profile_checks.hpp"
#include "hil/serial/s5/db_listing.hpp"
#include "hil/serial/serial_stream.hpp"
#include "hil/serial/tape/elg_tape.hpp"

using namespace hil::serial;
using namespace std::chrono_literals;

namespace {
std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
std::shared_ptr<const clm14::DeviceData> data() {
  static auto d = clm14::load_device_data();
  return *d;
}
}  // namespace

TEST(Examples, ClmProgramAndParametersValidate) {
  auto prog = clm14::parse_device_file(read("examples/serial/clm14-feed.prg"), clm14::FileKind::program, *data(), 2,
                                       "feed.prg");
  ASSERT_TRUE(prog) << prog.error().front();
  EXPECT_EQ(prog->items.size(), 6U);
  auto par = clm14::parse_device_file(read("examples/serial/clm14-parameters.par"), clm14::FileKind::parameters,
                                      *data(), 2, "p");
  ASSERT_TRUE(par) << par.error().front();
  EXPECT_EQ(par->items.size(), data()->parameter_numbers(2).size());
}

TEST(Examples, InvalidParameterFileListsEveryProblemWithItsLine) {
  auto par = clm14::parse_device_file("B002 019200 0 1 8 1\nA101 abc\nX999 1\nB002 1\nA112 99999999 10.0\n",
                                      clm14::FileKind::parameters, *data(), 2, "bad.par");
  ASSERT_FALSE(par);
  ASSERT_EQ(par.error().size(), 4U);
  EXPECT_NE(par.error()[0].find("bad.par:2: A101"), std::string::npos) << par.error()[0];
  EXPECT_NE(par.error()[1].find("bad.par:3: 'X999'"), std::string::npos) << par.error()[1];
  EXPECT_NE(par.error()[2].find("appears twice"), std::string::npos);
}

TEST(Examples, ElgTapeAndIp247ImageValidate) {
  auto elg = tape::parse_elg_text(read("examples/serial/elg-md-sd.tape.txt"));
  ASSERT_TRUE(elg) << elg.error().message;
  auto check = load_elg_check();
  ASSERT_TRUE(check) << check.error();
  for (const auto& s : *elg)
    for (const auto& e : s.entries) EXPECT_FALSE((*check)(s.kind, e.number, e.value)) << e.number;
  EXPECT_TRUE((*check)(tape::ElgSectionKind::machine_data, 396, "180000")) << "MD 396* is per axis: MD3960..3963";
  EXPECT_TRUE((*check)(tape::ElgSectionKind::machine_data, 3962, "2500000"))
      << "above the 2 000 000 maximum (alarm 2200)";
  auto dbs = s5::parse_db_listing(read("examples/serial/ip247-md-db1.s5db"), "md");
  ASSERT_TRUE(dbs);
  auto ip = load_ip247_check();
  ASSERT_TRUE(ip) << ip.error();
  EXPECT_TRUE((*ip)((*dbs)[0].words).empty());
  auto bad = (*dbs)[0].words;
  bad[6] = 0;  // fmax 0 Hz
  EXPECT_FALSE((*ip)(bad).empty());
}

TEST(Examples, Wf725DefaultImageValidatesAndAChangedMdIsChecked) {
  auto dbs = s5::parse_db_listing(read("examples/serial/wf725-md-defaults.s5db"), "wf");
  ASSERT_TRUE(dbs);
  auto check = load_wf725_check();
  ASSERT_TRUE(check) << check.error();
  const auto problems = (*check)((*dbs)[0].words);
  EXPECT_TRUE(problems.empty()) << problems.front();
  auto defaults = load_wf725_default_image();
  ASSERT_TRUE(defaults);
  EXPECT_EQ(*defaults, (*dbs)[0].words);
  auto bad = (*dbs)[0].words;
  bad[2 * 49 - 1] = 0;  // MD49 basic resolution 0: not a defined choice
  EXPECT_FALSE((*check)(bad).empty());
}

TEST(ClmProfileRoundTrip, EveryParameterOfFourAxesThroughClientAndEmulator) {
  hil::VirtualClock clock;
  auto mem = make_memory_line(&clock);
  hil::mocks::legacy::Clm14Line line(data(), 0, 4);
  line.set_mode(hil::mocks::legacy::ClmMode::parameter);
  SerialStream client_stream(std::move(mem.a), LineFormat{}, Discipline{}, clock);
  auto* dev = mem.b.get();
  *mem.a_to_b = [&](std::vector<std::uint8_t>& b) {
    const std::string out = line.on_bytes(b, clock.now());
    b.clear();
    (void)dev->write(std::span(reinterpret_cast<const std::uint8_t*>(out.data()), out.size()), 1s);
  };
  clm14::Client c(client_stream, clock, clm14::ClientOptions{});
  const auto numbers = data()->parameter_numbers(4);
  ASSERT_GT(numbers.size(), 150U);
  for (const auto& n : numbers) {
    const std::string def = data()->parameter_default(n);
    auto canon = data()->check_parameter(n, def);
    ASSERT_TRUE(canon) << n << " '" << def << "': " << canon.error().message;
    EXPECT_EQ(*canon, def) << n;
    ASSERT_TRUE(c.write_parameter(n, def)) << n;
    EXPECT_EQ(c.read_parameter(n).value(), def) << n;
  }
  line.set_mode(hil::mocks::legacy::ClmMode::manual);
  EXPECT_EQ(line.station(0).fault(), 0) << "the default set must validate when leaving Parameter mode";
}

namespace {
std::vector<std::uint8_t> tape_of(const std::string& text) {
  auto s = tape::parse_elg_text(text);
  std::vector<std::string> blocks;
  for (const auto& sec : *s) {
    auto b = tape::make_elg_blocks(sec);
    blocks.insert(blocks.end(), b.begin(), b.end());
  }
  return *tape::make_tape(blocks, tape::TapeWriterOptions{});
}
}  // namespace

TEST(ElgEndpoint, AcceptsTapesPunchesOnDataStartAndRejectsAtomically) {
  auto check = load_elg_check();
  ASSERT_TRUE(check);
  hil::mocks::legacy::ElgTapeEndpoint ep(*check);
  hil::TimePoint now{};
  EXPECT_EQ(ep.on_bytes(tape_of("%TEA1\nN3962=180000\nN3960=2000\nM02\n"), now), "");
  EXPECT_EQ(ep.alarm(), 0) << ep.alarm_text();
  EXPECT_EQ(ep.machine_data().at(3962), "180000");
  // One bad datum: the whole tape is refused, nothing changes.
  EXPECT_EQ(ep.on_bytes(tape_of("%TEA1\nN3962=170000\nN3961=2500000\nM02\n"), now), "");
  EXPECT_EQ(ep.alarm(), 32);
  EXPECT_EQ(ep.machine_data().at(3962), "180000");
  ep.clear_alarm();
  // Data Start (DC2) punches the MD tape; the output reads back as the same data.
  const std::uint8_t dc2 = 0x12;
  const std::string out = ep.on_bytes(std::span(&dc2, 1), now);
  auto r = tape::read_tape(std::span(reinterpret_cast<const std::uint8_t*>(out.data()), out.size()),
                           tape::TapeReaderOptions{});
  ASSERT_FALSE(r.error);
  auto s = tape::parse_elg_blocks(r.blocks);
  ASSERT_TRUE(s);
  EXPECT_EQ((*s)[0].kind, tape::ElgSectionKind::machine_data);
  EXPECT_EQ((*s)[0].entries.size(), 2U);
  // Character parity error on the tape: alarm 23; a stalled tape: alarm 22 after 60 s.
  auto bad = tape_of("%TEA1\nN3962=1\nM02\n");
  bad[25] ^= 0x80;
  (void)ep.on_bytes(bad, now);
  EXPECT_EQ(ep.alarm(), 23);
  ep.clear_alarm();
  auto half = tape_of("%TEA1\nN3962=1\nM02\n");
  half.resize(30);
  (void)ep.on_bytes(half, now);
  EXPECT_EQ(ep.next_deadline(), now + 60s);
  (void)ep.on_idle(now + 61s);
  EXPECT_EQ(ep.alarm(), 22);
  EXPECT_EQ(ep.on_line_error(LineError::overrun, now), "");
  EXPECT_EQ(ep.alarm(), 17);
  // Persistence.
  hil::mocks::legacy::ElgTapeEndpoint restored(*check);
  ASSERT_TRUE(restored.load_state(ep.save_state()));
  EXPECT_EQ(restored.machine_data().at(3962), "180000");
}
