// SPDX-License-Identifier: MIT
// The EDS/DCF regression corpus (tests/canopen/corpus, written here; each file reproduces one
// variation of real vendor files). Every drive file is taken to Operation Enabled and through a
// CSP move and a PP move by our master (layout derived from the file) against a simulated node
// built from the same file, in one process on the virtual clock. The positioner without CSP,
// the drive without 0x603F, the single-PDO drive and the I/O module show what the master says.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "hil/can/virtual_bus.hpp"
#include "hil/canopen/eds.hpp"
#include "hil/cia402/cia402_drive.hpp"
#include "hil/cia402/layout.hpp"
#include "hil/mocks/cia402_node.hpp"

using namespace std::chrono_literals;
namespace cia402 = hil::cia402;
namespace co = hil::canopen;
using hil::DriveState;

namespace {

std::string read_file(const std::string& name) {
  std::ifstream in(std::string(HIL_CANOPEN_CORPUS_DIR) + "/" + name, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

/// One simulated node built from `file`, our master with the layout planned from the same file,
/// and the drive, on the virtual clock.
struct Rig {
  hil::VirtualClock clock;
  hil::can::VirtualBus bus{clock, "vbus"};
  std::unique_ptr<hil::can::VirtualChannel> master_channel = bus.attach("master");
  std::unique_ptr<hil::can::VirtualChannel> node_channel = bus.attach("node");
  std::unique_ptr<cia402::Network> network;
  std::unique_ptr<hil::mocks::Cia402Node> node;
  std::unique_ptr<cia402::Cia402Drive> drive;
  cia402::AxisLayout layout;
  hil::DriveCommand command;
  co::NodeId id;

  Rig(const std::string& file, cia402::OperatingSetup setup, co::NodeId node_id = 4) : id(node_id) {
    const auto text = read_file(file);
    hil::canopen::MasterOptions mo;
    mo.sync_period = 1ms;
    mo.sdo.timeout = 50ms;
    network = std::make_unique<cia402::Network>(*master_channel, mo);
    hil::mocks::Cia402NodeOptions no;
    no.node = id;
    no.eds_text = text;
    no.eds_name = file;
    node = std::make_unique<hil::mocks::Cia402Node>(*node_channel, no);
    auto eds = co::parse_eds(text, file, id);
    EXPECT_TRUE(eds) << eds.error().describe();
    cia402::AxisOptions ao;
    ao.node = id;
    ao.setup = setup;
    auto axis = cia402::make_axis_config(*eds, ao);
    EXPECT_TRUE(axis) << axis.error().describe();
    layout = axis->layout;
    network->master().add_node(std::move(axis->node));
    cia402::DriveOptions dopt;
    dopt.setup = setup;
    dopt.layout = layout;
    drive = std::make_unique<cia402::Cia402Drive>(*network, id, dopt);
    node->start(clock.now());
    network->start(clock.now());
    bus.deliver(clock.now());
  }
  void cycle() {
    clock.advance(1ms);
    const hil::CycleTime c{clock.now(), 1ms};
    network->step(c.now);
    bus.deliver(c.now);
    drive->read(c);
    drive->write(c, command);
    node->step(c.now);
    bus.deliver(c.now);
  }
  bool run_until(const std::function<bool()>& done, hil::Duration limit) {
    for (auto end = clock.now() + limit; clock.now() < end;) {
      cycle();
      if (done()) return true;
    }
    return false;
  }
  std::string why() const {
    const auto& st = network->master().status(id);
    return "state " + std::string(hil::to_string(drive->feedback().state)) + ", fault '" +
           drive->feedback().fault.describe() + "', boot " + st.boot_error.message() + " " + st.detail + "\nlayout:\n" +
           joined(layout.decisions);
  }
  void enable() {
    ASSERT_TRUE(run_until([&] { return drive->feedback().state == DriveState::switch_on_disabled; }, 1s)) << why();
    command.position_inc = drive->feedback().position_inc;
    drive->request(hil::DriveRequest::enable);
    ASSERT_TRUE(run_until([&] { return drive->feedback().state == DriveState::operation_enabled; }, 500ms)) << why();
    EXPECT_EQ(node->state(), DriveState::operation_enabled);
  }
};

struct Case {
  const char* file;
  bool csp;           ///< the drive has CSP (else the master must refuse mode csp)
  std::int64_t move;  ///< increments (16-bit drives move less)
};

const Case k_drives[] = {
    {"v01_no_603f.eds", true, 20000},       {"v02_fixed_pdo.eds", true, 20000},   {"v03_pp_hm_only.eds", false, 20000},
    {"v04_four_entries.eds", true, 20000},  {"v05_16bit.eds", true, 3000},        {"v06_manufacturer.eds", true, 20000},
    {"v07_pdo_params.dcf", true, 20000},    {"v08_nodeid_cobs.eds", true, 20000}, {"v09_compact.eds", true, 20000},
    {"v10_mixed_case.eds", true, 20000},    {"v11_comments.eds", true, 20000},    {"v12_one_pdo.eds", true, 20000},
    {"v13_guarding_only.eds", true, 20000},
};

class Corpus : public ::testing::TestWithParam<Case> {};

TEST_P(Corpus, CspMoveAtOperationEnabled) {
  const auto& c = GetParam();
  if (!c.csp) {
    auto eds = co::parse_eds(read_file(c.file), c.file, 4);
    ASSERT_TRUE(eds);
    cia402::AxisOptions ao;
    ao.node = 4;
    ao.setup = cia402::OperatingSetup::csp;
    auto axis = cia402::make_axis_config(*eds, ao);
    ASSERT_FALSE(axis);
    EXPECT_EQ(axis.error().file, c.file);
    EXPECT_NE(axis.error().message.find("mode csp is not supported"), std::string::npos) << axis.error().message;
    return;
  }
  Rig rig(c.file, cia402::OperatingSetup::csp);
  rig.enable();
  const auto start = rig.drive->feedback().position_inc;
  // A 500 ms ramp, one set-point per 1 ms SYNC.
  for (int k = 1; k <= 500; ++k) {
    rig.command.position_inc = start + c.move * k / 500;
    rig.command.velocity_inc_per_s = static_cast<double>(c.move) * 2.0;
    rig.cycle();
    ASSERT_NE(rig.drive->feedback().state, DriveState::fault) << rig.why();
  }
  rig.command.velocity_inc_per_s = 0;
  rig.run_until([] { return false; }, 300ms);
  EXPECT_NEAR(static_cast<double>(rig.drive->feedback().position_inc), static_cast<double>(start + c.move), 50.0)
      << rig.why();
  EXPECT_NEAR(rig.node->plant().position_inc(), static_cast<double>(start + c.move), 50.0);
  EXPECT_EQ(rig.drive->feedback().state, DriveState::operation_enabled) << rig.why();
}

TEST_P(Corpus, PpMoveAtOperationEnabled) {
  const auto& c = GetParam();
  Rig rig(c.file, cia402::OperatingSetup::pp);
  rig.enable();
  const auto start = rig.drive->feedback().position_inc;
  rig.command.move.kind = hil::DriveMove::Kind::position;
  rig.command.move.id = 1;
  rig.command.move.target_inc = start + c.move;
  rig.command.move.velocity_inc_per_s = static_cast<double>(c.move);  // about 1 s
  rig.command.move.acceleration_inc_per_s2 = static_cast<double>(c.move) * 4;
  rig.command.move.deceleration_inc_per_s2 = static_cast<double>(c.move) * 4;
  rig.command.position_inc = start + c.move;
  ASSERT_TRUE(rig.run_until(
      [&] {
        return std::abs(rig.drive->feedback().position_inc - (start + c.move)) <= 20 &&
               (rig.drive->statusword() & 0x0400) != 0;
      },
      4s))
      << "position " << rig.drive->feedback().position_inc << " of " << start + c.move << ", statusword 0x" << std::hex
      << rig.drive->statusword() << std::dec << "\n"
      << rig.why();
  EXPECT_EQ(static_cast<int>(rig.node->od().get_int(0x6061, 0)), 1) << "profile position in effect";
  EXPECT_EQ(rig.drive->feedback().state, DriveState::operation_enabled) << rig.why();
}

std::string case_name(const ::testing::TestParamInfo<Case>& p) {
  std::string name = p.param.file;
  for (auto& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Files, Corpus, ::testing::ValuesIn(k_drives), case_name);

TEST(CorpusDecisions, DriveWithout603FSaysSoAndPollsNothingForIt) {
  Rig rig("v01_no_603f.eds", cia402::OperatingSetup::csp);
  const auto text = joined(rig.layout.decisions);
  EXPECT_NE(text.find("0x603F error code: not in the EDS, left out (fault codes come from EMCY)"), std::string::npos)
      << text;
  EXPECT_EQ(rig.layout.path(0x603F), cia402::ObjectPath::absent);
  EXPECT_EQ(rig.layout.polled(), (std::vector<cia402::ObjectKey>{{0x6077, 0}, {0x60F4, 0}})) << text;
  EXPECT_EQ(rig.layout.path(0x60FD), cia402::ObjectPath::pdo) << "digital inputs in a TPDO where there is room";
  rig.enable();
}

TEST(CorpusDecisions, FixedPdosAreReadAndUsed) {
  Rig rig("v02_fixed_pdo.eds", cia402::OperatingSetup::csp);
  const auto text = joined(rig.layout.decisions);
  EXPECT_NE(text.find("RPDO1 0x204 fixed ([DeviceInfo] Granularity=0), read from the EDS"), std::string::npos) << text;
  EXPECT_NE(text.find("TPDO2 0x284 fixed"), std::string::npos) << text;
  rig.enable();
  // Nothing was remapped: the node's mapping is still its own.
  EXPECT_EQ(rig.node->od().get_int(0x1A00, 3), 0x603F0010);
  EXPECT_EQ(rig.node->od().get_int(0x1601, 1), 0x607A0020);
}

TEST(CorpusDecisions, OnePdoDriveReadsAndWritesTheRestBySdo) {
  Rig rig("v12_one_pdo.eds", cia402::OperatingSetup::csp);
  const auto text = joined(rig.layout.decisions);
  EXPECT_EQ(rig.layout.path(0x6041), cia402::ObjectPath::pdo);
  EXPECT_EQ(rig.layout.path(0x6064), cia402::ObjectPath::pdo);
  EXPECT_EQ(rig.layout.path(0x606C), cia402::ObjectPath::sdo_poll) << text;
  EXPECT_EQ(rig.layout.path(0x60FF), cia402::ObjectPath::sdo_write) << text;
  EXPECT_NE(text.find("0x606C velocity actual value: no room in the PDOs, read by SDO every 100 ms"), std::string::npos)
      << text;
  rig.enable();
}

TEST(CorpusDecisions, FourEntryPdosPutTheProfileDecelerationOnSdo) {
  Rig rig("v04_four_entries.eds", cia402::OperatingSetup::pp);
  EXPECT_EQ(rig.layout.path(0x6084), cia402::ObjectPath::sdo_write) << joined(rig.layout.decisions);
  EXPECT_LE(rig.node->od().get_int(0x1600, 0), 4);
}

TEST(CorpusDecisions, DcfPdoParameterValuesAreWrittenWithTheCia301Sequence) {
  auto eds = co::parse_eds(read_file("v07_pdo_params.dcf"), "v07_pdo_params.dcf", 0);
  ASSERT_TRUE(eds) << eds.error().describe();
  EXPECT_EQ(eds->dcf_node_id, 3);
  cia402::AxisOptions ao;
  ao.node = 3;
  auto axis = cia402::make_axis_config(*eds, ao);
  ASSERT_TRUE(axis) << axis.error().describe();
  // TPDO1 (0x1800 / 0x1A00): COB-ID invalid, sub 0 = 0, entries, sub 0 = 3, transmission type, COB-ID valid.
  std::vector<std::string> seq;
  for (const auto& pv : axis->node.configuration) {
    if (pv.index != 0x1800 && pv.index != 0x1A00) continue;
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < pv.bytes.size(); ++i) v |= std::uint64_t{pv.bytes[i]} << (8 * i);
    seq.push_back(fmt::format("{:04X}:{}={:X}", pv.index, pv.sub, v));
  }
  EXPECT_EQ(seq, (std::vector<std::string>{"1800:1=80000183", "1A00:0=0", "1A00:1=60410010", "1A00:2=60610008",
                                           "1A00:3=603F0010", "1A00:0=3", "1800:2=1", "1800:1=183"}));
  // Other ParameterValues come first, in object order.
  ASSERT_GE(axis->node.configuration.size(), 2u);
  EXPECT_EQ(axis->node.configuration[0].index, 0x6065);
  EXPECT_EQ(axis->node.configuration[1].index, 0x6067);
  Rig rig("v07_pdo_params.dcf", cia402::OperatingSetup::csp, 3);
  rig.enable();
  EXPECT_EQ(rig.node->od().get_int(0x6065, 0), 30000);
}

TEST(CorpusDecisions, GuardingOnlyDriveIsGuardedAndALostNodeFaultsTheAxis) {
  Rig rig("v13_guarding_only.eds", cia402::OperatingSetup::csp);
  const auto text = joined(rig.layout.decisions);
  EXPECT_NE(text.find("node guarding instead (0x100C guard time 20 ms, 0x100D life-time factor 3"), std::string::npos)
      << text;
  rig.enable();
  EXPECT_EQ(rig.node->od().get_int(0x100C, 0), 20);
  EXPECT_EQ(rig.node->od().get_int(0x100D, 0), 3);
  rig.run_until([] { return false; }, 200ms);
  EXPECT_FALSE(rig.drive->feedback().fault) << "answers keep coming: " << rig.why();
  ASSERT_TRUE(rig.node->inject_fault("heartbeat_loss", true, rig.clock.now()));  // no more guarding answers
  ASSERT_TRUE(rig.run_until([&] { return static_cast<bool>(rig.drive->feedback().fault); }, 200ms)) << rig.why();
  EXPECT_EQ(rig.drive->feedback().fault.code.value(), 0x8130) << rig.why();
}

TEST(CorpusDecisions, NonDriveFailsAtOnceNamingTheMissingObjects) {
  auto eds = co::parse_eds(read_file("v14_io_module.eds"), "v14_io_module.eds", 4);
  ASSERT_TRUE(eds) << eds.error().describe();
  cia402::AxisOptions ao;
  ao.node = 4;
  auto axis = cia402::make_axis_config(*eds, ao);
  ASSERT_FALSE(axis);
  EXPECT_EQ(axis.error().file, "v14_io_module.eds");
  const auto& m = axis.error().message;
  for (const char* part : {"0x6040 controlword", "0x6041 statusword", "0x6060 modes of operation",
                           "0x6064 position actual value", "0x607A target position", "not a CiA 402 device"})
    EXPECT_NE(m.find(part), std::string::npos) << part << " in " << m;
  EXPECT_FALSE(hil::mocks::load_node_eds(read_file("v14_io_module.eds"), "v14_io_module.eds", 4));
}

TEST(CorpusDecisions, ScenarioOverrideMapsExactlyWhatItSays) {
  auto eds = co::parse_eds(read_file("v01_no_603f.eds"), "v01_no_603f.eds", 4);
  ASSERT_TRUE(eds);
  cia402::AxisOptions ao;
  ao.node = 4;
  ao.mapping.tpdo = std::vector<std::vector<co::PdoMappingEntry>>{{{0x6041, 0, 16}, {0x6064, 0, 32}}};
  auto axis = cia402::make_axis_config(*eds, ao);
  ASSERT_TRUE(axis) << axis.error().describe();
  EXPECT_EQ(axis->layout.path(0x6061), cia402::ObjectPath::sdo_poll);
  EXPECT_EQ(axis->layout.tpdos[0].mapping.size(), 2u);
  ao.mapping.tpdo = std::vector<std::vector<co::PdoMappingEntry>>{{{0x6041, 0, 16}, {0x1008, 0, 0}}};
  auto bad = cia402::make_axis_config(*eds, ao);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("0x1008:0 is not PDO-mappable"), std::string::npos) << bad.error().message;
  // A fixed PDO cannot be overridden.
  auto fixed = co::parse_eds(read_file("v02_fixed_pdo.eds"), "v02_fixed_pdo.eds", 4);
  ASSERT_TRUE(fixed);
  auto f = cia402::make_axis_config(*fixed, ao);
  ASSERT_FALSE(f);
  EXPECT_NE(f.error().message.find("only 0 remappable"), std::string::npos) << f.error().message;
}

TEST(CorpusFiles, EveryFileParsesAndOdditiesAreWarnings) {
  for (const auto* file :
       {"v01_no_603f.eds", "v02_fixed_pdo.eds", "v03_pp_hm_only.eds", "v04_four_entries.eds", "v05_16bit.eds",
        "v06_manufacturer.eds", "v07_pdo_params.dcf", "v08_nodeid_cobs.eds", "v09_compact.eds", "v10_mixed_case.eds",
        "v11_comments.eds", "v12_one_pdo.eds", "v13_guarding_only.eds", "v14_io_module.eds"}) {
    auto d = co::parse_eds(read_file(file), file, 5);
    ASSERT_TRUE(d) << d.error().describe();
    std::string w;
    for (const auto& x : d->warnings) w += x.describe() + "\n";
    const std::string name = file;
    if (name == "v10_mixed_case.eds")
      EXPECT_NE(w.find("not spelled as CiA 306 writes them"), std::string::npos) << w;
    else if (name == "v11_comments.eds")
      for (const char* part :
           {"byte-order mark", "inline ';' comment", "section appears again", "object 0x2222 is not in"})
        EXPECT_NE(w.find(part), std::string::npos) << part << " in\n" << w;
    else
      EXPECT_TRUE(d->warnings.empty()) << file << ":\n" << w;
  }
  auto cobs = co::parse_eds(read_file("v08_nodeid_cobs.eds"), "v08_nodeid_cobs.eds", 5);
  ASSERT_TRUE(cobs);
  EXPECT_EQ(cobs->od.get_int(0x1400, 1), 0x205);
  EXPECT_EQ(cobs->od.get_int(0x1401, 1), 0x305);
  EXPECT_EQ(cobs->od.get_int(0x1402, 1), 0x405);
  EXPECT_EQ(cobs->od.get_int(0x1403, 1), 0x505);
  auto compact = co::parse_eds(read_file("v09_compact.eds"), "v09_compact.eds", 5);
  ASSERT_TRUE(compact);
  EXPECT_EQ(compact->od.get_int(0x1016, 0), 4);
  EXPECT_EQ(compact->od.find(0x1016, 2)->name, "Axis 2");
  EXPECT_EQ(compact->od.get_int(0x1016, 2), 0x00020000);
  EXPECT_EQ(compact->od.get_int(0x2100, 0), 16);
}

}  // namespace
