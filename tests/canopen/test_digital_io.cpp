// SPDX-License-Identifier: MIT
// CiA 402 digital I/O end to end: the simulated node's 0x60FD (limit and home switches of its
// plant, bits a test forces) reaches DriveFeedback::digital_inputs, and DriveCommand::
// digital_outputs reaches the node's 0x60FE:1 through the 0x60FE:2 bit mask the master writes at
// boot-up. In a PDO where the layout has room (the shipped EDS), by SDO where it has not (an
// explicit mapping without them); our master against the simulated node on the virtual bus.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <string>

#include "hil/can/virtual_bus.hpp"
#include "hil/canopen/eds.hpp"
#include "hil/cia402/cia402_drive.hpp"
#include "hil/cia402/layout.hpp"
#include "hil/mocks/cia402_node.hpp"

using namespace std::chrono_literals;
namespace cia402 = hil::cia402;
namespace co = hil::canopen;
namespace di = hil::digital_input;
using hil::DriveState;

namespace {

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

struct Rig {
  hil::VirtualClock clock;
  hil::can::VirtualBus bus{clock, "vbus"};
  std::unique_ptr<hil::can::VirtualChannel> master_channel = bus.attach("master");
  std::unique_ptr<hil::can::VirtualChannel> node_channel = bus.attach("node");
  std::unique_ptr<cia402::Network> network;
  std::unique_ptr<hil::mocks::Cia402Node> node;
  std::unique_ptr<cia402::Cia402Drive> drive;
  cia402::AxisLayout layout;
  co::NodeConfig config;
  hil::DriveCommand command;
  std::size_t cycles = 0;
  static constexpr co::NodeId id = 3;

  explicit Rig(cia402::AxisOptions ao = {}, hil::mocks::PlantSwitches switches = {}) {
    hil::canopen::MasterOptions mo;
    mo.sync_period = 1ms;
    mo.sdo.timeout = 50ms;
    network = std::make_unique<cia402::Network>(*master_channel, mo);
    hil::mocks::Cia402NodeOptions no;
    no.node = id;
    no.switches = switches;
    node = std::make_unique<hil::mocks::Cia402Node>(*node_channel, no);
    auto eds = co::parse_eds(hil::mocks::cia402_node_eds(), "hil_cia402_drive.eds", id);
    EXPECT_TRUE(eds);
    ao.node = id;
    auto axis = cia402::make_axis_config(*eds, ao);
    EXPECT_TRUE(axis) << axis.error().describe();
    layout = axis->layout;
    config = axis->node;
    network->master().add_node(std::move(axis->node));
    cia402::DriveOptions dopt;
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
    ++cycles;
  }
  bool run_until(const std::function<bool()>& done, hil::Duration limit) {
    for (auto end = clock.now() + limit; clock.now() < end;) {
      cycle();
      if (done()) return true;
    }
    return false;
  }
  std::string why() const { return "layout:\n" + joined(layout.decisions); }
  void boot() {
    ASSERT_TRUE(run_until([&] { return drive->feedback().state == DriveState::switch_on_disabled; }, 1s)) << why();
  }
  void enable() {
    boot();
    command.position_inc = drive->feedback().position_inc;
    drive->request(hil::DriveRequest::enable);
    ASSERT_TRUE(run_until([&] { return drive->feedback().state == DriveState::operation_enabled; }, 500ms)) << why();
  }
};

bool has_write(const co::NodeConfig& c, std::uint16_t index, std::uint8_t sub, std::uint32_t value) {
  return std::any_of(c.configuration.begin(), c.configuration.end(), [&](const co::ParameterValue& pv) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < pv.bytes.size() && i < 4; ++i) v |= std::uint32_t{pv.bytes[i]} << (8 * i);
    return pv.index == index && pv.sub == sub && v == value;
  });
}

bool mapped(const std::vector<cia402::PlannedPdo>& pdos, std::uint16_t index, std::uint8_t sub) {
  for (const auto& p : pdos)
    for (const auto& e : p.mapping)
      if (e.index == index && e.sub == sub) return true;
  return false;
}

TEST(DigitalIoLayout, ShippedDriveMapsBothIntoPdosAndWritesTheMaskOnce) {
  for (auto setup : {cia402::OperatingSetup::csp, cia402::OperatingSetup::csv, cia402::OperatingSetup::pp}) {
    cia402::AxisOptions ao;
    ao.setup = setup;
    Rig rig(ao);
    const auto text = joined(rig.layout.decisions);
    EXPECT_EQ(rig.layout.path(0x60FD), cia402::ObjectPath::pdo) << text;
    EXPECT_EQ(rig.layout.path(0x60FE, 1), cia402::ObjectPath::pdo) << text;
    EXPECT_TRUE(mapped(rig.layout.tpdos, 0x60FD, 0)) << text;
    EXPECT_TRUE(mapped(rig.layout.rpdos, 0x60FE, 1)) << text;
    EXPECT_EQ(rig.layout.polled(), (std::vector<cia402::ObjectKey>{{0x6077, 0}})) << text;  // diagnostics only
    EXPECT_TRUE(rig.layout.written().empty()) << text;
    EXPECT_EQ(rig.layout.digital_output_mask, 0xFFFF0000u) << "bit 0 (set brake) stays the drive's by default";
    EXPECT_TRUE(has_write(rig.config, 0x60FE, 2, 0xFFFF0000u)) << "0x60FE:2 in the configuration download";
    EXPECT_NE(text.find("0x60FE:2 bit mask = 0xFFFF0000, written once at boot-up"), std::string::npos) << text;
    const auto caps = rig.drive->capabilities();
    EXPECT_TRUE(caps.digital_inputs);
    EXPECT_EQ(caps.digital_output_mask, 0xFFFF0000u);
  }
}

