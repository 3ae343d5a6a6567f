// SPDX-License-Identifier: MIT
// Device errors from the real catalogues (profiles/devices): number, text and reaction from the
// entry, the acknowledgement rule read from it, and the latch: duplicates, acknowledge by
// strength, self-clearing, history.
#include <gtest/gtest.h>

#include "hil/controllers/device_error.hpp"
#include "hil/profiles/loader.hpp"

namespace hil::controllers {
namespace {

const profiles::ErrorCatalogue& catalogue(std::string_view device, std::string_view id) {
  auto p = profiles::find_profile(device);
  EXPECT_TRUE(p) << (p ? "" : p.error().describe());
  const auto* c = (*p)->catalogue(id);
  EXPECT_NE(c, nullptr) << device << "." << id;
  return *c;
}

TEST(DeviceError, CarriesTheDevicesNumberTextAndReaction) {
  const auto& wf = catalogue("wf725-726", "traversing");
  const auto e = make_device_error(wf, 0x96, TimePoint{std::chrono::milliseconds(8)}, 0, "axis X");
  EXPECT_EQ(e.code, 0x96);
  EXPECT_EQ(e.code_text(), "96");
  EXPECT_EQ(e.fault.code.value(), 0x96);
  EXPECT_STREQ(e.fault.code.category().name(), "wf725-726.traversing");
  EXPECT_EQ(e.reaction, profiles::Reaction::stop);
  EXPECT_EQ(e.ack, AckRule::acknowledge);
  EXPECT_NE(e.fault.text.find("Pre-limit switch positive (MD 13)"), std::string::npos) << e.fault.text;
  EXPECT_NE(e.fault.text.find("(axis X)"), std::string::npos) << e.fault.text;
  EXPECT_EQ(e.describe().rfind("wf725-726.traversing 96 Pre-limit switch positive", 0), 0U) << e.describe();

  const auto& ip = catalogue("ip247", "module");
  const auto sw = make_device_error(ip, 28, TimePoint{});
  EXPECT_EQ(sw.code_text(), "28");
  EXPECT_NE(sw.fault.text.find("SW limit start"), std::string::npos);

  const auto& clm = catalogue("clm14", "diagnostic");
  const auto travel = make_device_error(clm, 0x50, TimePoint{});
  EXPECT_EQ(travel.code_text(), "50");
  EXPECT_EQ(travel.reaction, profiles::Reaction::drive_off);
}

TEST(DeviceError, UnknownCodeStillGivesAnError) {
  const auto& ip = catalogue("ip247", "module");
  const auto e = make_device_error(ip, 9999, TimePoint{});
  EXPECT_EQ(e.reaction, profiles::Reaction::stop);
  EXPECT_EQ(e.ack, AckRule::acknowledge);
  EXPECT_NE(e.fault.text.find("unknown"), std::string::npos) << e.fault.text;
}

TEST(DeviceError, AckRuleFollowsTheCatalogue) {
  const auto& wf = catalogue("wf725-726", "traversing");
  ASSERT_NE(wf.find(0x01), nullptr);
  EXPECT_EQ(ack_rule_for(*wf.find(0x01)), AckRule::reset) << "system fault needs RESET";
  EXPECT_EQ(ack_rule_for(*wf.find(0x95)), AckRule::acknowledge) << "data code 800C";
  const auto& ip = catalogue("ip247", "module");
  EXPECT_EQ(ack_rule_for(*ip.find(1)), AckRule::self_clearing) << "warning/information";
  EXPECT_EQ(ack_rule_for(*ip.find(28)), AckRule::acknowledge);
  const auto& clm = catalogue("clm14", "diagnostic");
  EXPECT_EQ(ack_rule_for(*clm.find(0x10)), AckRule::power_cycle) << "system failure";
}

TEST(DeviceErrorLatch, LatchesOnceAndAcknowledgesByStrength) {
  const auto& wf = catalogue("wf725-726", "traversing");
  DeviceErrorLatch latch;
  EXPECT_TRUE(latch.raise(make_device_error(wf, 0x95, TimePoint{}, 0)));
  EXPECT_FALSE(latch.raise(make_device_error(wf, 0x95, TimePoint{}, 0))) << "already active";
  EXPECT_TRUE(latch.raise(make_device_error(wf, 0x95, TimePoint{}, 1))) << "other axis";
  EXPECT_TRUE(latch.raise(make_device_error(wf, 0x01, TimePoint{})));  // needs RESET
  EXPECT_TRUE(latch.blocks_motion());
  EXPECT_TRUE(latch.blocks_motion(1));
  EXPECT_EQ(latch.active().size(), 3U);

  EXPECT_EQ(latch.acknowledge(Acknowledgement::acknowledge), 2U);
  ASSERT_EQ(latch.active().size(), 1U);
  EXPECT_EQ(latch.active()[0].code, 0x01) << "an acknowledge does not clear a reset error";
  EXPECT_EQ(latch.acknowledge(Acknowledgement::reset), 1U);
  EXPECT_FALSE(latch.any());
  EXPECT_EQ(latch.history().size(), 3U) << "history keeps every error";
  EXPECT_TRUE(latch.raise(make_device_error(wf, 0x95, TimePoint{}, 0))) << "raised again after clearing";
}

TEST(DeviceErrorLatch, SelfClearingErrorsClearOnlyThemselves) {
  const auto& ip = catalogue("ip247", "module");
  DeviceErrorLatch latch;
  latch.raise(make_device_error(ip, 7, TimePoint{}));   // speed out of range: message
  latch.raise(make_device_error(ip, 28, TimePoint{}));  // SW limit start: stop
  EXPECT_TRUE(latch.blocks_motion());
  EXPECT_FALSE(latch.clear(ip, 28)) << "latched until acknowledged";
  EXPECT_TRUE(latch.clear(ip, 7));
  EXPECT_EQ(latch.active().size(), 1U);
  const auto& clm = catalogue("clm14", "diagnostic");
  latch.raise(make_device_error(clm, 0x10, TimePoint{}));
  EXPECT_EQ(latch.acknowledge(Acknowledgement::reset), 1U) << "28 goes, the power-cycle error stays";
  EXPECT_EQ(latch.acknowledge(Acknowledgement::power_cycle), 1U);
}

}  // namespace
}  // namespace hil::controllers
