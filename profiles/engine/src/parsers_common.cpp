// SPDX-License-Identifier: MIT
#include "parsers.hpp"

namespace hil::profiles::detail {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<Line> split_lines(std::string_view text, bool strip_comments) {
  std::vector<Line> out;
  int n = 0;
  while (!text.empty() || n == 0) {
    ++n;
    const auto nl = text.find('\n');
    std::string_view l = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    if (strip_comments) {
      if (const auto c = l.find(';'); c != std::string_view::npos) l = l.substr(0, c);
      if (const auto c = l.find("//"); c != std::string_view::npos) l = l.substr(0, c);
    }
    if (!trim(l).empty()) out.push_back({n, l});
    if (nl == std::string_view::npos) break;
  }
  return out;
}

const ParamVariant& parse_variant(const Profile& p, const ParamRef& ref, const ParameterSet& so_far) {
  static const Settings none;
  const Scope scope(p, &so_far, none);
  if (const auto* v = select_variant(ref, scope)) return *v;
  return ref.spec->variants.front();
}

}  // namespace hil::profiles::detail