TEST(DigitalIoLayout, ADriveWithoutTheObjectsHasNoDigitalIo) {
  // The shipped EDS without 0x60FD and 0x60FE: the objects are left out, with their line.
  std::string text(hil::mocks::cia402_node_eds());
  for (auto [section, name] :
       {std::pair{"[60FD]", "2FF0"}, std::pair{"[60FE]", "2FF1"}, std::pair{"[60FEsub0]", "2FF1"},
        std::pair{"[60FEsub1]", "2FF1"}, std::pair{"[60FEsub2]", "2FF1"}}) {
    const auto at = text.find(section);
    ASSERT_NE(at, std::string::npos) << section;
    text.replace(at + 1, 4, name);  // moved out of the way (a listed object without a section is a warning)
  }
  auto eds = co::parse_eds(text, "no_io.eds", 3);
  ASSERT_TRUE(eds) << eds.error().describe();
  ASSERT_EQ(eds->od.find(0x60FD, 0), nullptr);
  cia402::AxisOptions ao;
  ao.node = 3;
  auto axis = cia402::make_axis_config(*eds, ao);
  ASSERT_TRUE(axis) << axis.error().describe();
  const auto decisions = joined(axis->layout.decisions);
  EXPECT_EQ(axis->layout.path(0x60FD), cia402::ObjectPath::absent);
  EXPECT_EQ(axis->layout.path(0x60FE, 1), cia402::ObjectPath::absent);
  EXPECT_EQ(axis->layout.digital_output_mask, 0u);
  EXPECT_NE(decisions.find("0x60FD digital inputs: not in the EDS, left out (the axis has no digital inputs)"),
            std::string::npos)
      << decisions;
  EXPECT_NE(decisions.find("0x60FE:1 digital outputs: not in the EDS, left out (the axis has no digital outputs)"),
            std::string::npos)
      << decisions;
  hil::VirtualClock clock;
  hil::can::VirtualBus bus{clock, "vbus"};
  auto ch = bus.attach("master");
  cia402::Network network(*ch, {});
  network.master().add_node(std::move(axis->node));
  cia402::DriveOptions dopt;
  dopt.layout = axis->layout;
  cia402::Cia402Drive drive(network, 3, dopt);
  EXPECT_FALSE(drive.capabilities().digital_inputs);
  EXPECT_EQ(drive.capabilities().digital_output_mask, 0u);
}

TEST(DigitalIo, ForcedNodeInputsReachTheFeedbackInAPdo) {
  Rig rig;
  rig.boot();
  EXPECT_EQ(rig.drive->feedback().digital_inputs, 0u);
  rig.node->inputs().force(di::interlock | (1u << 20), di::interlock | (1u << 20));
  ASSERT_TRUE(rig.run_until([&] { return rig.drive->feedback().digital_inputs == (di::interlock | (1u << 20)); }, 5ms))
      << "a PDO carries 0x60FD within a few cycles";
  rig.node->inputs().force(1u << 20, 0);
  ASSERT_TRUE(rig.run_until([&] { return rig.drive->feedback().digital_inputs == di::interlock; }, 5ms));
  rig.node->inputs().release(di::interlock | (1u << 20));
  ASSERT_TRUE(rig.run_until([&] { return rig.drive->feedback().digital_inputs == 0; }, 5ms));
}

