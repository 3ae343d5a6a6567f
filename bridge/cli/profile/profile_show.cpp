// SPDX-License-Identifier: MIT
#include <fmt/format.h>

#include "hil/profiles/wire.hpp"
#include "profile_cli.hpp"

namespace hil::cli::profile {
namespace hp = hil::profiles;
namespace {

std::string range_text(const hp::FieldSpec& f) {
  std::string s;
  for (const auto& r : f.ranges) {
    std::string one;
    if (r.min.is_set() || r.max.is_set())
      one = fmt::format("{}..{}", r.min.is_set() ? r.min.text() : "", r.max.is_set() ? r.max.text() : "");
    if (!r.allowed.empty()) {
      std::string list;
      for (const auto& a : r.allowed) list += (list.empty() ? "" : ", ") + a.to_string();
      one += (one.empty() ? "" : " or ") + std::string("{") + list + "}";
    }
    if (!r.when.empty()) one += fmt::format(" when {}", r.when.text());
    s += (s.empty() ? "" : "; ") + one;
  }
  return s;
}

std::string field_format(const hp::FieldSpec& f, hp::Encoding enc) {
  switch (f.type) {
    case hp::FieldType::io_address: {
      std::string t;
      for (const auto& x : f.io_types) t += x;
      return fmt::format("I/O address ({}x.yy.z or 00.00.0)", t);
    }
    case hp::FieldType::hex:
      return fmt::format("{} hex digits", f.hex_digits);
    case hp::FieldType::reserved:
      return f.fixed_text.empty() ? "reserved (empty)" : "reserved \"" + f.fixed_text + "\"";
    case hp::FieldType::bits:
      return fmt::format("{}-bit field{}", f.bits.bits, f.binary_text ? " (binary digits)" : "");
    default:
      break;
  }
  if (enc == hp::Encoding::text) return "text " + f.text.to_string();
  std::string s(hp::to_string(enc));
  if (f.word >= 0) s += fmt::format(" at word {}", f.word);
  if (f.fixed.lsb_num != 1 || f.fixed.lsb_den != 1)
    s += fmt::format(", lsb {}{}", f.fixed.lsb_num, f.fixed.lsb_den != 1 ? "/" + std::to_string(f.fixed.lsb_den) : "");
  return s;
}

}  // namespace

void print_overview(const hp::Profile& p) {
  fmt::print("{} — {}\n", p.device, p.title);
  if (!p.manual.empty()) fmt::print("manual: {}\n", p.manual);
  if (!p.description.empty()) fmt::print("\n{}\n", p.description);
  fmt::print("\nparameter-set format: {}   profile: {}\n", p.text_format, p.source_file);
  if (!p.settings.empty()) {
    fmt::print("\nsettings (--set name=value):\n");
    for (const auto& s : p.settings) {
      std::string vals;
      for (const auto& v : s.values) vals += (vals.empty() ? "" : ", ") + hp::to_string(v);
      fmt::print("  {:<18} {}{}{}{}\n", s.name, s.meaning, vals.empty() ? "" : " [" + vals + "]",
                 s.default_value ? " default " + hp::to_string(*s.default_value) : "",
                 s.from.empty() ? "" : " (derived: " + s.from.text() + ")");
    }
  }
  fmt::print("\nparameters:\n");
  for (const auto& spec : p.parameters) {
    std::string ids = spec.id;
    if (!spec.instances.empty())
      ids += fmt::format(" ({}…{})", spec.concrete_id(spec.instances.front()), spec.concrete_id(spec.instances.back()));
    const auto& v = spec.variants.front();
    std::string unit;
    for (const auto& f : v.fields)
      if (!f.unit.empty()) unit += (unit.empty() ? "" : ", ") + f.unit;
    fmt::print("  {:<22} {}{}{}\n", ids, v.name.empty() ? "-" : v.name, unit.empty() ? "" : " [" + unit + "]",
               spec.variants.size() > 1 ? fmt::format(" ({} variants)", spec.variants.size()) : "");
  }
  if (!p.constraints.empty()) {
    fmt::print("\nrules:\n");
    for (const auto& c : p.constraints)
      fmt::print("  {:<32} {}{}\n", c.id, c.rule.text(), c.when.empty() ? "" : "  when " + c.when.text());
  }
  fmt::print("\nerror catalogues (profile show {} --errors NAME):\n", p.device);
  for (const auto& c : p.catalogues) fmt::print("  {:<18} {} codes  {}\n", c->id(), c->entries().size(), c->title());
  if (!p.decisions.empty()) {
    fmt::print("\ndecisions where the manual is unclear:\n");
    for (const auto& d : p.decisions)
      fmt::print("  - {}: {}{}\n", d.topic, d.choice,
                 d.configurable.empty() ? "" : " (configurable: " + d.configurable + ")");
  }
  if (!p.tables.empty()) {
    fmt::print("\ndata tables:");
    for (const auto& [name, rows] : p.tables) fmt::print(" {} ({})", name, rows.size());
    fmt::print("\n");
  }
}

void print_parameter(const hp::Profile& p, const hp::ParamRef& ref) {
  const auto& spec = *ref.spec;
  fmt::print("{} ({}{}, group {})\n", ref.id(), spec.id,
             ref.instance ? fmt::format(", {} {}", spec.instance_key, *ref.instance) : "",
             spec.group.empty() ? "-" : spec.group);
  if (!spec.aliases.empty()) {
    std::string a;
    for (const auto& x : spec.aliases) a += (a.empty() ? "" : ", ") + x;
    fmt::print("aliases: {}\n", a);
  }
  if (!spec.source.empty()) fmt::print("source: {}\n", spec.source);
  if (!spec.required.empty())
    fmt::print("required: {}\n", spec.required.text() == "1" ? "yes" : "when " + spec.required.text());
  for (std::size_t i = 0; i < spec.variants.size(); ++i) {
    const auto& v = spec.variants[i];
    fmt::print("\n{}{}\n", spec.variants.size() > 1 ? fmt::format("variant {}: ", i + 1) : "",
               v.when.empty() ? (spec.variants.size() > 1 ? "(otherwise)" : "") : "when " + v.when.text());
    fmt::print("  name:         {}\n", v.name);
    if (!v.meaning.empty()) fmt::print("  meaning:      {}\n", v.meaning);
    fmt::print("  takes effect: {}\n  protection:   {}\n", hp::to_string(v.takes_effect), hp::to_string(v.protection));
    if (!v.note.empty()) fmt::print("  note:         {}\n", v.note);
    for (const auto& f : v.fields) {
      const auto enc = f.encoding.value_or(p.wire.encoding);
      fmt::print("  field {}:\n    wire:    {}\n", f.name, field_format(f, enc));
      if (!f.meaning.empty()) fmt::print("    meaning: {}\n", f.meaning);
      if (!f.unit.empty()) fmt::print("    unit:    {}\n", f.unit);
      if (const auto r = range_text(f); !r.empty()) fmt::print("    range:   {}\n", r);
      for (const auto& s : f.steps)
        fmt::print("    step:    {}{}\n", s.step.text(), s.when.empty() ? "" : " when " + s.when.text());
      for (const auto& c : f.choices) fmt::print("    {:>6} = {}\n", c.value, c.meaning);
      for (const auto& b : f.bits.fields)
        fmt::print("    bit {}{}: {}{}\n", b.first, b.width > 1 ? fmt::format("..{}", b.first + b.width - 1) : "",
                   b.name, b.meaning.empty() ? "" : " — " + b.meaning);
      if (f.default_value) fmt::print("    default: {}\n", hp::to_string(*f.default_value));
      if (!f.note.empty()) fmt::print("    note:    {}\n", f.note);
    }
  }
  bool header = false;
  for (const auto* c : rules_of(p, ref)) {
    if (!header) fmt::print("\nrules:\n");
    header = true;
    fmt::print("  {}: {} — {}\n", c->id, c->rule.text(), c->message);
  }
}

std::vector<const hp::Constraint*> rules_of(const hp::Profile& p, const hp::ParamRef& ref) {
  const auto& spec = *ref.spec;
  std::string bare = spec.pattern;
  if (const auto at = bare.find('{'); at != std::string::npos) bare.erase(at, bare.find('}', at) - at + 1);
  std::vector<const hp::Constraint*> out;
  for (const auto& c : p.constraints)
    for (const auto& n : c.rule.names()) {
      const auto base = n.substr(0, n.find('.'));
      if (hp::normalise_id(base) == hp::normalise_id(spec.id) || hp::normalise_id(base) == hp::normalise_id(ref.id()) ||
          (!bare.empty() && hp::normalise_id(base) == hp::normalise_id(bare))) {
        out.push_back(&c);
        break;
      }
    }
  return out;
}

void print_catalogues(const hp::Profile& p, const std::string& which) {
  for (const auto& c : p.catalogues) {
    if (!which.empty() && which != c->id()) continue;
    fmt::print("{} — {} (std::error_category \"{}\")\n", c->id(), c->title(), c->category().name());
    for (const auto& e : c->entries()) {
      fmt::print("  {:>5}  {}{}\n", e.code_text, e.text, e.text_de.empty() ? "" : "  [" + e.text_de + "]");
      if (!e.cause.empty()) fmt::print("         cause:  {}\n", e.cause);
      if (!e.remedy.empty()) fmt::print("         remedy: {}\n", e.remedy);
      fmt::print("         reaction: {}; acknowledge: {}\n", hp::to_string(e.reaction), e.acknowledge);
    }
    fmt::print("\n");
  }
}

}  // namespace hil::cli::profile
