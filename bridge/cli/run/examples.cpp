// SPDX-License-Identifier: MIT
#include "examples.hpp"

#include "hil/core/data_dir.hpp"

#include <cstdlib>
#include <system_error>
#include <utility>

namespace hil::cli {

std::vector<std::filesystem::path> example_dirs() {
  std::vector<std::filesystem::path> dirs;
  if (const char* env = std::getenv("HILBRIDGE_EXAMPLES"); env && *env) dirs.emplace_back(env);
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto dir = exe.parent_path();
    dirs.push_back(dir.parent_path() / "examples");
    dirs.push_back(dir / "examples");
    dirs.push_back(dir.parent_path().parent_path() / "examples");
  }
  dirs.emplace_back("examples");
  // <exe>/../share/hilbridge/examples (installed tree), then the source tree's examples/ this
  // hilbridge was built from (out-of-tree build dirs such as /tmp/build are not next to it).
  for (auto& d : hil::data_dirs("examples")) dirs.push_back(std::move(d));
  return dirs;
}

std::optional<std::filesystem::path> find_example(const std::string& name) {
  for (const auto& d : example_dirs()) {
    std::error_code ec;
    const auto p = d / name;
    if (std::filesystem::is_regular_file(p, ec)) return p;
  }
  return std::nullopt;
}

}  // namespace hil::cli