TEST(DigitalIo, SwitchesFollowThePlantPositionWhileTheAxisMoves) {
  hil::mocks::PlantSwitches sw;
  sw.negative_inc = -500.0;
  sw.positive_inc = 9500.0;
  sw.home = hil::mocks::HomeCam{1000.0, 1200.0};
  Rig rig({}, sw);
  rig.enable();
  EXPECT_EQ(rig.drive->feedback().digital_inputs, 0u) << "at 0 no switch is active";
  // Ramp through the home cam to beyond the positive limit, then back below the negative one.
  bool saw_home = false;
  for (std::int64_t p = 0; p <= 10'000; p += 20) {
    rig.command.position_inc = p;
    rig.cycle();
    const auto pos = rig.drive->feedback().position_inc;
    const auto in = rig.drive->feedback().digital_inputs;
    if ((in & di::home_switch) != 0) {
      saw_home = true;
      // The bit is two PDO cycles old at most: the position it was sampled at was on the cam.
      EXPECT_GE(pos, 1000 - 3 * 60) << pos;
      EXPECT_LE(pos, 1200 + 3 * 60) << pos;
    }
  }
  EXPECT_TRUE(saw_home);
  ASSERT_TRUE(rig.run_until([&] { return (rig.drive->feedback().digital_inputs & di::positive_limit) != 0; }, 200ms));
  EXPECT_GE(rig.node->plant().position_inc(), 9500.0);
  EXPECT_EQ(rig.drive->feedback().digital_inputs & (di::negative_limit | di::home_switch), 0u);
  rig.command.position_inc = -1000;
  ASSERT_TRUE(rig.run_until([&] { return (rig.drive->feedback().digital_inputs & di::negative_limit) != 0; }, 2s));
  EXPECT_EQ(rig.drive->feedback().digital_inputs & di::positive_limit, 0u);
}

TEST(DigitalIo, OutputsReachTheNodeThroughTheBitMaskInEveryState) {
  Rig rig;
  rig.boot();
  ASSERT_EQ(rig.node->od().get_int(0x60FE, 2), 0xFFFF0000) << "the mask was written during the boot-up";
  rig.command.digital_outputs = 0x00050001u;  // bit 0 (brake) is outside the default mask
  ASSERT_TRUE(rig.run_until([&] { return rig.node->digital_outputs() == 0x00050000u; }, 5ms))
      << "outputs are written while the drive is switched off, too";
  EXPECT_EQ(rig.node->od().get_int(0x60FE, 1), 0x00050000) << "the master writes only the bits of its mask";
  rig.enable();
  rig.command.digital_outputs = 0x80000000u;
  ASSERT_TRUE(rig.run_until([&] { return rig.node->digital_outputs() == 0x80000000u; }, 5ms));
}

TEST(DigitalIo, AScenarioMaskHandsTheBrakeBitToTheMaster) {
  cia402::AxisOptions ao;
  ao.digital_output_mask = 0x00000001u;
  Rig rig(ao);
  rig.boot();
  EXPECT_EQ(rig.drive->capabilities().digital_output_mask, 1u);
  rig.command.digital_outputs = 0xFFFFFFFFu;
  ASSERT_TRUE(rig.run_until([&] { return rig.node->digital_outputs() == 1u; }, 5ms));
  EXPECT_EQ(rig.node->od().get_int(0x60FE, 2), 1);
}

TEST(DigitalIo, WithoutPdoRoomBothGoBySdoAndTheCycleNeverWaits) {
  // An explicit mapping that leaves the digital I/O out: 0x60FD is polled, 0x60FE:1 written on change.
  cia402::AxisOptions ao;
  ao.mapping.rpdo = std::vector<std::vector<co::PdoMappingEntry>>{{{0x6040, 0, 16}, {0x6060, 0, 8}, {0x607A, 0, 32}},
                                                                  {{0x60FF, 0, 32}}};
  ao.mapping.tpdo = std::vector<std::vector<co::PdoMappingEntry>>{{{0x6041, 0, 16}, {0x6061, 0, 8}, {0x603F, 0, 16}},
                                                                  {{0x6064, 0, 32}, {0x606C, 0, 32}}};
  Rig rig(ao);
  const auto text = joined(rig.layout.decisions);
  EXPECT_EQ(rig.layout.path(0x60FD), cia402::ObjectPath::sdo_poll) << text;
  EXPECT_EQ(rig.layout.path(0x60FE, 1), cia402::ObjectPath::sdo_write) << text;
  EXPECT_EQ(rig.layout.polled(), (std::vector<cia402::ObjectKey>{{0x60FD, 0}, {0x6077, 0}})) << text;
  EXPECT_EQ(rig.layout.written(), (std::vector<cia402::ObjectKey>{{0x60FE, 1}})) << text;
  EXPECT_TRUE(rig.drive->capabilities().digital_inputs);
  rig.boot();
  rig.node->inputs().force(di::home_switch, di::home_switch);
  rig.command.digital_outputs = 0x00020000u;
  const auto start = rig.cycles;
  const auto t0 = rig.clock.now();
  ASSERT_TRUE(rig.run_until(
      [&] {
        return rig.drive->feedback().digital_inputs == di::home_switch && rig.node->digital_outputs() == 0x20000u;
      },
      300ms))
      << text;
  // Every cycle ran (1 ms each): the SDO transfers went on beside the cycle, never in it.
  EXPECT_EQ(rig.cycles - start, static_cast<std::size_t>((rig.clock.now() - t0) / 1ms));
  EXPECT_LE(rig.clock.now() - t0, 150ms) << "one poll period (100 ms) plus the transfer";
  EXPECT_EQ(rig.drive->feedback().state, DriveState::switch_on_disabled) << "no SDO write failed";
}

}  // namespace
