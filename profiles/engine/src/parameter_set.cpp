// SPDX-License-Identifier: MIT
#include "hil/profiles/parameter_set.hpp"

#include <fmt/format.h>

#include "parsers.hpp"

namespace hil::profiles {

std::string Problem::describe(std::string_view file) const {
  std::string s;
  if (!file.empty()) s += std::string(file) + ":";
  if (line > 0) s += fmt::format("{}:", line);
  if (!s.empty()) s += " ";
  if (!param.empty()) {
    s += param;
    if (!field.empty()) s += "." + field;
    if (!value.empty()) s += value.find('=') != std::string::npos ? " [" + value + "]" : " = " + value;
    s += ": ";
  }
  if (!rule.empty()) s += "rule " + rule + ": ";
  s += message;
  return s;
}

const SetEntry* ParameterSet::indexed(const std::string& key) const {
  const auto it = index_.find(key);
  if (it == index_.end() || it->second.pos >= entries.size()) return nullptr;
  const auto& e = entries[it->second.pos];
  // cheap identity check: the entry at that position still is the indexed parameter
  if (e.ref.spec != it->second.spec || e.ref.instance != it->second.instance) return nullptr;
  return &e;
}

const SetEntry* ParameterSet::find(std::string_view concrete_id) const {
  const auto key = normalise_id(concrete_id);
  if (const auto* e = indexed(key)) return e;
  if (index_.size() == entries.size() && !index_.count(key)) return nullptr;  // index complete: a miss is a miss
  for (const auto& e : entries)
    if (normalise_id(e.ref.id()) == key) return &e;
  return nullptr;
}

void ParameterSet::set(SetEntry e) {
  auto key = normalise_id(e.ref.id());
  if (const auto* old = indexed(key)) {
    entries[static_cast<std::size_t>(old - entries.data())] = std::move(e);
    return;
  }
  const bool complete = index_.size() == entries.size() && !index_.count(key);
  for (std::size_t i = 0; !complete && i < entries.size(); ++i)
    if (normalise_id(entries[i].ref.id()) == key) {
      index_[key] = Slot{i, e.ref.spec, e.ref.instance};
      entries[i] = std::move(e);
      return;
    }
  index_[std::move(key)] = Slot{entries.size(), e.ref.spec, e.ref.instance};
  entries.push_back(std::move(e));
}

std::uint8_t clm_checksum(std::string_view bytes) noexcept {
  unsigned s = 0;
  for (char c : bytes) s += static_cast<std::uint8_t>(c);
  const auto x = static_cast<std::uint8_t>((s >> 8) + (s & 0xFFu));
  return static_cast<std::uint8_t>(-x);
}

std::unique_ptr<ParameterSetParser> make_parameter_set_parser(std::shared_ptr<const Profile> profile) {
  if (!profile) return nullptr;
  const auto& f = profile->text_format;
  if (f == "clm-telegram") return detail::make_clm_parser(std::move(profile));
  if (f == "wf-md") return detail::make_wf_parser(std::move(profile));
  if (f == "s5-db") return detail::make_s5db_parser(std::move(profile));
  if (f == "sinumerik-md") return detail::make_sinumerik_parser(std::move(profile));
  if (f == "amk-db") return detail::make_amk_parser(std::move(profile));
  return nullptr;
}

}  // namespace hil::profiles
