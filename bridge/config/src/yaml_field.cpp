// SPDX-License-Identifier: MIT
#include "hil/config/yaml_field.hpp"

#include <cmath>

#include <fmt/format.h>

#include "hil/core/duration_text.hpp"

namespace hil::yaml {

YAML::Mark Field::mark() const noexcept {
  if (node_.IsDefined()) {
    const YAML::Mark m = node_.Mark();
    if (m.line >= 0) return m;
  }
  return fallback_;
}

ConfigError Field::error(std::string message) const {
  ConfigError e = error_at(node_, where_, std::move(message));
  if (!node_.IsDefined() || node_.Mark().line < 0) {  // missing: blame the parent's position
    e.line = fallback_.line >= 0 ? fallback_.line + 1 : 0;
    e.column = fallback_.column >= 0 ? fallback_.column + 1 : 0;
  }
  return e;
}

std::string Field::describe() const {
  if (!node_.IsDefined() || node_.IsNull()) return "nothing";
  if (node_.IsMap()) return "a map";
  if (node_.IsSequence()) return "a list";
  std::string s = node_.Scalar();
  if (s.size() > 40) s = s.substr(0, 40) + "...";
  return fmt::format("'{}'", s);
}

Field Field::child(const std::string& key) const {
  if (!present()) return Field(YAML::Node(YAML::NodeType::Undefined), where_.key(key), mark());
  if (!node_.IsMap()) fail(fmt::format("expected a map, got {}", describe()));
  return Field(node_[key], where_.key(key), mark());
}

Field Field::required(const std::string& key, std::string_view what) const {
  Field f = child(key);
  if (!f.present()) f.fail(fmt::format("missing key '{}' ({})", key, what));
  return f;
}

std::vector<Field> Field::items() const {
  if (!node_.IsSequence()) fail(fmt::format("expected a list, got {}", describe()));
  std::vector<Field> out;
  std::size_t i = 0;
  for (const auto& n : node_) out.emplace_back(n, where_.index(i++), mark());
  return out;
}

std::vector<std::string> Field::expect_map(std::initializer_list<std::string_view> allowed) const {
  if (!node_.IsMap()) fail(fmt::format("expected a map, got {}", describe()));
  std::vector<std::string> seen;
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar()) Field(kv.first, where_, mark()).fail("a map key must be a plain name");
    const std::string name = kv.first.Scalar();
    const Field named(kv.first, where_.key(name), mark());
    bool ok = false;
    for (auto a : allowed) ok = ok || a == name;
    if (!ok) named.fail(unknown_key_message(name, allowed));
    for (const auto& s : seen)
      if (s == name) named.fail(fmt::format("key '{}' appears twice", name));
    seen.push_back(name);
  }
  return seen;
}

std::string Field::as_string(std::string_view what) const {
  if (!node_.IsScalar() || node_.Scalar().empty()) fail(fmt::format("expected {}, got {}", what, describe()));
  return node_.Scalar();
}

double Field::as_number(std::string_view what) const {
  if (!node_.IsScalar()) fail(fmt::format("expected {}, got {}", what, describe()));
  double v = 0.0;
  if (!YAML::convert<double>::decode(node_, v) || !std::isfinite(v))
    fail(fmt::format("expected {}, got {}", what, describe()));
  return v;
}

double Field::as_positive(std::string_view what) const {
  const double v = as_number(what);
  if (!(v > 0.0)) fail(fmt::format("expected {} (> 0), got {}", what, describe()));
  return v;
}

double Field::as_non_negative(std::string_view what) const {
  const double v = as_number(what);
  if (v < 0.0) fail(fmt::format("expected {} (>= 0), got {}", what, describe()));
  return v;
}

bool Field::as_bool() const {
  bool v = false;
  if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, v))
    fail(fmt::format("expected true or false, got {}", describe()));
  return v;
}

Duration Field::as_duration() const {
  if (!node_.IsScalar()) fail(fmt::format("expected a duration (seconds, or '250ms', '2s'), got {}", describe()));
  auto d = parse_duration_text(node_.Scalar(), "s");  // the one grammar of scenario files and the CLI
  if (!d) fail(fmt::format("expected a duration (seconds, or '250ms', '2s'; 0 .. 10 days), got {}", describe()));
  return *d;
}

std::size_t Field::as_enum(std::initializer_list<std::string_view> names) const {
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

std::optional<double> Field::optional_number(const std::string& key, std::string_view what) const {
  Field f = child(key);
  if (!f.present()) return std::nullopt;
  return f.as_number(what);
}

std::optional<double> Field::optional_positive(const std::string& key, std::string_view what) const {
  Field f = child(key);
  if (!f.present()) return std::nullopt;
  return f.as_positive(what);
}

std::optional<Duration> Field::optional_duration(const std::string& key) const {
  Field f = child(key);
  if (!f.present()) return std::nullopt;
  return f.as_duration();
}

}  // namespace hil::yaml
