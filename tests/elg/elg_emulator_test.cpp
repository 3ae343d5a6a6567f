// SPDX-License-Identifier: MIT
// The running ELG behind its serial universal interface (mocks::legacy::ElgRunEndpoint, the model
// of `hilbridge emulate elg-tape --program`): the annex program runs on virtual time on simulated
// axes, and the V.24 answers come from the running gearbox: Data Start while coupled is alarm 2214
// and punches nothing, uncoupled it punches the ELG's MD store, a tape sent while coupled is not
// read in, and the PC data channel reads the model's actual values and alarms.
#include <gtest/gtest.h>

#include "hil/controllers/elg/elg_controller.hpp"
#include "hil/core/text_file.hpp"
#include "hil/mocks/legacy/elg_run_endpoint.hpp"
#include "hil/serial/profile_checks.hpp"
#include "hil/serial/tape/elg_tape.hpp"
#include "hil/serial/tape/tape_reader.hpp"

namespace elg = hil::controllers::elg;
namespace tape = hil::serial::tape;
using std::chrono::milliseconds;

namespace {

struct Emulator {
  Emulator() {
    auto loaded = hil::controllers::load_parameter_file("sinumerik-elg", "examples/controllers/elg-hobbing.tape.txt");
    EXPECT_TRUE(loaded) << loaded.error().describe();
    auto setup = elg::elg_setup_from_tape(*loaded, elg::HobbingConfig{}, milliseconds(2));
    EXPECT_TRUE(setup) << setup.error().describe();
    auto text = hil::read_text_file("examples/controllers/elg-annex.nc");
    auto program = elg::parse_nc_program(text.value_or(""));
    EXPECT_TRUE(program);
    auto check = hil::serial::load_elg_check();
    EXPECT_TRUE(check) << check.error();
    ep = std::make_unique<hil::mocks::legacy::ElgRunEndpoint>(*check, std::move(*setup), std::move(*program),
                                                              milliseconds(2));
    auto sections = tape::parse_elg_text(*hil::read_text_file("examples/controllers/elg-hobbing.tape.txt"));
    EXPECT_TRUE(sections);
    for (const auto& s : *sections)
      for (const auto& e : s.entries) ep->tape().set_datum(s.kind, e.number, e.value);
  }
  /// Advances virtual time in 10 ms steps (the host's idle calls) until `done` or `limit`.
  template <class F>
  bool run_until(F done, std::chrono::seconds limit = std::chrono::seconds(400)) {
    const auto end = now + limit;
    while (now < end) {
      now += milliseconds(10);
      out += ep->on_idle(now);
      if (done()) return true;
    }
    return false;
  }
  std::string send(const std::vector<std::uint8_t>& b) { return ep->on_bytes(b, now); }
  bool coupled() const { return ep->machine().gearbox().status().coupled; }

  std::unique_ptr<hil::mocks::legacy::ElgRunEndpoint> ep;
  hil::TimePoint now{};
  std::string out;
};

}  // namespace

TEST(ElgEmulator, DataStartWhileCoupledIsAlarm2214AndPunchesNothing) {
  Emulator em;
  ASSERT_TRUE(em.run_until([&] { return em.coupled(); }));
  em.out.clear();
  EXPECT_EQ(em.send({0x12}), "");  // Data Start: sampled by the next ELG cycle
  ASSERT_TRUE(em.run_until([&] { return !em.ep->alarms().empty(); }, std::chrono::seconds(1)));
  EXPECT_TRUE(em.ep->machine().gearbox().has_alarm(elg::Alarm::v24_not_permitted));
  EXPECT_EQ(em.ep->tape().alarm(), 2214);
  EXPECT_TRUE(em.out.empty());
  // A tape sent while coupled is not read in either.
  tape::ElgSection s{tape::ElgSectionKind::machine_data, {{3961, "90000"}}};
  auto t = tape::make_tape(tape::make_elg_blocks(s), tape::TapeWriterOptions{});
  ASSERT_TRUE(t);
  em.send(std::vector<std::uint8_t>(t->begin(), t->end()));
  EXPECT_EQ(em.ep->tape().machine_data().at(3961), "180000");
  // The PC data channel answers from the model: alarm slot 1 holds 2214.
  const auto reply = em.ep->pc_request({false, 27, 1, 0, {}});
  ASSERT_TRUE(reply.performed);
  EXPECT_EQ(elg::to_string(reply.value), "2214");
}

TEST(ElgEmulator, DataStartUncoupledPunchesTheStoreAndTheProgramRunsToTheEnd) {
  Emulator em;
  ASSERT_TRUE(em.run_until([&] { return em.coupled(); }));
  ASSERT_TRUE(em.run_until([&] { return !em.coupled(); }));
  em.out.clear();
  em.send({0x12});
  ASSERT_TRUE(em.run_until([&] { return !em.out.empty(); }, std::chrono::seconds(1)));
  auto r = tape::read_tape(std::span(reinterpret_cast<const std::uint8_t*>(em.out.data()), em.out.size()),
                           tape::TapeReaderOptions{});
  ASSERT_FALSE(r.error);
  auto sections = tape::parse_elg_blocks(r.blocks);
  ASSERT_TRUE(sections);
  ASSERT_EQ(sections->size(), 1u);
  EXPECT_EQ((*sections)[0].kind, tape::ElgSectionKind::machine_data);
  bool found = false;
  for (const auto& e : (*sections)[0].entries) found = found || (e.number == 3961 && e.value == "180000");
  EXPECT_TRUE(found);
  EXPECT_TRUE(em.ep->alarms().empty());
  // A datum the PC writes through the data channel is punched with the next MD tape.
  ASSERT_TRUE(em.ep->pc_request({true, 10, 1, 28, *elg::parse_pc_value("12000")}).performed);  // MD 2801
  EXPECT_EQ(em.ep->tape().machine_data().at(2801), "12000");
  // The cycle goes on to the end: ten gaps, C back at 360 deg, no alarm.
  ASSERT_TRUE(em.run_until([&] { return em.ep->machine().nc().state() == elg::NcState::ended; }));
  em.run_until([] { return false; }, std::chrono::seconds(2));
  EXPECT_EQ(em.ep->machine().couplings(), 10);
  EXPECT_TRUE(em.ep->alarms().empty());
  const auto c = em.ep->pc_request({false, 12, 2, 0, {}});  // actual value of C (axis 2)
  ASSERT_TRUE(c.performed);
  EXPECT_EQ(elg::to_string(c.value), "360.000");
  EXPECT_NE(em.ep->status().find("coupled 0"), std::string::npos) << em.ep->status();
}
