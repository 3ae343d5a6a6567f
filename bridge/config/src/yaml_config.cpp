// SPDX-License-Identifier: MIT
#include "hil/config/yaml_config.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "hil/core/text_file.hpp"

namespace hil::yaml {

ConfigError error_at(const YAML::Node& node, const Where& where, std::string message) {
  ConfigError e;
  e.file = where.file;
  e.key = where.path;
  e.message = std::move(message);
  if (node.IsDefined()) {
    const auto m = node.Mark();
    if (m.line >= 0) e.line = m.line + 1;
    if (m.column >= 0) e.column = m.column + 1;
  }
  return e;
}

std::string unknown_key_message(std::string_view key, std::initializer_list<std::string_view> allowed) {
  std::string list;
  for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
  return fmt::format("unknown key '{}'; allowed here: {}", key, list);
}

std::expected<void, ConfigError> check_keys(const YAML::Node& node, const Where& where,
                                            std::initializer_list<std::string_view> allowed) {
  if (!node.IsMap()) return std::unexpected(error_at(node, where, "expected a map of keys"));
  std::vector<std::string> seen;
  for (const auto& kv : node) {
    const auto k = kv.first.as<std::string>("");
    bool ok = false;
    for (auto a : allowed) ok = ok || a == k;
    if (!ok) return std::unexpected(error_at(kv.first, where.key(k), unknown_key_message(k, allowed)));
    for (const auto& s : seen)
      if (s == k) return std::unexpected(error_at(kv.first, where.key(k), fmt::format("key '{}' appears twice", k)));
    seen.push_back(k);
  }
  return {};
}

namespace {

template <class T>
std::expected<std::optional<T>, ConfigError> get_scalar(const YAML::Node& node, const Where& where,
                                                        std::string_view key, const char* what) {
  if (!node.IsMap()) return std::optional<T>{};
  const auto v = node[std::string(key)];
  if (!v.IsDefined() || v.IsNull()) return std::optional<T>{};
  const auto here = where.key(key);
  if (!v.IsScalar()) return std::unexpected(error_at(v, here, fmt::format("expected {}", what)));
  try {
    T out = v.as<T>();
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(out))
        return std::unexpected(error_at(v, here, fmt::format("expected {} (a finite number)", what)));
    }
    return std::optional<T>{out};
  } catch (const YAML::Exception&) {
    return std::unexpected(error_at(v, here, fmt::format("expected {}, got '{}'", what, v.Scalar())));
  }
}

}  // namespace

std::expected<std::optional<double>, ConfigError> get_double(const YAML::Node& n, const Where& w, std::string_view k) {
  return get_scalar<double>(n, w, k, "a number");
}
std::expected<std::optional<long long>, ConfigError> get_int(const YAML::Node& n, const Where& w, std::string_view k) {
  return get_scalar<long long>(n, w, k, "an integer");
}
std::expected<std::optional<bool>, ConfigError> get_bool(const YAML::Node& n, const Where& w, std::string_view k) {
  return get_scalar<bool>(n, w, k, "true or false");
}
std::expected<std::optional<std::string>, ConfigError> get_string(const YAML::Node& n, const Where& w,
                                                                  std::string_view k) {
  return get_scalar<std::string>(n, w, k, "a string");
}

std::expected<YAML::Node, ConfigError> load_string(const std::string& text, const std::string& name) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& ex) {
    ConfigError e;
    e.file = name;
    e.line = ex.mark.line >= 0 ? ex.mark.line + 1 : 0;
    e.column = ex.mark.column >= 0 ? ex.mark.column + 1 : 0;
    e.message = "YAML syntax error: " + ex.msg;
    return std::unexpected(e);
  }
}

std::expected<YAML::Node, ConfigError> load_file(const std::string& path) {
  auto text = read_text_file(path);
  if (!text) return std::unexpected(ConfigError{path, 0, 0, "", text.error()});
  return load_string(*text, path);
}

}  // namespace hil::yaml
