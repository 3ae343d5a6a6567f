// SPDX-License-Identifier: MIT
#include "hil/profiles/validation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/profiles/wire.hpp"

namespace hil::profiles {
namespace {

ExprValue to_expr(const FieldValue& v) {
  if (const auto* d = std::get_if<Decimal>(&v)) return d->to_long_double();
  return std::get<std::string>(v);
}

std::optional<Decimal> bound_value(const Bound& b, const Scope& scope, std::string* err) {
  if (b.literal) return b.literal;
  if (b.expr.empty()) return std::nullopt;
  auto v = b.expr.evaluate(scope.as_lookup());
  if (!v) {
    if (err && !v.error().undefined) *err = v.error().message;
    return std::nullopt;
  }
  if (const auto* d = std::get_if<long double>(&*v)) {
    // Bounds computed from other values: keep 9 decimals (enough for every manual's units).
    const long double scaled = std::round(*d * 1e9L);
    if (std::fabs(scaled) > 9.0e18L) return std::nullopt;
    return Decimal{static_cast<std::int64_t>(scaled), 9};
  }
  if (err) *err = fmt::format("bound '{}' is not a number", b.expr.text());
  return std::nullopt;
}

bool holds(const Expression& when, const Scope& scope) {
  if (when.empty()) return true;
  auto r = when.test(scope.as_lookup());
  return r && *r;
}

std::string field_label(const ParamVariant& v, const FieldSpec& f) {
  return v.fields.size() > 1 ? f.name : std::string();
}

}  // namespace

Scope::Scope(const Profile& profile, const ParameterSet* set, const Settings& settings,
             std::optional<std::int64_t> instance, std::string instance_key)
    : profile_(&profile),
      set_(set),
      settings_(std::make_shared<const Settings>(settings)),
      instance_(instance),
      instance_key_(std::move(instance_key)) {}

Scope Scope::with_instance(std::int64_t v, std::string key) const {
  Scope s(*this);
  s.instance_ = v;
  s.instance_key_ = std::move(key);
  s.depth_ = 0;
  return s;
}

Expression::Lookup Scope::as_lookup() const {
  return [this](std::string_view n) { return lookup(n); };
}

std::optional<ExprValue> Scope::lookup(std::string_view name) const {
  if (depth_ > 16) return std::nullopt;
  if (instance_ && name == instance_key_) return static_cast<long double>(*instance_);
  // settings: user-given, then derived, then default
  if (const auto* s = profile_->setting(name)) {
    if (auto it = settings_->find(name); it != settings_->end()) return it->second;
    if (!s->from.empty()) {
      ++depth_;
      auto v = s->from.evaluate(as_lookup());
      --depth_;
      if (v) return *v;
    }
    return s->default_value;
  }
  if (auto it = settings_->find(name); it != settings_->end()) return it->second;
  // parameters: "<id>" or "<id>.<field>"; template ids resolve with the current instance
  std::string_view id = name, field;
  if (const auto dot = name.find('.'); dot != std::string_view::npos) {
    id = name.substr(0, dot);
    field = name.substr(dot + 1);
  }
  auto ref = profile_->resolve(id);
  if (!ref) {
    // a template id ("Ax06", "MD204*") or its pattern without the placeholder ("MD204") names the
    // parameter of the instance in scope
    if (instance_)
      if (const auto* t = profile_->resolve_template(id)) ref = ParamRef{t, *instance_};
  }
  if (!ref) return std::nullopt;
  ++depth_;
  const ParamVariant* v = select_variant(*ref, *this);
  --depth_;
  if (!v) v = &ref->spec->variants.front();
  std::size_t idx = 0;
  const BitDef* bit = nullptr;  // "<id>.<bit group>" of a bit-field parameter
  if (!field.empty()) {
    bool found = false;
    for (std::size_t i = 0; i < v->fields.size() && !found; ++i) {
      if (v->fields[i].name == field) {
        idx = i;
        found = true;
      } else if (v->fields[i].type == FieldType::bits) {
        for (const auto& b : v->fields[i].bits.fields)
          if (b.name == field) {
            idx = i;
            bit = &b;
            found = true;
          }
      }
    }
    if (!found) return std::nullopt;
  }
  const auto extract = [bit](ExprValue value) -> ExprValue {
    if (!bit) return value;
    const auto* d = std::get_if<long double>(&value);
    if (!d || *d < 0) return value;
    const auto w = static_cast<unsigned long long>(*d);
    const unsigned long long mask = bit->width >= 64 ? ~0ULL : ((1ULL << bit->width) - 1);
    return static_cast<long double>((w >> bit->first) & mask);
  };
  if (set_) {
    if (const auto* e = set_->find(ref->id()); e && idx < e->value.size()) return extract(to_expr(e->value[idx]));
  }
  if (idx < v->fields.size() && v->fields[idx].default_value) return extract(to_expr(*v->fields[idx].default_value));
  return std::nullopt;
}

const ParamVariant* select_variant(const ParamRef& ref, const Scope& scope) {
  if (!ref.spec) return nullptr;
  const Scope s = ref.instance ? scope.with_instance(*ref.instance, ref.spec->instance_key) : scope;
  for (const auto& v : ref.spec->variants) {
    if (v.when.empty()) return &v;
    auto r = v.when.test(s.as_lookup());
    if (r && *r) return &v;
  }
  return nullptr;
}

std::vector<Problem> check_field(const ParamRef& ref, const FieldSpec& f, const FieldValue& value,
                                 const Scope& scope0) {
  std::vector<Problem> out;
  const Scope scope = ref.instance ? scope0.with_instance(*ref.instance, ref.spec->instance_key) : scope0;
  const auto problem = [&](std::string rule, std::string message) {
    out.push_back(Problem{0, ref.id(), f.name, to_string(value), std::move(rule), std::move(message)});
  };
  if (f.type == FieldType::io_address) {
    const auto* s = std::get_if<std::string>(&value);
    if (!s) {
      problem("I/O address", "expected an I/O address");
      return out;
    }
    if (*s != "00.00.0" && std::find(f.io_types.begin(), f.io_types.end(), s->substr(0, 1)) == f.io_types.end()) {
      std::string allowed;
      for (const auto& t : f.io_types) allowed += (allowed.empty() ? "" : "/") + t;
      problem(fmt::format("I/O type {} or 00.00.0", allowed),
              fmt::format("{} must be an {} address", f.meaning.empty() ? f.name : f.meaning, allowed));
    }
    return out;
  }
  if (f.type == FieldType::reserved) return out;
  const auto* d = std::get_if<Decimal>(&value);
  if (!d) {
    problem("number", "expected a number");
    return out;
  }
  if (f.type == FieldType::choice && !f.choices.empty()) {
    bool ok = false;
    std::string list;
    for (const auto& c : f.choices) {
      if (Decimal{c.value, 0} == *d) ok = true;
      list += (list.empty() ? "" : ", ") + std::to_string(c.value);
    }
    if (!ok) problem(fmt::format("one of {}", list), fmt::format("{} is not a defined choice", d->to_string()));
  }
  if (f.type == FieldType::bits) {
    if (auto b = parse_bit_field(static_cast<std::uint64_t>(std::max<std::int64_t>(d->units, 0)), f.bits);
        !b || d->units < 0)
      problem("defined bits only", b ? "negative bit field" : b.error().message);
  }
  // text template capacity (text encodings): the value must fit the field
  if ((f.type == FieldType::number || f.type == FieldType::choice) &&
      f.encoding.value_or(Encoding::text) == Encoding::text) {
    if (auto t = make_decimal_text(*d, f.text); !t)
      problem(fmt::format("field {}", f.text.to_string()), t.error().message);
  }
  for (const auto& r : f.ranges) {
    if (!holds(r.when, scope)) continue;
    std::string err;
    const auto lo = bound_value(r.min, scope, &err);
    const auto hi = bound_value(r.max, scope, &err);
    if (!err.empty()) problem("range", fmt::format("range bound cannot be evaluated: {}", err));
    const bool interval = r.min.is_set() || r.max.is_set();
    bool in_interval = (!lo || *d >= *lo) && (!hi || *d <= *hi);
    bool in_list = false;
    for (const auto& a : r.allowed)
      if (a == *d) in_list = true;
    const bool ok = (interval && in_interval) || in_list || (!interval && r.allowed.empty());
    if (!ok) {
      std::string rule;
      if (interval)
        rule = fmt::format("range {}..{}", r.min.is_set() ? r.min.text() : "", r.max.is_set() ? r.max.text() : "");
      if (!r.allowed.empty()) {
        std::string list;
        for (const auto& a : r.allowed) list += (list.empty() ? "" : ", ") + a.to_string();
        rule += (rule.empty() ? "" : " or ") + std::string("one of ") + list;
      }
      if (!r.when.empty()) rule += fmt::format(" (when {})", r.when.text());
      std::string computed;
      if (r.min.expr.empty() == false && lo) computed += fmt::format(" min = {}", lo->to_string());
      if (r.max.expr.empty() == false && hi) computed += fmt::format(" max = {}", hi->to_string());
      problem(rule, fmt::format("{} {} is out of range{}", f.meaning.empty() ? f.name : f.meaning, d->to_string(),
                                computed.empty() ? "" : ";" + computed));
    }
    break;  // first applicable rule only
  }
  for (const auto& s : f.steps) {
    if (!holds(s.when, scope)) continue;
    std::string err;
    const auto step = bound_value(s.step, scope, &err);
    if (step && step->units > 0 && !d->is_multiple_of(*step))
      problem(fmt::format("step {}{}", s.step.text(), s.when.empty() ? "" : fmt::format(" (when {})", s.when.text())),
              fmt::format("{} is not a multiple of {}", d->to_string(), step->to_string()));
    break;
  }
  return out;
}

std::vector<Problem> validate(const Profile& profile, const ParameterSet& set, const Settings& settings) {
  std::vector<Problem> out;
  const Scope scope(profile, &set, settings);
  // settings given by the user must be allowed values
  for (const auto& [name, value] : settings) {
    const auto* s = profile.setting(name);
    if (!s) {
      out.push_back({0, "", "", to_string(value), "known setting",
                     fmt::format("'{}' is not a setting of {}", name, profile.device)});
      continue;
    }
    if (!s->values.empty() && std::none_of(s->values.begin(), s->values.end(),
                                           [&](const ExprValue& a) { return to_string(a) == to_string(value); })) {
      std::string list;
      for (const auto& a : s->values) list += (list.empty() ? "" : ", ") + to_string(a);
      out.push_back(
          {0, name, "", to_string(value), "one of " + list, fmt::format("setting {} must be one of {}", name, list)});
    }
  }
  for (const auto& e : set.entries) {
    if (!e.ref.spec) continue;
    const ParamVariant* v = select_variant(e.ref, scope);
    if (!v) {
      std::string conds;
      for (const auto& x : e.ref.spec->variants) conds += (conds.empty() ? "" : " | ") + x.when.text();
      out.push_back({e.line, e.ref.id(), "", e.text, "applies when " + conds,
                     fmt::format("{} does not exist for this configuration", e.ref.id())});
      continue;
    }
    // read-only data (service data, versions) is never written; `system` data may be carried in a
    // complete image (IP247 header words, WF MD 50) and is not an error.
    if (v->protection == Protection::read_only) {
      out.push_back({e.line, e.ref.id(), "", e.text, std::string("protection ") + std::string(to_string(v->protection)),
                     fmt::format("{} ({}) cannot be written", e.ref.id(), v->name)});
    }
    if (e.value.size() != v->fields.size()) {
      out.push_back(
          {e.line, e.ref.id(), "", e.text, fmt::format("{} field(s)", v->fields.size()),
           fmt::format("{} has {} field(s), the set gives {}", e.ref.id(), v->fields.size(), e.value.size())});
      continue;
    }
    for (std::size_t i = 0; i < v->fields.size(); ++i)
      for (auto p : check_field(e.ref, v->fields[i], e.value[i], scope)) {
        p.line = e.line;
        p.field = field_label(*v, v->fields[i]);
        out.push_back(std::move(p));
      }
  }
  // required parameters
  for (const auto& r : profile.all_refs()) {
    if (r.spec->required.empty() || set.find(r.id())) continue;
    const Scope s = r.instance ? scope.with_instance(*r.instance, r.spec->instance_key) : scope;
    auto need = r.spec->required.test(s.as_lookup());
    if (need && *need && select_variant(r, scope))
      out.push_back({0, r.id(), "", "",
                     "required" + (r.spec->required.text() == "1" ? std::string() : " when " + r.spec->required.text()),
                     fmt::format("{} ({}) is missing", r.id(), r.spec->variants.front().name)});
  }
  // cross-parameter constraints
  for (const auto& c : profile.constraints) {
    std::vector<std::optional<std::int64_t>> insts;
    if (c.instances.empty()) insts.push_back(std::nullopt);
    for (auto i : c.instances) insts.push_back(i);
    for (const auto& inst : insts) {
      const Scope s = inst ? scope.with_instance(*inst, c.for_each) : scope;
      if (!holds(c.when, s)) continue;
      auto r = c.rule.test(s.as_lookup());
      if (!r) {
        if (r.error().undefined) continue;  // a value is neither set nor defaulted: nothing to check
        out.push_back({0, c.id, "", "", c.rule.text(), "rule cannot be evaluated: " + r.error().message});
        continue;
      }
      if (*r) continue;
      // name every value the rule reads, and the line of the first one from the set
      std::string params, values;
      int line = 0;
      for (const auto& n : c.rule.names()) {
        auto v = s.lookup(n);
        std::string id(n);
        std::string shown = id;
        if (inst) {
          if (auto ref = profile.resolve(id.substr(0, id.find('.'))); !ref) {
            for (const auto& p : profile.parameters) {
              std::string bare = p.pattern;
              if (const auto at = bare.find('{'); at != std::string::npos) bare.erase(at, bare.find('}', at) - at + 1);
              const auto key = normalise_id(id.substr(0, id.find('.')));
              if (!p.instances.empty() && (normalise_id(p.id) == key || normalise_id(bare) == key)) {
                shown = p.concrete_id(*inst) + (id.find('.') != std::string::npos ? id.substr(id.find('.')) : "");
                if (const auto* e = set.find(p.concrete_id(*inst)); e && !line) line = e->line;
              }
            }
          }
        }
        if (auto ref = profile.resolve(id.substr(0, id.find('.')))) {
          if (const auto* e = set.find(ref->id()); e && !line) line = e->line;
        }
        if (id == c.for_each) continue;
        params += (params.empty() ? "" : ", ") + shown;
        values += (values.empty() ? "" : ", ") + shown + "=" + (v ? to_string(*v) : std::string("?"));
      }
      std::string rule = c.rule.text();
      if (inst) rule += fmt::format(" ({} {})", c.for_each, *inst);
      out.push_back(
          {line, params, "", values, rule, c.message.empty() ? "constraint " + c.id + " violated" : c.message});
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Problem& a, const Problem& b) {
    if ((a.line == 0) != (b.line == 0)) return a.line != 0;
    return a.line < b.line;
  });
  return out;
}

ParameterSet default_set(const Profile& profile, const Settings& settings) {
  ParameterSet set;
  set.device = profile.device;
  const Scope scope(profile, &set, settings);
  for (const auto& r : profile.all_refs()) {
    const ParamVariant* v = select_variant(r, scope);
    if (!v) continue;
    ParamValue value;
    bool complete = true;
    for (const auto& f : v->fields) {
      if (!f.default_value) {
        complete = false;
        break;
      }
      value.push_back(*f.default_value);
    }
    if (!complete) continue;
    SetEntry e;
    e.ref = r;
    e.text = value_text(*v, value);
    e.value = std::move(value);
    set.set(std::move(e));
  }
  return set;
}

}  // namespace hil::profiles
