// SPDX-License-Identifier: MIT
#pragma once
// Validation of a parameter set against its profile: every field's range and step (which may
// depend on settings such as the resolution), choices, I/O address types, required parameters,
// applicability of variant-dependent parameters, and every cross-parameter constraint. All
// violations are reported (never only the first), each with parameter, value and rule.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/profile.hpp"
#include "hil/profiles/settings.hpp"

namespace hil::profiles {

/// Value of a name as the rules see it: settings, "<id>" / "<id>.<field>" of the set (or the
/// default when absent), instance key. `instance` resolves template ids ("Ax06" → "A106").
class Scope {
 public:
  Scope(const Profile& profile, const ParameterSet* set, const Settings& settings,
        std::optional<std::int64_t> instance = std::nullopt, std::string instance_key = "");
  [[nodiscard]] std::optional<ExprValue> lookup(std::string_view name) const;
  [[nodiscard]] Expression::Lookup as_lookup() const;
  [[nodiscard]] Scope with_instance(std::int64_t v, std::string key) const;

 private:
  const Profile* profile_;
  const ParameterSet* set_;
  std::shared_ptr<const Settings> settings_;  // owned copy: a Scope may outlive the caller's map
  std::optional<std::int64_t> instance_;
  std::string instance_key_;
  mutable int depth_ = 0;  // guards against settings defined through each other
};

/// The variant of `ref` that applies in `scope`; nullptr when the parameter does not exist for this
/// module/encoder/control type.
[[nodiscard]] const ParamVariant* select_variant(const ParamRef& ref, const Scope& scope);

/// Checks one field value against its range/step/choices/type. Empty = fine.
[[nodiscard]] std::vector<Problem> check_field(const ParamRef& ref, const FieldSpec& field, const FieldValue& value,
                                               const Scope& scope);

/// Everything wrong with `set` (sorted by line, rules without line last).
[[nodiscard]] std::vector<Problem> validate(const Profile& profile, const ParameterSet& set,
                                            const Settings& settings = {});

/// A set holding every parameter's default (for CLM "CSETPA", emulator start-up).
[[nodiscard]] ParameterSet default_set(const Profile& profile, const Settings& settings = {});

}  // namespace hil::profiles
