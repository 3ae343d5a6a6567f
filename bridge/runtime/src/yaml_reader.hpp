// SPDX-License-Identifier: MIT
#pragma once
// Checked access to a yaml-cpp tree for configuration loaders: every accessor knows the key path
// of its node and reports a ConfigError (file, line, column, key, what was expected) by throwing
// LoadFailure, which the loader's entry point turns into std::expected. Internal to the loader.

#include <cmath>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "hil/core/config_error.hpp"
#include "hil/runtime/scenario_loader.hpp"

namespace hil::runtime::detail {

struct LoadFailure {
  ConfigError error;
};

/// A node plus its key path and the mark to blame when it is missing.
class Field {
 public:
  Field(const std::string& file, YAML::Node node, std::string path, YAML::Mark mark)
      : file_(&file), node_(normalise(node)), path_(std::move(path)), mark_(mark) {}

  [[nodiscard]] const YAML::Node& node() const noexcept { return node_; }
  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  [[nodiscard]] bool present() const noexcept { return node_.IsDefined() && !node_.IsNull(); }
  [[nodiscard]] int line() const noexcept { return mark().line >= 0 ? mark().line + 1 : 0; }
  [[nodiscard]] YAML::Mark mark() const noexcept {
    if (node_.IsDefined()) {
      const YAML::Mark m = node_.Mark();
      if (m.line >= 0) return m;
    }
    return mark_;
  }

  [[noreturn]] void fail(std::string message) const {
    const YAML::Mark m = mark();
    throw LoadFailure{
        ConfigError{*file_, m.line >= 0 ? m.line + 1 : 0, m.column >= 0 ? m.column + 1 : 0, path_, std::move(message)}};
  }

  /// What the node is, for "got ..." in messages.
  [[nodiscard]] std::string describe() const {
    if (!node_.IsDefined() || node_.IsNull()) return "nothing";
    if (node_.IsMap()) return "a map";
    if (node_.IsSequence()) return "a list";
    std::string s = node_.Scalar();
    if (s.size() > 40) s = s.substr(0, 40) + "...";
    return fmt::format("'{}'", s);
  }

  [[nodiscard]] Field child(const std::string& key) const {
    const std::string p = path_.empty() ? key : path_ + "." + key;
    if (!present()) return Field(*file_, YAML::Node(YAML::NodeType::Undefined), p, mark());
    if (!node_.IsMap()) fail(fmt::format("expected a map, got {}", describe()));
    return Field(*file_, node_[key], p, mark());
  }
  [[nodiscard]] Field required(const std::string& key, std::string_view what) const {
    Field f = child(key);
    if (!f.present()) f.fail(fmt::format("missing key '{}' ({})", key, what));
    return f;
  }
  [[nodiscard]] std::vector<Field> items() const {
    if (!node_.IsSequence()) fail(fmt::format("expected a list, got {}", describe()));
    std::vector<Field> out;
    std::size_t i = 0;
    for (const auto& n : node_) out.emplace_back(*file_, n, fmt::format("{}[{}]", path_, i++), mark());
    return out;
  }

  /// Map with only `allowed` keys (unknown or duplicate keys are errors). Returns the keys present.
  std::vector<std::string> expect_map(std::initializer_list<std::string_view> allowed) const {
    if (!node_.IsMap()) fail(fmt::format("expected a map, got {}", describe()));
    std::vector<std::string> seen;
    for (const auto& kv : node_) {
      const Field key(*file_, kv.first, path_, mark());
      if (!kv.first.IsScalar()) key.fail("a map key must be a plain name");
      const std::string name = kv.first.Scalar();
      const std::string key_path = path_.empty() ? name : path_ + "." + name;
      const Field named(*file_, kv.first, key_path, mark());
      bool ok = false;
      for (auto a : allowed) ok = ok || a == name;
      if (!ok) {
        std::string list;
        for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        named.fail(fmt::format("unknown key '{}'; allowed here: {}", name, list));
      }
      for (const auto& s : seen)
        if (s == name) named.fail(fmt::format("key '{}' appears twice", name));
      seen.push_back(name);
    }
    return seen;
  }

  [[nodiscard]] std::string as_string(std::string_view what) const {
    if (!node_.IsScalar() || node_.Scalar().empty()) fail(fmt::format("expected {}, got {}", what, describe()));
    return node_.Scalar();
  }
  [[nodiscard]] double as_number(std::string_view what) const {
    if (!node_.IsScalar()) fail(fmt::format("expected {}, got {}", what, describe()));
    double v = 0.0;
    if (!YAML::convert<double>::decode(node_, v) || !std::isfinite(v))
      fail(fmt::format("expected {}, got {}", what, describe()));
    return v;
  }
  [[nodiscard]] double as_positive(std::string_view what) const {
    const double v = as_number(what);
    if (!(v > 0.0)) fail(fmt::format("expected {} (> 0), got {}", what, describe()));
    return v;
  }
  [[nodiscard]] double as_non_negative(std::string_view what) const {
    const double v = as_number(what);
    if (v < 0.0) fail(fmt::format("expected {} (>= 0), got {}", what, describe()));
    return v;
  }
  [[nodiscard]] bool as_bool() const {
    bool v = false;
    if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, v))
      fail(fmt::format("expected true or false, got {}", describe()));
    return v;
  }
  [[nodiscard]] Duration as_duration() const {
    if (!node_.IsScalar()) fail(fmt::format("expected a duration (seconds, or '250ms', '2s'), got {}", describe()));
    auto d = parse_duration(node_.Scalar());
    if (!d) fail(fmt::format("expected a duration (seconds, or '250ms', '2s'; 0 .. 10 days), got {}", describe()));
    return *d;
  }
  /// One of `names`; returns its index.
  [[nodiscard]] std::size_t as_enum(std::initializer_list<std::string_view> names) const {
    std::string list;
    for (auto n : names) list += (list.empty() ? "" : ", ") + std::string(n);
    if (!node_.IsScalar()) fail(fmt::format("expected one of: {}; got {}", list, describe()));
    std::size_t i = 0;
    for (auto n : names) {
      if (n == node_.Scalar()) return i;
      ++i;
    }
    fail(fmt::format("expected one of: {}; got {}", list, describe()));
  }

  [[nodiscard]] std::optional<double> optional_number(const std::string& key, std::string_view what) const {
    Field f = child(key);
    if (!f.present()) return std::nullopt;
    return f.as_number(what);
  }
  [[nodiscard]] std::optional<double> optional_positive(const std::string& key, std::string_view what) const {
    Field f = child(key);
    if (!f.present()) return std::nullopt;
    return f.as_positive(what);
  }
  [[nodiscard]] std::optional<Duration> optional_duration(const std::string& key) const {
    Field f = child(key);
    if (!f.present()) return std::nullopt;
    return f.as_duration();
  }

 private:
  /// A missing key yields an invalid ("zombie") node on which most calls throw; replace it by
  /// an undefined node. (Never assign to a yaml-cpp Node: assignment writes through.)
  static YAML::Node normalise(const YAML::Node& n) { return n.IsDefined() ? n : YAML::Node(YAML::NodeType::Undefined); }

  const std::string* file_;
  YAML::Node node_;
  std::string path_;
  YAML::Mark mark_;
};

}  // namespace hil::runtime::detail
