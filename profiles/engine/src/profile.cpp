// SPDX-License-Identifier: MIT
#include "hil/profiles/profile.hpp"

#include <fmt/format.h>

#include <cctype>

namespace hil::profiles {

std::string_view to_string(TakesEffect t) noexcept {
  switch (t) {
    case TakesEffect::immediately:
      return "immediately";
    case TakesEffect::leaving_parameter_mode:
      return "leaving_parameter_mode";
    case TakesEffect::after_reset:
      return "after_reset";
    case TakesEffect::after_power_cycle:
      return "after_power_cycle";
  }
  return "?";
}

std::string_view to_string(Protection p) noexcept {
  switch (p) {
    case Protection::none:
      return "none";
    case Protection::machine_builder:
      return "machine_builder";
    case Protection::read_only:
      return "read_only";
    case Protection::system:
      return "system";
  }
  return "?";
}

std::optional<Encoding> parse_encoding(std::string_view s) noexcept {
  if (s == "text") return Encoding::text;
  if (s == "bcd_binary") return Encoding::bcd_binary;
  if (s == "KF") return Encoding::kf;
  if (s == "KH") return Encoding::kh;
  if (s == "KY") return Encoding::ky;
  if (s == "KD" || s == "DD") return Encoding::kd;
  if (s == "DL") return Encoding::byte_l;
  if (s == "DR") return Encoding::byte_r;
  if (s == "fixed") return Encoding::fixed;
  return std::nullopt;
}

std::string_view to_string(Encoding e) noexcept {
  switch (e) {
    case Encoding::text:
      return "text";
    case Encoding::bcd_binary:
      return "bcd_binary";
    case Encoding::kf:
      return "KF";
    case Encoding::kh:
      return "KH";
    case Encoding::ky:
      return "KY";
    case Encoding::kd:
      return "KD";
    case Encoding::byte_l:
      return "DL";
    case Encoding::byte_r:
      return "DR";
    case Encoding::fixed:
      return "fixed";
  }
  return "?";
}

std::string Bound::text() const {
  if (literal) return literal->to_string();
  return expr.text();
}

std::string normalise_id(std::string_view id) {
  std::string s;
  for (char c : id)
    if (c != ' ' && c != '\t' && c != '_') s += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string ParamSpec::concrete_id(std::optional<std::int64_t> instance) const {
  if (pattern.empty() || !instance) return id;
  std::string out = pattern;
  const std::string key = "{" + instance_key + "}";
  if (const auto p = out.find(key); p != std::string::npos) out.replace(p, key.size(), std::to_string(*instance));
  return out;
}

void Profile::index() {
  index_.clear();
  templates_.clear();
  for (const auto& p : parameters) {
    if (p.instances.empty()) continue;
    templates_.emplace(normalise_id(p.id), &p);
    std::string bare = p.pattern;
    if (const auto at = bare.find('{'); at != std::string::npos) bare.erase(at, bare.find('}', at) - at + 1);
    if (!bare.empty()) templates_.emplace(normalise_id(bare), &p);
  }
  for (const auto& p : parameters) {
    if (p.instances.empty()) {
      index_.emplace(normalise_id(p.id), ParamRef{&p, std::nullopt});
      for (const auto& a : p.aliases) index_.emplace(normalise_id(a), ParamRef{&p, std::nullopt});
    } else {
      for (auto i : p.instances) index_.emplace(normalise_id(p.concrete_id(i)), ParamRef{&p, i});
    }
  }
}

std::optional<ParamRef> Profile::resolve(std::string_view id) const {
  const auto it = index_.find(normalise_id(id));
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

const ParamSpec* Profile::resolve_template(std::string_view id) const {
  const auto it = templates_.find(normalise_id(id));
  return it == templates_.end() ? nullptr : it->second;
}

std::vector<ParamRef> Profile::all_refs() const {
  std::vector<ParamRef> out;
  for (const auto& p : parameters) {
    if (p.instances.empty())
      out.push_back({&p, std::nullopt});
    else
      for (auto i : p.instances) out.push_back({&p, i});
  }
  return out;
}

const ErrorCatalogue* Profile::catalogue(std::string_view id) const {
  for (const auto& c : catalogues)
    if (c->id() == id) return c.get();
  return nullptr;
}

const SettingSpec* Profile::setting(std::string_view name) const {
  for (const auto& s : settings)
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace hil::profiles
