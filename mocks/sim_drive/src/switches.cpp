// SPDX-License-Identifier: MIT
#include "hil/mocks/switches.hpp"

#include <cmath>

#include <fmt/format.h>

#include "hil/core/drive.hpp"

namespace hil::mocks {

std::uint32_t PlantSwitches::inputs(double position_inc) const noexcept {
  std::uint32_t bits = 0;
  if (negative_inc && position_inc <= *negative_inc) bits |= digital_input::negative_limit;
  if (positive_inc && position_inc >= *positive_inc) bits |= digital_input::positive_limit;
  if (home && position_inc >= home->from_inc && position_inc <= home->to_inc) bits |= digital_input::home_switch;
  return bits;
}

std::expected<PlantSwitches, ConfigError> parse_switches(const YAML::Node& node, const yaml::Where& where) {
  PlantSwitches s;
  if (!node.IsMap())
    return std::unexpected(yaml::error_at(
        node, where,
        "expected a map of switch positions in increments: {negative: -500, positive: 9500, home: [1000, 1200]}"));
  if (auto k = yaml::check_keys(node, where, {"negative", "positive", "home"}); !k) return std::unexpected(k.error());
  constexpr double k_max = 1e15;
  auto position = [&](std::string_view key, std::optional<double>& out) -> std::expected<void, ConfigError> {
    auto v = yaml::get_double(node, where, key);
    if (!v) return std::unexpected(v.error());
    if (!v->has_value()) return {};
    if (!std::isfinite(**v) || std::fabs(**v) > k_max)
      return std::unexpected(yaml::error_at(node[std::string(key)], where.key(key),
                                            fmt::format("must be a position in [-1e15, 1e15] inc, got {}", **v)));
    out = **v;
    return {};
  };
  if (auto r = position("negative", s.negative_inc); !r) return std::unexpected(r.error());
  if (auto r = position("positive", s.positive_inc); !r) return std::unexpected(r.error());
  if (const auto home = node["home"]) {
    const auto at = where.key("home");
    auto bad = [&](std::string what) { return std::unexpected(yaml::error_at(home, at, std::move(what))); };
    if (!home.IsSequence() || home.size() != 2)
      return bad("the home cam is two positions [from, to] in increments, e.g. home: [1000, 1200]");
    double ends[2] = {};
    for (std::size_t i = 0; i < 2; ++i) {
      try {
        ends[i] = home[i].as<double>();
      } catch (const YAML::Exception&) {
        return bad(fmt::format("'{}' is not a number", home[i].IsScalar() ? home[i].Scalar() : std::string("?")));
      }
      if (!std::isfinite(ends[i]) || std::fabs(ends[i]) > k_max)
        return bad(fmt::format("must be positions in [-1e15, 1e15] inc, got {}", ends[i]));
    }
    if (ends[0] > ends[1]) return bad(fmt::format("the cam's start {} is after its end {}", ends[0], ends[1]));
    s.home = HomeCam{ends[0], ends[1]};
  }
  if (s.negative_inc && s.positive_inc && *s.negative_inc >= *s.positive_inc)
    return std::unexpected(yaml::error_at(
        node["negative"], where.key("negative"),
        fmt::format("the negative limit {} must lie below the positive limit {}", *s.negative_inc, *s.positive_inc)));
  return s;
}

}  // namespace hil::mocks
