// SPDX-License-Identifier: MIT
#pragma once
// Internal: the per-device parameter-set parsers and helpers they share.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/validation.hpp"
#include "hil/profiles/wire.hpp"

namespace hil::profiles::detail {

std::unique_ptr<ParameterSetParser> make_clm_parser(std::shared_ptr<const Profile> p);
std::unique_ptr<ParameterSetParser> make_wf_parser(std::shared_ptr<const Profile> p);
std::unique_ptr<ParameterSetParser> make_s5db_parser(std::shared_ptr<const Profile> p);
std::unique_ptr<ParameterSetParser> make_sinumerik_parser(std::shared_ptr<const Profile> p);
std::unique_ptr<ParameterSetParser> make_amk_parser(std::shared_ptr<const Profile> p);

/// Lines with their 1-based numbers, CR stripped, comments (';', '//') removed, blank lines skipped.
struct Line {
  int number = 0;
  std::string_view text;
};
std::vector<Line> split_lines(std::string_view text, bool strip_comments = true);
std::string_view trim(std::string_view s);

/// Variant of `ref` for parsing (settings unknown at parse time: first applicable, else first).
const ParamVariant& parse_variant(const Profile& p, const ParamRef& ref, const ParameterSet& so_far);

}  // namespace hil::profiles::detail
