// SPDX-License-Identifier: MIT
#include "hil/controllers/parameter_file.hpp"

#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "hil/profiles/loader.hpp"
#include "hil/profiles/validation.hpp"

namespace hil::controllers {
namespace {

ConfigError from_problems(const std::vector<profiles::Problem>& problems, std::string_view name) {
  ConfigError e;
  e.file = std::string(name);
  e.line = problems.front().line;
  const auto& p = problems.front();
  e.key = p.field.empty() ? p.param : p.param + "." + p.field;
  std::string msg;
  if (!p.value.empty()) msg += fmt::format("value {}: ", p.value);
  if (!p.rule.empty()) msg += fmt::format("rule {}: ", p.rule);
  msg += p.message;
  for (std::size_t i = 1; i < problems.size() && i < 20; ++i) msg += "\n  " + problems[i].describe(name);
  if (problems.size() > 20) msg += fmt::format("\n  ... and {} more", problems.size() - 20);
  e.message = std::move(msg);
  return e;
}

}  // namespace

std::expected<LoadedParameters, ConfigError> load_parameter_text(std::string_view device, std::string_view text,
                                                                 std::string_view name,
                                                                 const profiles::Settings& settings) {
  auto profile = profiles::find_profile(device);
  if (!profile) return std::unexpected(profile.error());
  auto parser = profiles::make_parameter_set_parser(*profile);
  if (!parser) {
    return std::unexpected(ConfigError{
        std::string(name), 0, 0, "",
        fmt::format("device '{}' has no parameter-file parser (text_format '{}')", device, (*profile)->text_format)});
  }
  auto parsed = parser->parse(text, settings);
  if (!parsed.problems.empty()) return std::unexpected(from_problems(parsed.problems, name));
  const auto problems = profiles::validate(**profile, parsed.set, settings);
  if (!problems.empty()) return std::unexpected(from_problems(problems, name));
  return LoadedParameters{*profile, std::move(parsed.set), std::filesystem::path(name)};
}

std::expected<LoadedParameters, ConfigError> load_parameter_file(std::string_view device,
                                                                 const std::filesystem::path& file,
                                                                 const profiles::Settings& settings) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    return std::unexpected(
        ConfigError{file.string(), 0, 0, "", fmt::format("cannot read the {} parameter file: check the path", device)});
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  auto r = load_parameter_text(device, ss.str(), file.string(), settings);
  if (r) r->file = file;
  return r;
}

}  // namespace hil::controllers
