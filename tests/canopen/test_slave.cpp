// SPDX-License-Identifier: MIT
// A CiA 301 slave built from the shipped EDS: NMT state machine and boot-up, heartbeat, node
// guarding, PDO mapping with the CiA 301 dynamic remapping sequence over SDO (and its abort
// codes), transmission types (every n-th SYNC, event-driven with inhibit time), RPDO length
// errors as EMCY. Byte-exact.
#include <gtest/gtest.h>

#include "frames.hpp"
#include "hil/canopen/eds.hpp"
#include "hil/canopen/slave.hpp"

using namespace hil::canopen;
using hil::canopen::test::f;
using hil::canopen::test::Recorder;
using namespace std::chrono_literals;
using Strings = std::vector<std::string>;

namespace {
struct SlaveFixture : ::testing::Test {
  Recorder rec;
  std::unique_ptr<Slave> slave;
  hil::TimePoint t{};
  void SetUp() override {
    auto d = load_eds(HIL_CANOPEN_PROFILE_DIR "/hil_cia402_drive.eds", 4);
    ASSERT_TRUE(d) << d.error().describe();
    slave = std::make_unique<Slave>(std::move(d->od), 4, rec.sink());
    slave->start(t);
  }
  Strings send(std::initializer_list<const char*> frames) {
    for (const char* s : frames) slave->on_frame(f(s), t += 100us);
    return rec.take();
  }
  Strings step(hil::Duration d) {
    for (auto end = t + d; t < end;) slave->step(t += 1ms);
    return rec.take();
  }
};
}  // namespace

TEST_F(SlaveFixture, BootUpAndNmtStates) {
  EXPECT_EQ(rec.take(), Strings{"704#00"});
  EXPECT_EQ(slave->state(), NmtState::preoperational);
  send({"000#0104"});
  EXPECT_EQ(slave->state(), NmtState::operational);
  send({"000#0205"});
  EXPECT_EQ(slave->state(), NmtState::operational) << "addressed to node 5";
  send({"000#0200"});
  EXPECT_EQ(slave->state(), NmtState::stopped);
  EXPECT_TRUE(send({"604#4000100000000000"}).empty()) << "no SDO in Stopped";
  send({"000#8004"});
  EXPECT_EQ(slave->state(), NmtState::preoperational);
  EXPECT_EQ(send({"604#4000100000000000"}), Strings{"584#4300100092010200"});
}

TEST_F(SlaveFixture, HeartbeatConfiguredOverSdoAndGuarding) {
  rec.take();
  EXPECT_EQ(send({"604#2B17100064000000"}), Strings{"584#6017100000000000"});
  EXPECT_EQ(step(250ms), (Strings{"704#7F", "704#7F"}));
  slave->set_heartbeat_muted(true);
  EXPECT_TRUE(step(300ms).empty());
  slave->set_heartbeat_muted(false);
  EXPECT_EQ(send({"704#R1", "704#R1"}), (Strings{"704#7F", "704#FF"})) << "guarding toggles bit 7";
}

TEST_F(SlaveFixture, ResetCommunicationRestoresDefaultsAndBootsAgain) {
  rec.take();
  send({"604#2B17100064000000", "604#2300180184010080"});
  EXPECT_EQ(slave->od().get_int(0x1800, 1), 0x80000184);
  EXPECT_EQ(send({"000#8204"}), Strings{"704#00"});
  EXPECT_EQ(slave->od().get_int(0x1800, 1), 0x184);
  EXPECT_EQ(slave->od().get_int(0x1017, 0), 0);
}

TEST_F(SlaveFixture, Cia301RemapSequenceAndItsAbortCodes) {
  rec.take();
  struct Row {
    const char* req;
    const char* rsp;
    const char* why;
  };
  const Row rows[] = {
      {"604#23001A0120006460", "584#80001A0100000106", "mapping while the PDO is valid: 0x06010000"},
      {"604#2300180184010080", "584#6000180100000000", "1: disable TPDO1 (bit 31)"},
      {"604#23001A0120006460", "584#80001A0100000106", "entries while sub 0 != 0: 0x06010000"},
      {"604#2F001A0000000000", "584#60001A0000000000", "2: sub 0 = 0"},
      {"604#23001A0120006560", "584#80001A0141000406", "0x6065 is not mappable: 0x06040041"},
      {"604#23001A012000FF5F", "584#80001A0100000206", "0x5FFF does not exist: 0x06020000"},
      {"604#23001A0110004160", "584#60001A0100000000", "3: statusword"},
      {"604#23001A0220006460", "584#60001A0200000000", "3: position actual"},
      {"604#23001A0320006C60", "584#60001A0300000000", "3: velocity actual"},
      {"604#2F001A0003000000", "584#80001A0042000406", "16+32+32 bits > 64: 0x06040042"},
      {"604#2F001A0009000000", "584#80001A0031000906", "more than 8 entries: 0x06090031"},
      {"604#2F001A0002000000", "584#60001A0000000000", "4: sub 0 = 2"},
      {"604#2F001802F1000000", "584#8000180230000906", "transmission type 241 is reserved: 0x06090030"},
      {"604#2F00180203000000", "584#6000180200000000", "every 3rd SYNC"},
      {"604#2300180184010000", "584#6000180100000000", "5: enable TPDO1"},
      {"604#2300180185010000", "584#8000180130000906", "COB-ID change while valid: 0x06090030"},
      {"604#2300180184010000", "584#6000180100000000", "same COB-ID again is fine"},
  };
  for (const auto& r : rows) EXPECT_EQ(send({r.req}), Strings{r.rsp}) << r.why;
}

