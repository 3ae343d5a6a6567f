// SPDX-License-Identifier: MIT
#pragma once
// Reading a loaded parameter set the way the profile's rules read it (value or default, derived
// settings), for the axis mappings. Internal to hil::controller_runtime.

#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "hil/controllers/parameter_file.hpp"
#include "hil/core/config_error.hpp"
#include "hil/motion/ratio.hpp"
#include "hil/profiles/validation.hpp"

namespace hil::controllers::detail {

struct MappingFailure {
  ConfigError error;
};

class Params {
 public:
  explicit Params(const LoadedParameters& p) : p_(p), scope_(*p.profile, &p.set, {}) {}
  /// Number (value or default); throws MappingFailure naming the parameter when it has none.
  [[nodiscard]] long double number(std::string_view name) const {
    const auto v = scope_.lookup(name);
    if (v)
      if (const auto* d = std::get_if<long double>(&*v)) return *d;
    fail(name, "has no numeric value (set it in the parameter file)");
  }
  [[nodiscard]] std::optional<std::string> text(std::string_view name) const {
    const auto v = scope_.lookup(name);
    if (!v) return std::nullopt;
    if (const auto* s = std::get_if<std::string>(&*v)) return *s;
    return profiles::to_string(*v);
  }
  /// An exact integer parameter.
  [[nodiscard]] std::int64_t integer(std::string_view name) const {
    const long double v = number(name);
    if (v != std::floor(v)) fail(name, fmt::format("= {} must be a whole number here", static_cast<double>(v)));
    return static_cast<std::int64_t>(v);
  }
  [[noreturn]] void fail(std::string_view name, std::string message) const {
    const auto* e = p_.set.find(name.substr(0, name.find('.')));
    throw MappingFailure{
        ConfigError{p_.file.string(), e ? e->line : 0, 0, std::string(name), fmt::format("{} {}", name, message)}};
  }
  [[nodiscard]] const LoadedParameters& loaded() const noexcept { return p_; }

 private:
  const LoadedParameters& p_;
  profiles::Scope scope_;
};

/// num/den reduced; both > 0.
inline motion::Ratio reduced(std::int64_t num, std::int64_t den) {
  const std::int64_t g = std::gcd(num, den);
  return {num / g, den / g};
}

/// A decimal parameter value as an exact fraction value * 10^digits / 10^digits.
inline std::int64_t scaled(long double v, int digits) {
  return static_cast<std::int64_t>(std::llround(v * std::pow(10.0L, digits)));
}

}  // namespace hil::controllers::detail
