// SPDX-License-Identifier: MIT
#pragma once
// A device parameter file (in the device's own format: CLM telegrams, WF MD list, S5 DB
// listing, SINUMERIK MD tape, AMK DB) loaded and validated by the profile engine.

#include <expected>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

#include "hil/core/config_error.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/profile.hpp"
#include "hil/profiles/settings.hpp"

namespace hil::controllers {

struct LoadedParameters {
  std::shared_ptr<const profiles::Profile> profile;
  profiles::ParameterSet set;
  std::filesystem::path file;
};

/// Finds `device`'s profile, reads `file`, parses it with the profile's parser and validates it
/// (hil::profiles::validate). The first problem becomes the ConfigError (file, line, parameter,
/// rule); the others are appended to its message, one per line. Blocking file I/O.
[[nodiscard]] std::expected<LoadedParameters, ConfigError> load_parameter_file(std::string_view device,
                                                                               const std::filesystem::path& file,
                                                                               const profiles::Settings& settings = {});

/// Same from text (tests); `name` stands for the file in messages.
[[nodiscard]] std::expected<LoadedParameters, ConfigError> load_parameter_text(std::string_view device,
                                                                               std::string_view text,
                                                                               std::string_view name,
                                                                               const profiles::Settings& settings = {});

}  // namespace hil::controllers
