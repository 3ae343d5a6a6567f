// SPDX-License-Identifier: MIT
// Fuzz the stepdir drive configuration: any YAML either parses into a valid configuration or
// yields a ConfigError; never a crash or an escaping exception.
#include <cstdint>
#include <cstdlib>
#include <string>

#include <yaml-cpp/yaml.h>

#include "hil/drives/stepdir/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  YAML::Node node;
  try {
    node = YAML::Load(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const YAML::Exception&) {
    return 0;  // not YAML: the loader reports it before we are called
  }
  if (!node.IsMap()) return 0;
  auto cfg = hil::drives::stepdir::parse_stepdir_config(node, hil::yaml::Where{"fuzz.yaml", "drive"});
  if (!cfg && cfg.error().message.empty()) std::abort();
  if (cfg && cfg->timing.min_period_ns() <= 0) std::abort();
  return 0;
}
