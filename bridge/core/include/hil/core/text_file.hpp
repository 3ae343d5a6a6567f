// SPDX-License-Identifier: MIT
#pragma once
// Reading a user's input file (scenario, profile, EDS, parameter set, program) whole: only a
// regular file of bounded size, so `/dev/zero`, a FIFO or a huge file is a clear error instead of
// an allocation failure, a hang or gigabytes of parse tree.
#include <cstddef>
#include <expected>
#include <filesystem>
#include <string>

namespace hil {

/// Input files are at most this long (4 MiB: far beyond any real scenario, profile or EDS).
inline constexpr std::size_t max_text_file_bytes = std::size_t{4} << 20;

/// The whole content of `path`, or what is wrong: "cannot open PATH: No such file or directory",
/// "PATH is not a regular file (a FIFO)", "PATH is 52428800 bytes; input files are limited to
/// 4194304 bytes (4 MiB)". Never blocks on a FIFO.
[[nodiscard]] std::expected<std::string, std::string> read_text_file(const std::filesystem::path& path,
                                                                     std::size_t max_bytes = max_text_file_bytes);

}  // namespace hil
