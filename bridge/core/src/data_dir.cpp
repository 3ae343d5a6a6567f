// SPDX-License-Identifier: MIT
#include "hil/core/data_dir.hpp"

#include <string>
#include <system_error>

#ifndef HIL_SOURCE_DATA_ROOT
#define HIL_SOURCE_DATA_ROOT ""
#endif

namespace hil {

std::filesystem::path installed_data_root() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  return exe.parent_path().parent_path() / "share" / "hilbridge";
}

std::vector<std::filesystem::path> data_dirs(std::string_view relative) {
  std::vector<std::filesystem::path> dirs;
  const std::filesystem::path rel{std::string(relative)};
  auto add = [&](const std::filesystem::path& root) {
    if (root.empty()) return;
    std::error_code ec;
    const auto d = root / rel;
    if (std::filesystem::is_directory(d, ec)) dirs.push_back(d);
  };
  add(installed_data_root());
  add(std::filesystem::path(HIL_SOURCE_DATA_ROOT));
  return dirs;
}

std::filesystem::path find_data_dir(std::string_view relative) {
  auto dirs = data_dirs(relative);
  return dirs.empty() ? std::filesystem::path{} : dirs.front();
}

}  // namespace hil
