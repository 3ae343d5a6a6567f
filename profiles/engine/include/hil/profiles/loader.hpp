// SPDX-License-Identifier: MIT
#pragma once
// Loading profiles from YAML. A profile file may `include:` further files (relative to itself)
// whose parameters, constraints, catalogues, settings, decisions and tables are appended.
//
// Search path for find_profile()/list_profiles(), first hit wins:
//   1. every directory in $HILBRIDGE_PROFILES (':'-separated),
//   2. <dir of the running executable>/../profiles/devices and <exe>/profiles/devices,
//   3. hil::data_dirs("profiles/devices"): <exe>/../share/hilbridge/profiles/devices (installed
//      tree), then the source tree's profiles/devices (baked in at compile time).

#include <expected>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hil/core/config_error.hpp"
#include "hil/profiles/profile.hpp"

namespace hil::profiles {

/// Loads and checks one profile file. Errors name file, line and key. Thread-safe (no shared state).
[[nodiscard]] std::expected<std::shared_ptr<const Profile>, hil::ConfigError> load_profile(
    const std::filesystem::path& file);
/// Loads from YAML text (for tests/fuzzing); `includes` are not followed.
[[nodiscard]] std::expected<std::shared_ptr<const Profile>, hil::ConfigError> load_profile_text(
    std::string_view yaml, std::string_view name = "<text>");

/// Directories searched, in order (existing ones only).
[[nodiscard]] std::vector<std::filesystem::path> profile_search_path();
/// Device names found ("amkasyn-sf", "clm14", …), sorted, each once.
[[nodiscard]] std::vector<std::string> list_profiles();
/// Finds and loads "<device>.yaml" on the search path. Loaded profiles are cached for the
/// process (so error categories stay unique and alive); thread-safe.
[[nodiscard]] std::expected<std::shared_ptr<const Profile>, hil::ConfigError> find_profile(std::string_view device);

}  // namespace hil::profiles