TEST_F(SlaveFixture, SynchronousTpdoEveryNthSync) {
  send({"604#2300180184010080", "604#2F001A0000000000", "604#23001A0110004160", "604#23001A0220006460",
        "604#2F001A0002000000", "604#2F00180202000000", "604#2300180184010000", "000#0100"});
  rec.take();
  slave->od().set_int(0x6041, 0, 0x0637);
  slave->od().set_int(0x6064, 0, -2);
  EXPECT_TRUE(send({"080#"}).empty());
  EXPECT_EQ(send({"080#"}), Strings{"184#3706FEFFFFFF"});
  EXPECT_TRUE(send({"080#"}).empty());
  EXPECT_EQ(send({"080#"}), Strings{"184#3706FEFFFFFF"});
  send({"000#8000"});
  EXPECT_TRUE(send({"080#", "080#"}).empty()) << "no PDOs in pre-operational";
}

TEST_F(SlaveFixture, EventDrivenTpdoHonoursInhibitTime) {
  // TPDO2 (statusword + position) event-driven with 10 ms inhibit time (100 x 100 µs).
  send({"604#2301180184020080", "604#2B01180364000000", "604#2301180184020000", "000#0100"});
  rec.take();
  EXPECT_EQ(step(1ms), (Strings{"184#000000", "284#000000000000"})) << "first transmission after start";
  slave->od().set_int(0x6064, 0, 1);
  EXPECT_TRUE(step(9ms).empty()) << "a change inside the inhibit time waits";
  EXPECT_EQ(step(1ms), Strings{"284#000001000000"}) << "change of a mapped value, 10 ms after the last";
  EXPECT_TRUE(step(20ms).empty()) << "no change, no event timer: nothing";
  slave->od().set_int(0x6064, 0, 2);
  EXPECT_EQ(step(1ms), Strings{"284#000002000000"});
}

TEST_F(SlaveFixture, TpdosGoOutAgainEveryTimeTheNodeEntersOperational) {
  // Event-driven TPDOs (the EDS defaults) are sent on every entry to Operational, changed or not,
  // as CANopenNode does; python-canopen's BaseNode402 waits for them after each NMT start.
  send({"000#0100"});
  rec.take();
  EXPECT_EQ(step(1ms), (Strings{"184#000000", "284#000000000000"})) << "first start";
  EXPECT_TRUE(step(5ms).empty());
  send({"000#0200"});
  EXPECT_TRUE(step(5ms).empty()) << "stopped: no PDOs";
  send({"000#0100"});
  EXPECT_EQ(step(1ms), (Strings{"184#000000", "284#000000000000"})) << "second start, nothing changed";
  send({"000#8000", "000#0100"});
  EXPECT_EQ(step(1ms), (Strings{"184#000000", "284#000000000000"})) << "pre-operational, then start";
  // SYNC TPDOs count from the first SYNC after the new start.
  send({"604#2300180184010080", "604#2F00180202000000", "604#2300180184010000", "000#0200", "000#0100"});
  rec.take();
  EXPECT_TRUE(send({"080#"}).empty());
  EXPECT_EQ(send({"080#"}), Strings{"184#000000"});
}

TEST_F(SlaveFixture, RpdoWritesMappedObjectsAndLengthErrorsRaiseEmcy) {
  send({"000#0100"});
  rec.take();
  send({"204#0F0008"});
  EXPECT_EQ(slave->od().get_int(0x6040, 0), 0x000F);
  EXPECT_EQ(slave->od().get_int(0x6060, 0), 8);
  EXPECT_EQ(send({"304#0F00"}), Strings{"084#1082100000000000"}) << "RPDO2 too short: EMCY 0x8210";
  EXPECT_EQ(slave->od().get_int(0x1001, 0), 0x10);
  EXPECT_EQ(slave->od().get_int(0x1003, 1), 0x8210) << "pre-defined error field";
  // RPDO2 synchronous: applied at the next SYNC only.
  send({"000#8000", "604#2301140104030080", "604#2F01140201000000", "604#2301140104030000", "000#0100"});
  rec.take();
  send({"304#1F00E8030000"});
  EXPECT_EQ(slave->od().get_int(0x607A, 0), 0);
  send({"080#"});
  EXPECT_EQ(slave->od().get_int(0x607A, 0), 1000);
  EXPECT_EQ(slave->od().get_int(0x6040, 0), 0x001F);
}

TEST_F(SlaveFixture, HeartbeatConsumerOfTheMasterRaisesEmcy8130) {
  rec.take();
  EXPECT_EQ(send({"604#2316100164007F00"}), Strings{"584#6016100100000000"}) << "0x1016:1 = node 127, 100 ms";
  EXPECT_TRUE(step(500ms).empty()) << "no heartbeat seen yet: no monitoring";
  send({"77F#05"});
  EXPECT_TRUE(step(100ms).empty());
  EXPECT_EQ(step(2ms), Strings{"084#3081100000000000"}) << "EMCY 0x8130, error register: communication";
  EXPECT_TRUE(step(500ms).empty()) << "once per loss";
}
