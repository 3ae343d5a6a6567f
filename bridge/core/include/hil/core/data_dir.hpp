// SPDX-License-Identifier: MIT
#pragma once
// Where hilbridge's shipped data lives: device profiles (profiles/devices), Modbus register
// profiles (profiles/modbus), EDS files (profiles/canopen) and the examples (examples).
//
// An installed tree keeps them under <prefix>/share/hilbridge/<relative>, where <prefix> is the
// parent of the running executable's folder (/usr/bin/hilbridge -> /usr), so a tree moved
// elsewhere (`mv /tmp/p /tmp/q`) still finds its own data. Binaries that run from the build tree
// (hilbridge, tests, benchmarks) fall back to the source tree the library was built from.

#include <filesystem>
#include <string_view>
#include <vector>

namespace hil {

/// Candidate folders for `relative` (a path under share/hilbridge, e.g. "profiles/modbus"), in
/// order: <exe prefix>/share/hilbridge/<relative>, then <source tree>/<relative>. Only existing
/// folders are returned. Thread-safe; reads /proc/self/exe and the file system.
[[nodiscard]] std::vector<std::filesystem::path> data_dirs(std::string_view relative);

/// The first of data_dirs(relative), or an empty path when none exists.
[[nodiscard]] std::filesystem::path find_data_dir(std::string_view relative);

/// <exe prefix>/share/hilbridge: the installed data root of the running executable (whether it
/// exists or not; empty when /proc/self/exe cannot be read).
[[nodiscard]] std::filesystem::path installed_data_root();

}  // namespace hil
