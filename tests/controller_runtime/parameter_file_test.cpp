// SPDX-License-Identifier: MIT
// Parameter files in the devices' own formats through the profile engine, and the controller
// registry's errors.
#include <gtest/gtest.h>

#include "hil/controllers/controller_registry.hpp"
#include "hil/controllers/parameter_file.hpp"

namespace hil::controllers {
namespace {

TEST(ParameterFile, LoadsTheShippedDeviceFiles) {
  const auto ip = load_parameter_file("ip247", "examples/serial/ip247-md-db1.s5db");
  ASSERT_TRUE(ip) << ip.error().describe();
  EXPECT_EQ(ip->profile->device, "ip247");
  EXPECT_FALSE(ip->set.entries.empty());
  const auto clm = load_parameter_file("clm14", "examples/serial/clm14-parameters.par");
  ASSERT_TRUE(clm) << clm.error().describe();
  EXPECT_NE(clm->set.find("A101"), nullptr);
}

TEST(ParameterFile, ProblemsNameFileLineAndParameter) {
  const auto bad = load_parameter_text("wf725-726", "MD 19 = 1\nMD 20 = banana\n", "md.txt");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().file, "md.txt");
  EXPECT_EQ(bad.error().line, 2) << bad.error().describe();
  const auto missing = load_parameter_file("ip247", "no/such/file.s5db");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("cannot read"), std::string::npos);
  const auto unknown = load_parameter_text("no-such-device", "", "x");
  ASSERT_FALSE(unknown);
}

TEST(ControllerRegistry, UnknownDeviceListsTheKnownOnes) {
  ControllerRegistry r;
  r.add("wf725-726", [](const ControllerSpec& s) -> std::expected<std::unique_ptr<Controller>, ConfigError> {
    return std::unexpected(ConfigError{s.file, s.line, 0, "", "factory reached"});
  });
  EXPECT_TRUE(r.contains("wf725-726"));
  ControllerSpec spec;
  spec.device = "wf999";
  spec.file = "s.yaml";
  spec.line = 3;
  const auto e = r.create(spec);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().line, 3);
  EXPECT_NE(e.error().message.find("wf725-726"), std::string::npos) << e.error().message;
  spec.device = "wf725-726";
  EXPECT_EQ(r.create(spec).error().message, "factory reached");
  EXPECT_EQ(r.names(), std::vector<std::string>{"wf725-726"});
}

}  // namespace
}  // namespace hil::controllers
