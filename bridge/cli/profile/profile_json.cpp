// SPDX-License-Identifier: MIT
// `hilbridge profile show --json`: the same content as profile_show.cpp as JSON (docs/json.md).
// Decimal values stay text ("3000.0"): exact, as the device writes them.
#include <fmt/format.h>

#include "hil/profiles/wire.hpp"
#include "profile_cli.hpp"

namespace hil::cli::profile {
namespace hp = hil::profiles;
namespace {

nlohmann::json ranges_json(const hp::FieldSpec& f) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& r : f.ranges) {
    nlohmann::json j = nlohmann::json::object();
    j["min"] = r.min.is_set() ? nlohmann::json(r.min.text()) : nlohmann::json(nullptr);
    j["max"] = r.max.is_set() ? nlohmann::json(r.max.text()) : nlohmann::json(nullptr);
    nlohmann::json allowed = nlohmann::json::array();
    for (const auto& a : r.allowed) allowed.push_back(a.to_string());
    j["allowed"] = std::move(allowed);
    j["when"] = r.when.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.when.text());
    out.push_back(std::move(j));
  }
  return out;
}

nlohmann::json field_json(const hp::Profile& p, const hp::FieldSpec& f) {
  const auto enc = f.encoding.value_or(p.wire.encoding);
  nlohmann::json j{{"name", f.name},
                   {"encoding", std::string(hp::to_string(enc))},
                   {"meaning", f.meaning},
                   {"unit", f.unit},
                   {"ranges", ranges_json(f)},
                   {"default", f.default_value ? nlohmann::json(hp::to_string(*f.default_value)) : nullptr},
                   {"note", f.note}};
  nlohmann::json steps = nlohmann::json::array();
  for (const auto& s : f.steps)
    steps.push_back({{"step", s.step.text()}, {"when", s.when.empty() ? nullptr : nlohmann::json(s.when.text())}});
  j["steps"] = std::move(steps);
  nlohmann::json choices = nlohmann::json::array();
  for (const auto& c : f.choices) choices.push_back({{"value", c.value}, {"meaning", c.meaning}});
  j["choices"] = std::move(choices);
  nlohmann::json bits = nlohmann::json::array();
  for (const auto& b : f.bits.fields)
    bits.push_back({{"first", b.first}, {"width", b.width}, {"name", b.name}, {"meaning", b.meaning}});
  j["bits"] = std::move(bits);
  return j;
}

nlohmann::json entry_json(const hp::ErrorCatalogue& c, const hp::ErrorEntry& e) {
  return {{"catalogue", c.id()},
          {"code", e.code_text},
          {"text", e.text},
          {"text_de", e.text_de},
          {"cause", e.cause},
          {"remedy", e.remedy},
          {"reaction", std::string(hp::to_string(e.reaction))},
          {"acknowledge", e.acknowledge}};
}

}  // namespace

