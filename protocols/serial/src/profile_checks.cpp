// SPDX-License-Identifier: MIT
#include "hil/serial/profile_checks.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hil/profiles/loader.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/validation.hpp"
#include "hil/profiles/wire.hpp"

namespace hil::serial {

namespace pf = hil::profiles;

namespace {

std::expected<std::shared_ptr<const pf::Profile>, std::string> find_first(
    std::initializer_list<std::string_view> names) {
  std::string why;
  for (auto n : names) {
    auto p = pf::find_profile(n);
    if (p) return *p;
    why = p.error().describe();
  }
  return std::unexpected(fmt::format("no device profile {} found ({})", fmt::join(names, " / "), why));
}

/// Decode `wire` for `ref` and check every field; empty = fine.
std::vector<std::string> check_wire(const pf::Profile& p, const pf::ParamRef& ref, std::string_view wire) {
  const pf::Settings settings;
  const pf::Scope scope(p, nullptr, settings, ref.instance, ref.spec->instance_key);
  const auto* v = pf::select_variant(ref, scope);
  if (v == nullptr) return {fmt::format("{} does not apply to this device variant", ref.id())};
  auto value = pf::decode_wire(p, *v, wire);
  if (!value) return {fmt::format("{} = {}: {}", ref.id(), wire, value.error())};
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v->fields.size() && i < value->size(); ++i)
    for (const auto& prob : pf::check_field(ref, v->fields[i], (*value)[i], scope)) out.push_back(prob.describe());
  return out;
}

}  // namespace

std::expected<ElgCheck, std::string> load_elg_check() {
  auto p = find_first({"sinumerik-elg", "elg"});
  if (!p) return std::unexpected(p.error());
  return ElgCheck(
      [prof = *p](tape::ElgSectionKind k, int number, const std::string& value) -> std::optional<std::string> {
        const std::string id = fmt::format("{}{}", k == tape::ElgSectionKind::machine_data ? "MD" : "SD", number);
        auto ref = prof->resolve(id);
        if (!ref)
          return fmt::format("{} is not a {} of the ELG", id,
                             k == tape::ElgSectionKind::machine_data ? "machine datum" : "setting datum");
        auto problems = check_wire(*prof, *ref, value);
        if (problems.empty()) return std::nullopt;
        return fmt::format("{}", fmt::join(problems, "; "));
      });
}

std::expected<Ip247Check, std::string> load_ip247_check() {
  auto p = find_first({"ip247"});
  if (!p) return std::unexpected(p.error());
  std::shared_ptr<const pf::ParameterSetParser> parser = pf::make_parameter_set_parser(*p);
  if (!parser) return std::unexpected(std::string("ip247 profile has no S5 DB parser"));
  // The profile's own S5 DB parser reads the image word by word; validate() then applies every
  // field range and cross-field MD check with its MD error number.
  return Ip247Check([prof = *p, parser](const std::vector<std::uint16_t>& w) {
    std::string listing;
    for (std::size_t i = 0; i < w.size(); ++i) listing += fmt::format("{}: KH = {:04X}\n", i, w[i]);
    auto parsed = parser->parse(listing);
    std::vector<std::string> out;
    for (const auto& prob : parsed.problems) out.push_back(prob.describe());
    for (const auto& prob : pf::validate(*prof, parsed.set)) out.push_back(prob.describe());
    return out;
  });
}

std::expected<Wf725Check, std::string> load_wf725_check() {
  auto p = find_first({"wf725-726", "wf725"});
  if (!p) return std::unexpected(p.error());
  std::shared_ptr<const pf::ParameterSetParser> parser = pf::make_parameter_set_parser(*p);
  if (!parser) return std::unexpected(std::string("wf725-726 profile has no MD parser"));
  return Wf725Check([prof = *p, parser](const std::vector<std::uint16_t>& w) {
    std::vector<std::string> out;
    if (w.size() != 100) return std::vector<std::string>{"the MD image has 100 words (MD1..MD50, 2 words each)"};
    const pf::Settings settings;
    std::string text;
    for (int md = 1; md <= 50; ++md) {
      const std::uint16_t hi = w[static_cast<std::size_t>(2 * md - 2)];
      const std::uint16_t lo = w[static_cast<std::size_t>(2 * md - 1)];
      auto ref = prof->resolve(fmt::format("MD{}", md));
      const pf::Scope scope(*prof, nullptr, settings, ref ? ref->instance : std::nullopt,
                            ref ? ref->spec->instance_key : "");
      if (!ref || pf::select_variant(*ref, scope) == nullptr) {
        // An MD this module variant does not use must stay 0.
        if (hi != 0 || lo != 0)
          out.push_back(fmt::format("MD{} is not used by this module variant but holds {:04X} {:04X}", md, hi, lo));
        continue;
      }
      text += fmt::format("MD {} HEX {:04X} {:04X}\n", md, hi, lo);
    }
    auto parsed = parser->parse(text);
    for (const auto& prob : parsed.problems) out.push_back(prob.describe());
    for (const auto& prob : pf::validate(*prof, parsed.set)) out.push_back(prob.describe());
    return out;
  });
}

std::expected<std::vector<std::uint16_t>, std::string> load_wf725_default_image() {
  auto p = find_first({"wf725-726", "wf725"});
  if (!p) return std::unexpected(p.error());
  const pf::Settings settings;
  const auto defaults = pf::default_set(**p, settings);
  std::vector<std::uint16_t> words(100, 0);
  for (int md = 1; md <= 50; ++md) {
    auto ref = (*p)->resolve(fmt::format("MD{}", md));
    if (!ref) continue;
    const auto* e = defaults.find(ref->id());
    const pf::Scope scope(**p, &defaults, settings, ref->instance, ref->spec->instance_key);
    const auto* v = pf::select_variant(*ref, scope);
    if (e == nullptr || v == nullptr) continue;
    auto img = pf::encode_value(**p, *v, e->value);
    if (!img || !img->binary) continue;
    words[static_cast<std::size_t>(2 * md - 2)] = static_cast<std::uint16_t>(*img->binary >> 16);
    words[static_cast<std::size_t>(2 * md - 1)] = static_cast<std::uint16_t>(*img->binary & 0xFFFF);
  }
  return words;
}

}  // namespace hil::serial
