// SPDX-License-Identifier: MIT
#pragma once
// A cursor over a yaml-cpp tree for loaders that read a whole document (the scenario loader and
// its io_links and coupling parts): a node plus its Where (file and key path, as everywhere in
// hil::yaml) and the mark to blame when the node is missing. Every accessor checks what it reads
// and reports a ConfigError built by hil::yaml::error_at (file, line, column, key path, what was
// expected). Inside a loader a wrong value throws Failure, so that deep readers stay linear; the
// loader's entry point catches it and returns std::expected (read_document below), so no
// exception crosses a library boundary.

#include <cstddef>
#include <expected>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "hil/config/yaml_config.hpp"
#include "hil/core/clock.hpp"
#include "hil/core/config_error.hpp"

namespace hil::yaml {

/// What a Field throws; carries the located error to the loader's entry point.
struct Failure {
  ConfigError error;
};

class Field {
 public:
  /// `fallback` is blamed when `node` is missing (the parent's position).
  Field(const YAML::Node& node, Where where, YAML::Mark fallback)
      : node_(normalise(node)), where_(std::move(where)), fallback_(fallback) {}

  [[nodiscard]] const YAML::Node& node() const noexcept { return node_; }
  [[nodiscard]] const Where& where() const noexcept { return where_; }
  [[nodiscard]] const std::string& path() const noexcept { return where_.path; }
  [[nodiscard]] bool present() const noexcept { return node_.IsDefined() && !node_.IsNull(); }
  /// The node's position, or the fallback when yaml-cpp knows none (a missing key).
  [[nodiscard]] YAML::Mark mark() const noexcept;
  /// 1-based line of mark(); 0 when unknown.
  [[nodiscard]] int line() const noexcept { return mark().line >= 0 ? mark().line + 1 : 0; }

  /// The located error for this node (error_at, with the fallback position when missing).
  [[nodiscard]] ConfigError error(std::string message) const;
  [[noreturn]] void fail(std::string message) const { throw Failure{error(std::move(message))}; }

  /// What the node is, for "got ..." in messages: "nothing", "a map", "a list" or the quoted scalar.
  [[nodiscard]] std::string describe() const;

  /// `key` of this map (missing: an absent Field at the key's path; not a map: an error).
  [[nodiscard]] Field child(const std::string& key) const;
  /// Like child(), but a missing key is an error naming `what` belongs there.
  [[nodiscard]] Field required(const std::string& key, std::string_view what) const;
  /// The elements of this list, at paths "path[i]".
  [[nodiscard]] std::vector<Field> items() const;
  /// Map with only `allowed` keys (unknown or duplicate keys are errors). Returns the keys present.
  std::vector<std::string> expect_map(std::initializer_list<std::string_view> allowed) const;

  [[nodiscard]] std::string as_string(std::string_view what) const;   ///< non-empty scalar
  [[nodiscard]] double as_number(std::string_view what) const;        ///< finite
  [[nodiscard]] double as_positive(std::string_view what) const;      ///< > 0
  [[nodiscard]] double as_non_negative(std::string_view what) const;  ///< >= 0
  [[nodiscard]] bool as_bool() const;
  /// The duration grammar of hil/core/duration_text.hpp; a bare number is seconds.
  [[nodiscard]] Duration as_duration() const;
  /// One of `names`; returns its index.
  [[nodiscard]] std::size_t as_enum(std::initializer_list<std::string_view> names) const;

  [[nodiscard]] std::optional<double> optional_number(const std::string& key, std::string_view what) const;
  [[nodiscard]] std::optional<double> optional_positive(const std::string& key, std::string_view what) const;
  [[nodiscard]] std::optional<Duration> optional_duration(const std::string& key) const;

 private:
  /// A missing key yields an invalid ("zombie") node on which most calls throw; replace it by
  /// an undefined node. (Never assign to a yaml-cpp Node: assignment writes through.)
  static YAML::Node normalise(const YAML::Node& n) { return n.IsDefined() ? n : YAML::Node(YAML::NodeType::Undefined); }

  YAML::Node node_;
  Where where_;
  YAML::Mark fallback_;
};

/// The boundary of a Field-based loader: runs `read()` and returns its result, or the error of the
/// Failure it threw, or (defensively, for a yaml-cpp accessor a loader did not guard) a yaml-cpp
/// exception located in `file`.
template <class Read>
[[nodiscard]] auto read_document(const std::string& file, Read&& read)
    -> std::expected<decltype(std::forward<Read>(read)()), ConfigError> {
  try {
    return std::forward<Read>(read)();
  } catch (const Failure& f) {
    return std::unexpected(f.error);
  } catch (const YAML::Exception& e) {
    return std::unexpected(ConfigError{file, e.mark.line >= 0 ? e.mark.line + 1 : 0,
                                       e.mark.column >= 0 ? e.mark.column + 1 : 0, "", e.msg});
  }
}

}  // namespace hil::yaml
