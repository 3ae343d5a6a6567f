// SPDX-License-Identifier: MIT
#pragma once
// Shared fixture of the per-device profile tests: loads the device's profile and its
// parameter-set parser, reads test data, and finds problems by text.

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "hil/profiles/loader.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/validation.hpp"

namespace hil::profiles::testing {

/// A file below tests/profiles/data.
inline std::string read(const std::string& rel) {
  std::ifstream in(std::string(HIL_TEST_DATA) + "/" + rel);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class DeviceTest : public ::testing::Test {
 protected:
  explicit DeviceTest(std::string device) : device_(std::move(device)) {}

  void SetUp() override {
    auto p = find_profile(device_);
    ASSERT_TRUE(p) << p.error().describe();
    profile_ = *p;
    parser_ = make_parameter_set_parser(profile_);
    ASSERT_TRUE(parser_);
  }

  /// The parser's problems first, then those of validating the parsed set under `settings`.
  std::vector<Problem> problems_of(const ParseResult& r, const Settings& settings) const {
    auto v = validate(*profile_, r.set, settings);
    v.insert(v.begin(), r.problems.begin(), r.problems.end());
    return v;
  }

  /// Whether a problem mentions `text` in its parameter, rule or message.
  static bool has(const std::vector<Problem>& v, std::string_view text) {
    for (const auto& p : v)
      if ((p.param + " " + p.rule + " " + p.message).find(text) != std::string::npos) return true;
    return false;
  }

  std::shared_ptr<const Profile> profile_;
  std::unique_ptr<ParameterSetParser> parser_;

 private:
  std::string device_;
};

}  // namespace hil::profiles::testing