nlohmann::json overview_json(const hp::Profile& p) {
  nlohmann::json settings = nlohmann::json::array();
  for (const auto& s : p.settings) {
    nlohmann::json values = nlohmann::json::array();
    for (const auto& v : s.values) values.push_back(hp::to_string(v));
    settings.push_back({{"name", s.name},
                        {"meaning", s.meaning},
                        {"values", std::move(values)},
                        {"default", s.default_value ? nlohmann::json(hp::to_string(*s.default_value)) : nullptr},
                        {"derived_from", s.from.empty() ? nullptr : nlohmann::json(s.from.text())}});
  }
  nlohmann::json params = nlohmann::json::array();
  for (const auto& spec : p.parameters) {
    const auto& v = spec.variants.front();
    nlohmann::json units = nlohmann::json::array();
    for (const auto& f : v.fields)
      if (!f.unit.empty()) units.push_back(f.unit);
    params.push_back(
        {{"id", spec.id},
         {"first", spec.instances.empty() ? nullptr : nlohmann::json(spec.concrete_id(spec.instances.front()))},
         {"last", spec.instances.empty() ? nullptr : nlohmann::json(spec.concrete_id(spec.instances.back()))},
         {"name", v.name},
         {"units", std::move(units)},
         {"variants", spec.variants.size()}});
  }
  nlohmann::json rules = nlohmann::json::array();
  for (const auto& c : p.constraints)
    rules.push_back({{"id", c.id},
                     {"rule", c.rule.text()},
                     {"when", c.when.empty() ? nullptr : nlohmann::json(c.when.text())},
                     {"message", c.message}});
  nlohmann::json catalogues = nlohmann::json::array();
  for (const auto& c : p.catalogues)
    catalogues.push_back({{"id", c->id()}, {"title", c->title()}, {"codes", c->entries().size()}});
  nlohmann::json decisions = nlohmann::json::array();
  for (const auto& d : p.decisions)
    decisions.push_back({{"topic", d.topic}, {"choice", d.choice}, {"configurable", d.configurable}});
  nlohmann::json tables = nlohmann::json::object();
  for (const auto& [name, rows] : p.tables) tables[name] = rows.size();
  return {{"device", p.device},
          {"title", p.title},
          {"manual", p.manual},
          {"description", p.description},
          {"text_format", p.text_format},
          {"profile", p.source_file},
          {"settings", std::move(settings)},
          {"parameters", std::move(params)},
          {"rules", std::move(rules)},
          {"catalogues", std::move(catalogues)},
          {"decisions", std::move(decisions)},
          {"tables", std::move(tables)}};
}

nlohmann::json parameter_json(const hp::Profile& p, const hp::ParamRef& ref) {
  const auto& spec = *ref.spec;
  nlohmann::json variants = nlohmann::json::array();
  for (const auto& v : spec.variants) {
    nlohmann::json fields = nlohmann::json::array();
    for (const auto& f : v.fields) fields.push_back(field_json(p, f));
    variants.push_back({{"when", v.when.empty() ? nullptr : nlohmann::json(v.when.text())},
                        {"name", v.name},
                        {"meaning", v.meaning},
                        {"takes_effect", std::string(hp::to_string(v.takes_effect))},
                        {"protection", std::string(hp::to_string(v.protection))},
                        {"note", v.note},
                        {"fields", std::move(fields)}});
  }
  nlohmann::json rules = nlohmann::json::array();
  for (const auto* c : rules_of(p, ref))
    rules.push_back({{"id", c->id}, {"rule", c->rule.text()}, {"message", c->message}});
  return {{"device", p.device},
          {"id", ref.id()},
          {"spec", spec.id},
          {"instance", ref.instance ? nlohmann::json(*ref.instance) : nullptr},
          {"group", spec.group},
          {"aliases", spec.aliases},
          {"source", spec.source},
          {"required", spec.required.empty() ? nullptr : nlohmann::json(spec.required.text())},
          {"variants", std::move(variants)},
          {"rules", std::move(rules)}};
}

nlohmann::json catalogues_json(const hp::Profile& p, const std::string& which) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& c : p.catalogues) {
    if (!which.empty() && which != c->id()) continue;
    nlohmann::json entries = nlohmann::json::array();
    for (const auto& e : c->entries()) entries.push_back(entry_json(*c, e));
    out.push_back(
        {{"id", c->id()}, {"title", c->title()}, {"category", c->category().name()}, {"entries", std::move(entries)}});
  }
  return {{"device", p.device}, {"catalogues", std::move(out)}};
}

nlohmann::json error_codes_json(const hp::Profile& p, const std::string& code) {
  nlohmann::json matches = nlohmann::json::array();
  for (const auto& c : p.catalogues)
    if (auto n = c->parse_code(code); n && c->find(*n)) {
      auto j = entry_json(*c, *c->find(*n));
      j["category"] = c->category().name();
      matches.push_back(std::move(j));
    }
  return matches;
}

}  // namespace hil::cli::profile
