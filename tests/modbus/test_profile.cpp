// SPDX-License-Identifier: MIT
// Register profiles: the shipped ones load, bad ones give located errors; exchange plans; the
// state machine words of both ends.
#include <gtest/gtest.h>

#include "hil/modbus/drive_words.hpp"
#include "hil/modbus/exchange_plan.hpp"
#include "hil/modbus/profile.hpp"

namespace hil::modbus {
namespace {

Profile load_shipped(const char* name) {
  auto p = load_profile(std::string("profiles/modbus/") + name);
  EXPECT_TRUE(p) << (p ? "" : p.error().describe());
  return p ? *p : Profile{};
}

TEST(ModbusProfile, ShippedProfilesLoadAndPlan) {
  const Profile cia = load_shipped("cia402.yaml");
  EXPECT_EQ(cia.state_machine, StateMachineKind::cia402);
  EXPECT_EQ(cia.field(FieldRole::actual_position).format.words, 2);
  auto plan = make_exchange_plan(cia);
  ASSERT_TRUE(plan);
  EXPECT_TRUE(plan->read_write);
  EXPECT_EQ(plan->requests_per_exchange(), 1u);
  EXPECT_EQ(plan->writes[0].first, 0);
  EXPECT_EQ(plan->writes[0].count, 6);
  EXPECT_EQ(plan->reads[0].first, 10);
  EXPECT_EQ(plan->reads[0].count, 6);
  EXPECT_EQ(cia.fault_text(0x7305).substr(0, 11), "incremental");

  const Profile v = load_shipped("vendor_simple.yaml");
  EXPECT_EQ(v.state_machine, StateMachineKind::vendor);
  EXPECT_EQ(v.feedback_space(), RegisterSpace::input);
  EXPECT_EQ(v.field(FieldRole::target_position).format.order, WordOrder::low_first);
  EXPECT_DOUBLE_EQ(v.field(FieldRole::actual_velocity).scale, 10.0);
  auto vp = make_exchange_plan(v);
  ASSERT_TRUE(vp);
  EXPECT_FALSE(vp->read_write);
  EXPECT_EQ(vp->read_fc, 4);
  EXPECT_EQ(vp->requests_per_exchange(), 2u);
}

const char* kMinimal = R"(name: t
state_machine: cia402
registers:
  control_word: {address: 0}
  target_position: {address: 1, type: s32}
  status_word: {address: 10}
  actual_position: {address: 11, type: s32}
)";

TEST(ModbusProfile, MinimalDefaults) {
  auto p = parse_profile(kMinimal, "t.yaml");
  ASSERT_TRUE(p) << p.error().describe();
  EXPECT_EQ(p->function_codes.read, 3);
  EXPECT_EQ(p->function_codes.write, 16);
  EXPECT_FALSE(p->field(FieldRole::mode).present);
  auto plan = make_exchange_plan(*p);
  ASSERT_TRUE(plan);
  EXPECT_EQ(plan->writes.size(), 1u);
  EXPECT_EQ(plan->writes[0].count, 3);
}

TEST(ModbusProfile, TypeNamesOfTheCliAndTheOldOnes) {
  // i16/i32 as the CLI writes them (docs/cli.md); s16/s32 as profiles wrote them before.
  std::string yaml = kMinimal;
  yaml.replace(yaml.find("type: s32"), 9, "type: i32");
  auto p = parse_profile(yaml, "t.yaml");
  ASSERT_TRUE(p) << p.error().describe();
  EXPECT_EQ(p->field(FieldRole::target_position).format.words, 2);
  EXPECT_TRUE(p->field(FieldRole::target_position).format.is_signed);
  EXPECT_TRUE(p->field(FieldRole::actual_position).format.is_signed);
}

struct BadCase {
  const char* what;
  std::string yaml;
  int line;
  const char* key;
  const char* message_part;
};

TEST(ModbusProfile, ErrorsNameLineKeyAndFix) {
  const std::string base = kMinimal;
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = base;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const std::vector<BadCase> cases = {
      {"typo key", replace("control_word: {address: 0}", "control_wrd: {address: 0}"), 4, "registers.control_wrd",
       "unknown key"},
      {"bad type", replace("type: s32}\n  status", "type: f32}\n  status"), 5, "registers.target_position.type",
       "u16, i16"},
      {"overlap", replace("address: 11, type: s32", "address: 10, type: s32"), 7, "registers.actual_position",
       "overlaps"},
      {"address range", replace("address: 0}", "address: 70000}"), 4, "registers.control_word.address", "0..65535"},
      {"32-bit control word", replace("control_word: {address: 0}", "control_word: {address: 20, type: u32}"), 4,
       "registers.control_word.type", "16-bit"},
      {"state machine", replace("cia402", "ds402"), 2, "state_machine", "'cia402' or 'vendor'"},
      {"missing status word", replace("  status_word: {address: 10}\n", ""), 4, "registers.status_word", "required"},
      {"fc6 with 32-bit", base + "function_codes: {write: 6}\n", 5, "registers.target_position.type", "FC 16"},
      {"fc23 with input regs", base + "function_codes: {read: 4, read_write: true}\n", 8, "function_codes", "FC 23"},
      {"vendor without bits", replace("cia402", "vendor"), 1, "bits.enable", "missing"},
      {"syntax", "name: [unclosed\n", 2, "", "YAML syntax error"},
      {"homing without a mode register", base + "modes: {homing: 6}\n", 8, "modes.homing", "needs a `mode` register"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    auto p = parse_profile(c.yaml, "bad.yaml");
    ASSERT_FALSE(p);
    EXPECT_EQ(p.error().file, "bad.yaml");
    EXPECT_EQ(p.error().line, c.line) << p.error().describe();
    EXPECT_EQ(p.error().key, c.key) << p.error().describe();
    EXPECT_NE(p.error().message.find(c.message_part), std::string::npos) << p.error().describe();
  }
  auto missing = load_profile("profiles/modbus/does_not_exist.yaml");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("cannot open"), std::string::npos);
}

TEST(ModbusDriveWords, Cia402RoundTripAndEnableSequence) {
  const Profile p = load_shipped("cia402.yaml");
  for (auto s : {DriveState::not_ready, DriveState::switch_on_disabled, DriveState::ready_to_switch_on,
                 DriveState::switched_on, DriveState::operation_enabled, DriveState::quick_stop_active,
                 DriveState::fault_reaction_active, DriveState::fault})
    EXPECT_EQ(decode_status(p, make_status_word(p, s, true, true)).state, s) << to_string(s);
  // Client and device walk the FSA together: SOD -> RTSO -> SO -> OE.
  DriveState s = DriveState::switch_on_disabled;
  std::uint16_t prev = 0;
  std::vector<std::uint16_t> sent;
  for (int i = 0; i < 5 && s != DriveState::operation_enabled; ++i) {
    const auto cw = make_control_word(p, s, PowerTarget::enabled, false);
    sent.push_back(cw);
    s = next_device_state(p, s, cw, prev, false, true);
    prev = cw;
  }
  EXPECT_EQ(s, DriveState::operation_enabled);
  EXPECT_EQ(sent, (std::vector<std::uint16_t>{0x06, 0x07, 0x0F}));
  // Quick stop, then standstill ends in switch on disabled.
  s = next_device_state(p, s, 0x02, 0x0F, false, false);
  EXPECT_EQ(s, DriveState::quick_stop_active);
  s = next_device_state(p, s, 0x02, 0x02, false, true);
  EXPECT_EQ(s, DriveState::switch_on_disabled);
  // Fault needs a rising edge of bit 7 and the cause gone.
  s = next_device_state(p, DriveState::operation_enabled, 0x0F, 0x0F, true, true);
  EXPECT_EQ(s, DriveState::fault_reaction_active);
  s = next_device_state(p, s, 0x0F, 0x0F, true, true);
  EXPECT_EQ(s, DriveState::fault);
  EXPECT_EQ(next_device_state(p, s, 0x80, 0x00, true, true), DriveState::fault);   // cause still active
  EXPECT_EQ(next_device_state(p, s, 0x80, 0x80, false, true), DriveState::fault);  // no edge
  EXPECT_EQ(next_device_state(p, s, 0x80, 0x00, false, true), DriveState::switch_on_disabled);
}

TEST(ModbusDriveWords, VendorBits) {
  const Profile p = load_shipped("vendor_simple.yaml");
  EXPECT_EQ(make_control_word(p, DriveState::switch_on_disabled, PowerTarget::enabled, false), 0x0001);
  EXPECT_EQ(make_control_word(p, DriveState::fault, PowerTarget::enabled, true), 0x0002);
  EXPECT_EQ(make_control_word(p, DriveState::operation_enabled, PowerTarget::quick_stop, false), 0x0004);
  EXPECT_EQ(make_status_word(p, DriveState::operation_enabled, true, false), 0x000B);
  EXPECT_EQ(decode_status(p, 0x000B).state, DriveState::operation_enabled);
  EXPECT_TRUE(decode_status(p, 0x000B).referenced);
  EXPECT_EQ(decode_status(p, 0x0004).state, DriveState::fault);
  EXPECT_EQ(decode_status(p, 0x0001).state, DriveState::switch_on_disabled);
  EXPECT_EQ(decode_status(p, 0x0000).state, DriveState::not_ready);
  EXPECT_EQ(next_device_state(p, DriveState::switch_on_disabled, 0x1, 0x0, false, true), DriveState::operation_enabled);
  EXPECT_EQ(next_device_state(p, DriveState::operation_enabled, 0x5, 0x1, false, false), DriveState::quick_stop_active);
  EXPECT_EQ(next_device_state(p, DriveState::fault, 0x2, 0x0, false, true), DriveState::switch_on_disabled);
}

}  // namespace
}  // namespace hil::modbus
