// SPDX-License-Identifier: MIT
#pragma once
// Reading YAML configuration with errors that name file, line, column and key path.
// Every loader (scenarios, drive blocks, profiles) uses these so errors look the same everywhere.

#include <expected>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include <yaml-cpp/yaml.h>

#include "hil/core/config_error.hpp"

namespace hil::yaml {

/// Where we are in a document: the file and the dotted key path of the current node.
struct Where {
  std::string file;
  std::string path;  ///< "axes[2].drive"
  [[nodiscard]] Where key(std::string_view k) const {
    return {file, path.empty() ? std::string(k) : path + "." + std::string(k)};
  }
  [[nodiscard]] Where index(std::size_t i) const { return {file, path + "[" + std::to_string(i) + "]"}; }
};

/// Error located at `node` (its line/column when yaml-cpp knows it).
[[nodiscard]] ConfigError error_at(const YAML::Node& node, const Where& where, std::string message);

/// The one message for a key that is not allowed, in every loader:
/// "unknown key 'kvv'; allowed here: kv, lag".
[[nodiscard]] std::string unknown_key_message(std::string_view key, std::initializer_list<std::string_view> allowed);

/// Every key of map `node` must be one of `allowed` and appear once; the first unknown key is an
/// error that lists the allowed ones (typos must not be silently ignored).
[[nodiscard]] std::expected<void, ConfigError> check_keys(const YAML::Node& node, const Where& where,
                                                          std::initializer_list<std::string_view> allowed);

/// Typed scalar at `node[key]`; `std::nullopt` inside the expected when the key is absent.
[[nodiscard]] std::expected<std::optional<double>, ConfigError> get_double(const YAML::Node& node, const Where& where,
                                                                           std::string_view key);
[[nodiscard]] std::expected<std::optional<long long>, ConfigError> get_int(const YAML::Node& node, const Where& where,
                                                                           std::string_view key);
[[nodiscard]] std::expected<std::optional<bool>, ConfigError> get_bool(const YAML::Node& node, const Where& where,
                                                                       std::string_view key);
[[nodiscard]] std::expected<std::optional<std::string>, ConfigError> get_string(const YAML::Node& node,
                                                                                const Where& where,
                                                                                std::string_view key);

/// Load a file; a syntax error becomes a ConfigError with yaml-cpp's line and column.
[[nodiscard]] std::expected<YAML::Node, ConfigError> load_file(const std::string& path);
[[nodiscard]] std::expected<YAML::Node, ConfigError> load_string(const std::string& text, const std::string& name);

}  // namespace hil::yaml
