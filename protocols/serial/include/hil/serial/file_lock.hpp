// SPDX-License-Identifier: MIT
#pragma once
// An exclusive advisory lock on a file, held for the life of the object: the emulators lock
// their state file so that two of them never overwrite each other's state.
#include <expected>
#include <filesystem>
#include <string>

namespace hil::serial {

class FileLock {
 public:
  /// Lock `path` through `path.lock` (flock, not inherited across exec; the lock file stays and
  /// names the holder's pid). Fails at once with "PATH is in use by another process (pid N): ..."
  /// while another holder has it.
  [[nodiscard]] static std::expected<FileLock, std::string> acquire(const std::filesystem::path& path);

  FileLock(FileLock&& other) noexcept;
  FileLock& operator=(FileLock&& other) noexcept;
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock();

 private:
  explicit FileLock(int fd) noexcept : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace hil::serial
